// surrogate info on a carrier: carrier::describeCarrier's summary, and the processing choices
// a run without options repeats (run::standingDecisions), as text or JSON.
#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "carrier/summary.h"
#include "cli/commands.h"
#include "cli/info_print.h"
#include "core/error.h"
#include "core/text.h"
#include "image/raw_settings.h"
#include "run/plan.h"
#include "stages/web_copy_stage.h"

namespace surrogate::cli {

namespace {

// The lights the carrier records last (the light estimation's result): each image's path, its
// direction's elevation and azimuth, and its uncertainty (light/@uncertaintyDegrees: the 95 %
// bound in degrees on its angle from the true direction; absent for lights from an .lp file).
struct RecordedLight {
  std::string image;
  double elevationDeg = 0, azimuthDeg = 0;
  std::optional<double> uncertaintyDeg;
  // Where the light was (nearLight, LightDirections version 7): distance in frame widths and
  // how it was placed (spheres, stated-distance); absent for a light at infinity.
  std::optional<double> distance;
  std::string placedBy;
};
std::vector<RecordedLight> recordedLights(const carrier::Carrier& c) {
  const carrier::Result* result = c.lastResultWith("light");
  std::vector<RecordedLight> out;
  if (!result) return out;
  for (const carrier::DataItem* l : result->itemsOf("light")) {
    RecordedLight rl;
    const carrier::FileRecord* f = c.findFile(l->get("image").value_or(""));
    rl.image = f ? f->path : l->get("image").value_or("");
    try {
      rl.elevationDeg = l->number("elevationDeg");
      rl.azimuthDeg = l->number("azimuthDeg");
      if (l->get("uncertaintyDegrees")) rl.uncertaintyDeg = l->number("uncertaintyDegrees");
      for (const carrier::DataItem* p : result->itemsOf("nearLight"))
        if (p->get("image") == l->get("image")) {
          rl.distance = p->number("distance");
          rl.placedBy = p->get("source").value_or("");
        }
    } catch (const Error&) {
      continue;  // a light that is not numbers is not shown
    }
    out.push_back(rl);
  }
  return out;
}

// "  lights: 12, each within 0.8-1.6 deg (median 1.1) of the true direction (95 %); the widest
// jpeg-exports/IMG_0004.jpg", or without uncertainties "  lights: 12 (from an .lp file, no uncertainty)".
void printLights(const carrier::Carrier& c) {
  const std::vector<RecordedLight> lights = recordedLights(c);
  if (lights.empty()) return;
  std::vector<double> bounds;
  const RecordedLight* widest = nullptr;
  for (const RecordedLight& l : lights)
    if (l.uncertaintyDeg) {
      bounds.push_back(*l.uncertaintyDeg);
      if (!widest || *l.uncertaintyDeg > *widest->uncertaintyDeg) widest = &l;
    }
  std::cout << "  lights: " << lights.size();
  if (bounds.empty()) {
    std::cout << " (no uncertainty recorded: given by an .lp file)\n";
    return;
  }
  std::sort(bounds.begin(), bounds.end());
  const double median = bounds.size() % 2 ? bounds[bounds.size() / 2]
                                          : (bounds[bounds.size() / 2 - 1] + bounds[bounds.size() / 2]) / 2;
  const std::string lowest = fixedDecimals(bounds.front(), 1), highest = fixedDecimals(bounds.back(), 1);
  if (lowest == highest) {  // "within 1.2-1.2 deg (median 1.2)" says one figure three times
    std::cout << ", each within " << lowest << " deg of the true direction (95 %)\n";
    return;
  }
  std::cout << ", each within " << lowest << "-" << highest << " deg (median " << fixedDecimals(median, 1)
            << ") of the true direction (95 %); the widest " << widest->image << "\n";
}


using carrier::shownValue;

// The processing choices a carrier records besides the human interventions: what a run without
// options repeats (run::standingDecisions), and the web copy with its recorded options.
struct Choices {
  run::RunRequest standing;
  const carrier::Step* webCopy = nullptr;  // the first WebCopy step: every model's has the same options
  std::vector<std::string> webModels;
};

Choices choicesOf(const carrier::Carrier& c) {
  Choices out;
  out.standing = run::standingDecisions(c);
  // The decoding step records every LibRaw setting; the choices are those that differ from
  // the defaults.
  const auto defaults = image::RawDecodeSettings{}.toParameters();
  auto& decode = out.standing.decodeSettings;
  decode.erase(std::remove_if(decode.begin(), decode.end(),
                              [&](const auto& kv) { return std::find(defaults.begin(), defaults.end(), kv) != defaults.end(); }),
               decode.end());
  // The web copy's options are shown with it.
  auto& params = out.standing.stageParams;
  params.erase(std::remove_if(params.begin(), params.end(),
                              [](const auto& p) { return p.component == stages::WebCopyStage::kComponent; }),
               params.end());
  for (const carrier::Step& s : c.process) {
    if (s.component != stages::WebCopyStage::kComponent) continue;
    if (!out.webCopy) out.webCopy = &s;
    out.webModels.push_back(s.param("model"));
  }
  return out;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& i : items) out += (out.empty() ? "" : ", ") + i;
  return out;
}

std::string paramsText(const std::vector<std::pair<std::string, std::string>>& params) {
  std::string out;
  for (const auto& [name, value] : params) out += (out.empty() ? "" : ", ") + name + " " + shownValue(value);
  return out;
}

// A carrier whose steps this version cannot read (another version's, or a forged one) still
// gets described: its choices are then left out, saying why, and `verify` judges it.
std::optional<Choices> readableChoices(const carrier::Carrier& c, std::string* why) {
  try {
    return choicesOf(c);
  } catch (const Error& e) {
    if (why) *why = e.message();
    return std::nullopt;
  }
}

void choicesJson(JsonWriter& j, const carrier::Carrier& c) {
  const std::optional<Choices> readable = readableChoices(c, nullptr);
  if (!readable) {
    j.key("choices").null();
    return;
  }
  const Choices& ch = *readable;
  const run::RunRequest& r = ch.standing;
  j.key("choices").beginObject().key("source").value(r.source.empty() ? "auto" : r.source).key("bases").beginArray();
  for (const std::string& b : r.bases.value_or(std::vector<std::string>{})) j.value(b);
  j.endArray().key("decode").beginArray();
  for (const auto& [name, value] : r.decodeSettings)
    j.beginObject().key("name").value(name).key("value").value(value).endObject();
  j.endArray().key("preprocessing").beginArray();
  for (const run::PlannedStage& p : r.preprocessing) {
    j.beginObject().key("component").value(p.component).key("parameters").beginArray();
    for (const auto& [name, value] : p.params)
      j.beginObject().key("name").value(name).key("value").value(value).endObject();
    j.endArray().endObject();
  }
  j.endArray().key("options").beginArray();
  for (const run::RunRequest::StageParam& p : r.stageParams)
    j.beginObject().key("component").value(p.component).key("name").value(p.name).key("value").value(p.value).endObject();
  j.endArray().key("webCopy");
  if (!ch.webCopy) {
    j.null();
  } else {
    j.beginObject().key("models").beginArray();
    for (const std::string& m : ch.webModels) j.value(m);
    j.endArray().key("parameters").beginArray();
    for (const carrier::Param& p : ch.webCopy->params)
      if (p.name != "model") j.beginObject().key("name").value(p.name).key("value").value(p.value).endObject();
    j.endArray().endObject();
  }
  j.endObject();
}

// The processing choices, as text: what a run without options repeats.
void printChoices(const carrier::Carrier& c) {
  std::string why;
  const std::optional<Choices> readable = readableChoices(c, &why);
  if (!readable) {
    std::cout << "  processing choices: not readable by this version of Surrogate (" << why << ")\n";
    return;
  }
  const Choices& ch = *readable;
  const run::RunRequest& r = ch.standing;
  std::cout << "  processing choices (a run without options repeats them):\n"
            << "    image source: " << (r.source.empty() ? "auto" : r.source) << "\n";
  if (r.bases) std::cout << "    models: " << joined(*r.bases) << "\n";
  for (const auto& [name, value] : r.decodeSettings) std::cout << "    LibRaw " << name << " = " << value << "\n";
  for (const run::PlannedStage& p : r.preprocessing)
    std::cout << "    pre-processing " << p.component << ": " << paramsText(p.params) << "\n";
  for (const run::RunRequest::StageParam& p : r.stageParams)
    std::cout << "    " << p.component << " " << p.name << " = " << shownValue(p.value) << "\n";
  if (!ch.webCopy) {
    std::cout << "    web copy: none (run --publish makes one of each model)\n";
    return;
  }
  std::vector<std::pair<std::string, std::string>> options;
  for (const carrier::Param& p : ch.webCopy->params)
    if (p.name != "model") options.emplace_back(p.name, p.value);
  std::cout << "    web copy of " << joined(ch.webModels) << " in finished-files/web/ (" << paramsText(options)
            << "); run --no-publish withdraws it\n";
}

// The standing decisions (human interventions: what, in which step, who, when and why), the
// excluded images and the run history, as text.
void printDecisionsAndRuns(const carrier::Carrier& c, const carrier::CarrierSummary& s) {
  std::cout << "  standing decisions:";
  for (const carrier::DecisionSummary& d : s.decisions) {
    const carrier::Intervention& i = d.intervention;
    std::cout << "\n    " << i.kind << " " << i.target << " (" << d.step << " " << d.component << "): " << d.what
              << "\n      by " << i.who << ", " << i.time << ": " << i.reason;
  }
  for (const std::string& lp : s.domeLights) std::cout << "\n    lights from " << lp << " (dome capture)";
  std::cout << (s.decisions.empty() && s.domeLights.empty() ? " none\n" : "\n");
  std::string excluded;
  for (const carrier::DecisionSummary& d : s.exclusions) excluded += (excluded.empty() ? "" : ", ") + d.intervention.target;
  std::cout << "  excluded images: " << (excluded.empty() ? "none" : excluded) << "\n";
  // Decisions given on a failed last run stand (carrier::standingProcess) though the results
  // are still those of the run before: said, so that the two are not taken for one another.
  if (&carrier::standingProcess(c) != &c.process)
    std::cout << "  (the decisions above include those of " << c.header.runs.back().id
              << ", which failed: the next run starts from them; the steps and results are the run before's)\n";
  printChoices(c);
  if (s.runs.empty()) return;
  std::cout << "  runs:\n";
  for (const carrier::RunRecord& r : s.runs) {
    std::string args;
    for (const std::string& a : r.arguments) args += " " + (a.find(' ') != std::string::npos || a.empty() ? "\"" + a + "\"" : a);
    std::cout << "    " << r.id << " " << r.started << " " << r.who << ": surrogate " << r.command
              << args << " -> " << r.outcome << "\n";
    for (const std::string& note : r.notes) std::cout << "      " << note << "\n";
  }
}

}  // namespace

void carrierJson(JsonWriter& j, const carrier::Carrier& c) {
  const carrier::CarrierSummary s = carrier::describeCarrier(c);
  j.beginObject().key("kind").value("carrier").key("title").value(s.title)
      .key("created").value(s.created).key("modified").value(s.modified)
      .key("rights").value(s.rights).key("license").value(s.license)
      .key("metadata").beginArray();
  for (const auto& [name, value] : s.metadata)
    j.beginObject().key("name").value(name).key("value").value(value).endObject();
  j.endArray().key("files").value(static_cast<int>(s.files))
      .key("images").value(static_cast<int>(s.images)).key("steps").beginArray();
  for (const carrier::StepSummary& step : s.steps)
    j.beginObject().key("id").value(step.id).key("component").value(step.component)
        .key("version").value(step.version).key("status").value(step.status)
        .key("seconds").value(step.seconds)
        .key("interventions").value(static_cast<int>(step.interventions)).endObject();
  j.endArray();
  choicesJson(j, c);
  j.key("creators").beginArray();
  for (const carrier::Creator& cr : s.creators)
    j.beginObject().key("name").value(cr.name).key("role").value(cr.role).endObject();
  j.endArray().key("decisions").beginArray();
  for (const carrier::DecisionSummary& d : s.decisions) {
    const carrier::Intervention& i = d.intervention;
    j.beginObject().key("step").value(d.step).key("component").value(d.component)
        .key("kind").value(i.kind).key("target").value(i.target).key("value").value(i.value)
        .key("what").value(d.what)
        .key("who").value(i.who).key("time").value(i.time).key("reason").value(i.reason).endObject();
  }
  j.endArray().key("exclusions").beginArray();
  for (const carrier::DecisionSummary& d : s.exclusions) {
    const carrier::Intervention& i = d.intervention;
    j.beginObject().key("image").value(i.target).key("who").value(i.who).key("time").value(i.time)
        .key("reason").value(i.reason).endObject();
  }
  j.endArray().key("runs").beginArray();
  for (const carrier::RunRecord& r : s.runs) {
    j.beginObject().key("id").value(r.id).key("command").value(r.command).key("who").value(r.who)
        .key("started").value(r.started).key("ended").value(r.ended).key("outcome").value(r.outcome)
        .key("arguments").beginArray();
    for (const std::string& a : r.arguments) j.value(a);
    j.endArray().key("notes").beginArray();
    for (const std::string& n : r.notes) j.value(n);
    j.endArray().endObject();
  }
  j.endArray().key("lights").beginArray();
  for (const RecordedLight& l : recordedLights(c)) {
    j.beginObject().key("image").value(l.image).key("elevationDeg").value(l.elevationDeg)
        .key("azimuthDeg").value(l.azimuthDeg).key("uncertaintyDegrees");
    if (l.uncertaintyDeg) j.value(*l.uncertaintyDeg);
    else j.null();
    j.key("distance");  // frame widths from the frame's centre; null: at infinity
    if (l.distance) j.value(*l.distance);
    else j.null();
    j.key("placedBy");
    if (l.distance) j.value(l.placedBy);
    else j.null();
    j.endObject();
  }
  j.endArray();
  colourJson(j, c);
  j.key("warnings").beginArray();
  for (const carrier::WarningSummary& w : s.warnings)
    j.beginObject().key("step").value(w.step).key("component").value(w.component).key("time").value(w.time)
        .key("text").value(w.text).endObject();
  j.endArray().endObject();
}

void printCarrierText(const carrier::Carrier& c) {
  const carrier::CarrierSummary s = carrier::describeCarrier(c);
  std::cout << "  title:   " << s.title << "\n"
            << "  created: " << s.created << " on " << s.hostname << "\n";
  for (const carrier::Creator& cr : s.creators) std::cout << "  " << cr.role << ": " << cr.name << "\n";
  if (!s.rights.empty()) std::cout << "  rights:  " << s.rights << "\n";
  if (!s.license.empty()) std::cout << "  licence: " << s.license << "\n";
  for (const auto& [name, value] : s.metadata) std::cout << "  metadata: " << name << " = " << value << "\n";
  std::cout << "  files:   " << s.files << " (" << s.images << " images)\n  steps:\n";
  for (const carrier::StepSummary& step : s.steps) {
    std::cout << "    " << step.id << " " << step.component << " v" << step.version << ": " << step.status;
    if (step.status == "completed") std::cout << " in " << fixedDecimals(step.seconds, 1) << " s";
    if (step.interventions)
      std::cout << ", " << step.interventions << (step.interventions == 1 ? " decision" : " decisions") << " (below)";
    std::cout << "\n";
  }
  printLights(c);
  printColour(c);
  printDecisionsAndRuns(c, s);
  if (s.warnings.empty()) std::cout << "  warnings: none\n";
  else printWarnings(s, 0, "");
}

void printCarrier(const std::filesystem::path& path, bool json) {
  const carrier::Carrier c = carrier::loadCarrier(path);
  if (json) {
    JsonWriter j;
    carrierJson(j, c);
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": Surrogate carrier\n";
  printCarrierText(c);
}

}  // namespace surrogate::cli
