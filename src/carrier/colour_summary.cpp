#include "carrier/colour_summary.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"

namespace surrogate::carrier {

namespace {

// The component's name (stages::ColourChartStage::kComponent): the carrier library does not
// link the stages.
constexpr const char* kColourComponent = "ColourCorrection";

// "37.54 14.37 14.92" -> the three numbers; nullopt for anything else.
std::optional<LabValues> labValues(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  std::istringstream in(*text);
  in.imbue(std::locale::classic());
  LabValues v{};
  if (!(in >> v[0] >> v[1] >> v[2])) return std::nullopt;
  std::string rest;
  if (in >> rest) return std::nullopt;
  return v;
}

std::optional<double> numberOf(const DataItem& d, const char* name) {
  if (!d.get(name)) return std::nullopt;
  try {
    return d.number(name);
  } catch (const Error&) {
    return std::nullopt;
  }
}

void readValue(ColourSummary& s, const std::string& name, const DataItem& v) {
  const std::string text = v.get("value").value_or("");
  const std::optional<double> number = numberOf(v, "value");
  if (name == "chart") s.chart = text;
  else if (name == "outcome") s.outcome = text;
  else if (name == "method") s.method = text;
  else if (name == "framesMeasured" && number) s.framesMeasured = static_cast<int>(*number);
  else if (name == "reference") s.reference = text;
  else if (name == "referenceTitle") s.referenceTitle = text;
  else if (name == "referenceSource") s.referenceSource = text;
  else if (name == "model") s.model = text;
  else if (name == "deltaE2000MeanBefore") s.meanBefore = number;
  else if (name == "deltaE2000MaxBefore") s.maxBefore = number;
  else if (name == "deltaE2000Mean") s.meanAfter = number;
  else if (name == "deltaE2000Max") s.maxAfter = number;
  else if (name == "deltaE2000MeanHeldOut") s.meanHeldOut = number;
  else if (name == "deltaE2000MaxHeldOut") s.maxHeldOut = number;
  else if (name == "qualityLevel") s.qualityLevels.push_back(text);
}

}  // namespace

std::optional<ColourSummary> describeColour(const Carrier& c) {
  const Result* result = nullptr;
  for (const Step& step : c.process)
    if (step.component == kColourComponent)
      if (const Result* r = c.findResult(step.id)) result = r;
  if (!result) return std::nullopt;
  ColourSummary s;
  s.step = result->step;
  for (const DataItem* v : result->itemsOf("value")) readValue(s, v->get("name").value_or(""), *v);
  for (const DataItem* in : result->itemsOf("input")) {
    const std::string kind = in->get("kind").value_or("");
    if (kind != "chart" && kind != "chart-search") continue;
    const std::string id = in->get("file").value_or("");
    const FileRecord* f = c.findFile(id);
    s.image = f ? f->path : id;
  }
  for (const DataItem* p : result->itemsOf("chartPatch")) {
    ColourPatch patch;
    const std::optional<double> index = numberOf(*p, "index");
    if (!index) continue;  // a patch without its place on the chart cannot be shown in it
    patch.index = static_cast<int>(*index);
    patch.name = p->get("name").value_or("");
    patch.reference = labValues(p->get("reference"));
    patch.before = labValues(p->get("before"));
    patch.corrected = labValues(p->get("corrected"));
    patch.deltaE2000Before = numberOf(*p, "deltaE2000Before");
    patch.deltaE2000 = numberOf(*p, "deltaE2000");
    patch.deltaE2000HeldOut = numberOf(*p, "deltaE2000HeldOut");
    patch.frames = static_cast<int>(numberOf(*p, "frames").value_or(0));
    s.patches.push_back(patch);
  }
  // The step records the patches it measured first, then those it could not.
  std::stable_sort(s.patches.begin(), s.patches.end(),
                   [](const ColourPatch& a, const ColourPatch& b) { return a.index < b.index; });
  s.corrected = s.outcome == "corrected";
  if (s.outcome.empty()) {
    if (result->status == "failed") s.outcome = "the colour step failed (see the log): the images keep their colours";
    else if (s.chart == "none") s.outcome = "no colour chart (chart=none): the images keep their colours";
  }
  return s;
}

}  // namespace surrogate::carrier
