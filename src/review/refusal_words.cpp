#include "review/refusal_words.h"

#include "core/text.h"
#include "hrti/highlight_refusal.h"

namespace surrogate::review {

namespace {

using Refusal = hrti::HighlightRefusal;

// "IMG_0001; IMG_0002; and 3 more": the frames named, as the page's thumbnails name them.
std::string framesNamed(const std::vector<std::string>& frames) {
  constexpr std::size_t kMost = 8;
  std::string out;
  for (std::size_t i = 0; i < frames.size() && i < kMost; ++i) out += (i ? "; " : "") + frames[i];
  if (frames.size() > kMost) out += "; and " + std::to_string(frames.size() - kMost) + " more";
  return out;
}

// What to do with a frame whose highlight is missing, in the page's buttons.
std::string framesAdvice(bool one) {
  return std::string(one ? "" : "for each, ") +
         "click it among the frames, then leave it out (tick \u201cLeave this frame out\u201d and say why) or place "
         "its highlight by hand (\u201cPlace this frame\u2019s highlight\u201d, then click the centre of the highlight).";
}

std::string words(const Refusal& r) {
  const std::string sphere = "sphere " + std::to_string(r.sphere + 1);
  const std::string counted = "shows no trustworthy highlight in " + std::to_string(r.frames.size()) + " of " +
                              std::to_string(r.images) + " frames (" + framesNamed(r.frames) + ")";
  switch (r.subject) {
    case Refusal::Subject::CircleByHand:
      return "The circle placed by hand for " + sphere + " " + counted +
             ", so it is probably not where the sphere is. Drag the circle onto " + sphere +
             " and resize it with its orange square (\u201cMove or resize a sphere\u201d), then apply again; or "
             "withdraw it (\u201cWithdraw\u2026\u201d beside it under Standing decisions) to let Surrogate find the "
             "sphere. If the circle is right, those frames show no highlight: " + framesAdvice(false);
    case Refusal::Subject::CircleFound:
      return "The circle Surrogate found for " + sphere + " " + counted +
             ", so it is probably not a sphere. Drag the circle onto the sphere and resize it with its orange "
             "square (\u201cMove or resize a sphere\u201d), then apply again. If the circle is right, those frames "
             "show no highlight: " + framesAdvice(false);
    case Refusal::Subject::Frames: {
      const bool one = r.frames.size() == 1;
      return (one ? r.frames.front() + " shows" : framesNamed(r.frames) + " show") +
             " no trustworthy highlight on any sphere, so " + (one ? "its" : "their") +
             " light direction cannot be measured: " + framesAdvice(one);
    }
  }
  return r.text();
}

}  // namespace

std::string pageWords(const Error& e) {
  if (const auto* refusal = dynamic_cast<const Refusal*>(&e)) return words(*refusal);
  return e.text();
}

}  // namespace surrogate::review
