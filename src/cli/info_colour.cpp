// surrogate info on a carrier: what its colour step recorded (carrier/colour_summary.h), as
// one or two lines of text or the "colour" object of the JSON:
//
//   colour: corrected with ColorChecker Classic (from November 2014), found in IMG_0003.jpg,
//           24 frames; matrix: CIEDE2000 mean 6.10 -> 0.90, max 12.31 -> 2.05 (held out 1.20, 3.10)
//           FADGI 2023: 4 star; Metamorfoze 2019: Full
#include <iostream>
#include <optional>
#include <string>

#include "carrier/colour_summary.h"
#include "cli/info_print.h"
#include "core/text.h"

namespace surrogate::cli {

namespace {

std::string figure(const std::optional<double>& v) { return v ? fixedDecimals(*v, 2) : std::string("-"); }

void numberOrNull(JsonWriter& j, const char* key, const std::optional<double>& v) {
  j.key(key);
  if (v) j.value(*v);
  else j.null();
}

void labOrNull(JsonWriter& j, const char* key, const std::optional<carrier::LabValues>& lab) {
  j.key(key);
  if (!lab) {
    j.null();
    return;
  }
  j.beginArray().value((*lab)[0]).value((*lab)[1]).value((*lab)[2]).endArray();
}

}  // namespace

void printColour(const carrier::Carrier& c) {
  const std::optional<carrier::ColourSummary> k = carrier::describeColour(c);
  if (!k) return;
  if (!k->corrected) {
    std::cout << "  colour:  " << (k->outcome.empty() ? "no colour correction recorded" : k->outcome) << "\n";
    return;
  }
  std::cout << "  colour:  corrected with " << (k->referenceTitle.empty() ? k->reference : k->referenceTitle) << ", "
            << (k->method == "given" ? "given by hand" : "found") << " in " << k->image;
  if (k->framesMeasured) std::cout << ", " << *k->framesMeasured << (*k->framesMeasured == 1 ? " frame" : " frames");
  std::cout << "; " << k->model << ": CIEDE2000 mean " << figure(k->meanBefore) << " -> " << figure(k->meanAfter)
            << ", max " << figure(k->maxBefore) << " -> " << figure(k->maxAfter) << " (held out: mean "
            << figure(k->meanHeldOut) << ", max " << figure(k->maxHeldOut) << ")\n";
  std::string levels;
  for (const std::string& l : k->qualityLevels) levels += (levels.empty() ? "" : "; ") + l;
  if (!levels.empty()) std::cout << "           " << levels << "\n";
}

void colourJson(JsonWriter& j, const carrier::Carrier& c) {
  const std::optional<carrier::ColourSummary> k = carrier::describeColour(c);
  if (!k) return;
  j.key("colour").beginObject().key("step").value(k->step).key("chart").value(k->chart)
      .key("corrected").value(k->corrected).key("outcome").value(k->outcome).key("image");
  if (k->image.empty()) j.null();
  else j.value(k->image);
  if (!k->corrected) {  // nothing else is recorded
    j.endObject();
    return;
  }
  j.key("method").value(k->method).key("reference").value(k->reference).key("referenceTitle").value(k->referenceTitle)
      .key("model").value(k->model).key("framesMeasured");
  if (k->framesMeasured) j.value(*k->framesMeasured);
  else j.null();
  j.key("deltaE2000").beginObject();
  numberOrNull(j, "meanBefore", k->meanBefore);
  numberOrNull(j, "maxBefore", k->maxBefore);
  numberOrNull(j, "mean", k->meanAfter);
  numberOrNull(j, "max", k->maxAfter);
  numberOrNull(j, "meanHeldOut", k->meanHeldOut);
  numberOrNull(j, "maxHeldOut", k->maxHeldOut);
  j.endObject().key("qualityLevels").beginArray();
  for (const std::string& l : k->qualityLevels) j.value(l);
  j.endArray().key("patches").beginArray();
  // index counts from 0 in chart order (dark skin .. black), as the carrier does; a patch not
  // measured (frames 0) has null colours and figures.
  for (const carrier::ColourPatch& p : k->patches) {
    j.beginObject().key("index").value(p.index).key("name").value(p.name).key("frames").value(p.frames);
    labOrNull(j, "reference", p.reference);
    labOrNull(j, "before", p.before);
    labOrNull(j, "corrected", p.corrected);
    numberOrNull(j, "deltaE2000Before", p.deltaE2000Before);
    numberOrNull(j, "deltaE2000", p.deltaE2000);
    numberOrNull(j, "deltaE2000HeldOut", p.deltaE2000HeldOut);
    j.endObject();
  }
  j.endArray().endObject();
}

}  // namespace surrogate::cli
