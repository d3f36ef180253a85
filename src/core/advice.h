// A warning a person can act on: what happened, whether the result can be used, and what to
// do, in plain words, with the figure that shows it kept as detail. Every warning of the
// carrier's log is written through it, so `run`, `info`, the report and the review page all
// answer the two questions a conservator asks of a warning: can I use this, and what now?
//
//   carrier::addWarning(carrier, step.id,  // carrier/advice.h
//       {"IMG_0003: two bright spots on the sphere; the one nearest its centre was taken",
//        Usable::WithCare, "that photograph's light may point the wrong way",
//        "look at it on the highlight overview (assembly-files/highlights-sphere1.png)",
//        "confidence 0.42"});
//   // "IMG_0003: two bright spots ... taken. Usable with care: that photograph's light may
//   //  point the wrong way. What to do: look at it on ... (confidence 0.42)"
#pragma once

#include <string>

namespace surrogate {

enum class Usable {
  Yes,       // the result is as good as usual for what it is used for
  WithCare,  // usable, but part of it (named in `why`) is less trustworthy
  No         // the named part of the result should not be relied on
};

struct Advice {
  std::string what;    // what happened, without jargon: a sentence, no final full stop
  Usable usable = Usable::WithCare;
  std::string why;     // why the result can (or cannot) be used as it is
  std::string todo;    // what to do about it: an action, or "nothing" with the reason
  std::string detail;  // the figure behind it (counts, percentages, thresholds); may be empty
};

// The words that open the usability sentence: "Usable", "Usable with care", "Not usable".
const char* usableWords(Usable usable);

// "WHAT. USABLE: WHY. What to do: TODO. (DETAIL)", each part's own final full stop not doubled.
std::string adviceText(const Advice& advice);

}  // namespace surrogate
