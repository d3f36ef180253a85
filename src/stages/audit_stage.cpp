#include "stages/audit_stage.h"

#include "carrier/advice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

#include "audit/audit.h"
#include "audit/rtibuilder_log.h"
#include "capture/capture.h"
#include "core/error.h"
#include "core/text.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/lights_from_file_stage.h"
#include "stages/outputs.h"
#include "stages/prior_work.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {
constexpr const char* kThresholdParameter = "angleThresholdDegrees";
constexpr const char* kMarginParameter = "reproducedMarginDb";
constexpr const char* kDifferenceImagesParameter = "differenceImages";
// How many photographs' names an unknown name's error lists.
constexpr std::size_t kNamesListed = 4;
// The difference images: named after the prior model (audit::AuditOptions).
constexpr const char* kDifferenceFolder = "assembly-files/audit";

std::vector<std::string> splitNames(const std::string& value) {
  std::vector<std::string> out;
  if (value.empty()) return out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = value.find(',', from);
    std::string name = value.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    const auto first = name.find_first_not_of(" \t"), last = name.find_last_not_of(" \t");
    name = first == std::string::npos ? std::string() : name.substr(first, last - first + 1);
    if (name.empty())
      throw Error(ErrorKind::Input, std::string(kDifferenceImagesParameter) + "=" + value, "audit",
                  "holds an empty name; give photographs' file names separated by commas");
    out.push_back(name);
    if (comma == std::string::npos) return out;
    from = comma + 1;
  }
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

double parameterNumber(const std::string& name, const std::string& value, double low, double high) {
  try {
    std::size_t used = 0;
    const double v = std::stod(value, &used);
    if (used == value.size() && std::isfinite(v) && v >= low && v < high) return v;
  } catch (const std::exception&) {
  }
  throw Error(ErrorKind::Input, name + "=" + value, "audit",
              "must be a number from " + formatNumber(low) + " up to " + formatNumber(high));
}

bool isAudited(const std::string& kind) { return kind == "lp" || kind == "rti"; }

std::string captureRelative(const fs::path& p, const fs::path& capture) {
  return p.lexically_relative(capture).generic_string();
}

// Paths of the report relative to the capture, as the carrier lists the files.
void relativise(audit::AuditReport& report, const fs::path& capture) {
  const auto rel = [&](fs::path& p) {
    if (!p.empty()) p = captureRelative(p, capture);
  };
  for (auto& l : report.lights) rel(l.file);
  for (auto& m : report.models) {
    rel(m.file);
    rel(m.lightFile);
  }
  for (auto& v : report.verdicts) {
    rel(v.model);
    rel(v.lightFile);
  }
}

// Runs the audit; a prior file that cannot be read as what its name says (a damaged .ptm, an
// .lp naming images ambiguously) is left out, with the reason recorded and logged, so that
// another tool's broken file never stops the processing of the photographs.
audit::AuditReport auditReadable(audit::AuditInputs& in, const audit::AuditOptions& options,
                                 const carrier::Step& step, pipeline::Context& ctx) {
  std::vector<audit::AuditReport::NotAudited> left;
  for (;;) {
    try {
      audit::AuditReport report = audit::runAudit(in, options);
      report.notAudited = left;
      return report;
    } catch (const Error& e) {
      bool dropped = false;
      for (auto* list : {&in.priorLightFiles, &in.priorModels})
        for (auto it = list->begin(); it != list->end() && !dropped; ++it) {
          if (it->string() != e.file()) continue;
          const std::string relative = captureRelative(*it, ctx.capture);
          left.push_back({relative, e.message()});
          carrier::addWarning(ctx.carrier, step.id,
                              {relative + " is not audited: it cannot be read", carrier::Usable::Yes,
                               "the other prior files are audited; this one is kept and packed as found",
                               "if it should be audited, check that it is complete (copy it again from its source) "
                               "and run again",
                               e.message()});
          list->erase(it);
          dropped = true;
          break;
        }
      if (!dropped) throw;
    }
  }
}

// The prior tool's processing logs that are RTIBuilder's, read and compared with the capture;
// one that cannot be read is named as not audited.
void auditLogs(audit::AuditReport& report, audit::RecordedIds& ids, const ImageStack& rgb, const InputImages& inputs,
               const carrier::Step& step, pipeline::Context& ctx) {
  audit::CaptureFacts facts;
  for (const InputImage& image : inputs) facts.photographs.push_back(image.relativePath);
  facts.photographCount = inputs.size();
  facts.width = rgb.width();
  facts.height = rgb.height();
  for (const carrier::Result& r : ctx.carrier.data)
    facts.spheres = std::max(facts.spheres, static_cast<int>(r.itemsOf("sphere").size()));
  if (!report.models.empty()) facts.basis = report.models.front().basis;
  for (const carrier::FileRecord& f : ctx.carrier.files) {
    if (f.role != "prior" || f.priorKind != "log") continue;
    const fs::path file = ctx.capture / fs::u8path(f.path);
    if (!audit::looksLikeRtiBuilderLog(file)) continue;
    ids.priorFiles[f.path] = f.id;
    try {
      report.logs.push_back(audit::auditedLog(audit::readRtiBuilderLog(file), f.path, facts));
    } catch (const Error& e) {
      report.notAudited.push_back({f.path, e.message()});
      carrier::addWarning(ctx.carrier, step.id,
                          {f.path + " is not audited: it cannot be read as RTIBuilder's log", carrier::Usable::Yes,
                           "the other prior files are audited; this one is kept and packed as found",
                           "if it should be audited, check that it is complete (copy it again from its source) and "
                           "run again",
                           e.message()});
    }
  }
}

// Per photograph (in `inputs`' order), the 95 % bound on Surrogate's light that its light item
// records (uncertaintyDegrees, from the last result holding light items); unset where none is
// recorded (a carrier from before the bound was measured): the light is then taken as exact.
std::vector<std::optional<double>> lightUncertainties(const carrier::Carrier& c, const InputImages& inputs) {
  const carrier::Result* lights = c.lastResultWith("light");
  std::vector<std::optional<double>> out(inputs.size());
  if (!lights) return out;
  std::map<std::string, double> byImage;
  for (const carrier::DataItem* l : lights->itemsOf("light"))
    if (l->get("uncertaintyDegrees")) byImage[l->get("image").value_or("")] = l->number("uncertaintyDegrees");
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (const auto it = byImage.find(inputs[i].fileId); it != byImage.end()) out[i] = it->second;
  return out;
}

// Lights from a dome's .lp are not an independent estimate: the audit compares the fit only.
bool lightsFromSpheres(const carrier::Carrier& c) {
  for (const carrier::Step& s : c.process)
    if (s.component == LightsFromFileStage::kComponent) return false;
  return true;
}
}  // namespace

pipeline::Parameters AuditStageOptions::toParameters() const {
  return {{kThresholdParameter, formatNumber(angleThresholdDegrees)},
          {kMarginParameter, formatNumber(reproducedMarginDb)},
          {kDifferenceImagesParameter, joinNames(differenceImages)}};
}

AuditStageOptions AuditStageOptions::fromParameters(const pipeline::Parameters& parameters) {
  AuditStageOptions o;
  for (const auto& [name, value] : parameters) {
    if (name == kThresholdParameter) o.angleThresholdDegrees = parameterNumber(name, value, 0, 180);
    else if (name == kMarginParameter) o.reproducedMarginDb = parameterNumber(name, value, 0, 100);
    else if (name == kDifferenceImagesParameter) o.differenceImages = splitNames(value);
    else
      throw Error(ErrorKind::Input, name + "=" + value, "audit",
                  std::string("is not a parameter of Audit (") + kThresholdParameter + ", " + kMarginParameter +
                      ", " + kDifferenceImagesParameter + ")");
  }
  if (!(o.angleThresholdDegrees > 0))
    throw Error(ErrorKind::Input, std::string(kThresholdParameter) + "=0", "audit", "must be more than 0 degrees");
  return o;
}

pipeline::StageInfo AuditStage::info() {
  // Version 1: light angles, model errors against the photographs, refits, clipped planes and
  // the verdict as docs/hrti-math.md "Auditing a prior RTI" defines them.
  // Version 2: the difference pictures are PNG files encoded with fixed Up filters and
  // run-length deflate (src/image/png_encoder.h).
  // Version 3: those PNG files compressed by libdeflate at level 1 (src/image/png_encoder.h).
  // Version 4: the refits are conditioned on their light set (src/fit/conditioning.h), so a
  // refit at a narrow cone of lights, and the verdict on it, differ from version 3's.
  // Version 5: the difference image is made at the worst image (lowest PSNR) instead of the
  // light nearest the axis, as luminance in false colour at a full scale chosen from the data,
  // with its legend; more at the photographs `differenceImages` names; each recorded with its
  // photograph, light and scale, and every photograph's prior light with its errors.
  // Also in version 5: RTIBuilder's processing logs among the prior work are read, listed and
  // compared with the capture (audit/rtibuilder_log.h); the result has a section per log.
  // Version 6: the difference PNGs carry an iTXt chunk (PNG 1.2, fmt/13) and their PRONOM
  // identifier is recorded (formats/pronom.h); the pixels are the same.
  // Version 7: a light differs only beyond both the threshold and the combined uncertainty of
  // the two lights (Surrogate's light items' uncertaintyDegrees, the prior's where it states
  // one); each photograph's uncertainties are recorded (lightUncertainty, priorLightUncertainty).
  pipeline::StageInfo info = pipeline::withOptions<AuditStageOptions>(
      {kComponent, "7",
       "Audit of prior work: its light file against Surrogate's lights, its model against the "
       "photographs beside Surrogate's refits, and a verdict",
       pipeline::PlanSlot::PriorWork});
  info.outputs = [](const carrier::Step& step) {
    std::vector<std::string> out{std::string(kDifferenceFolder) + "/*-difference.png"};
    for (const std::string& name : AuditStageOptions::fromParameters(parametersOf(step)).differenceImages)
      out.push_back(std::string(kDifferenceFolder) + "/*-difference-" + fs::u8path(name).stem().u8string() + ".png");
    return out;
  };
  info.reads = pipeline::alwaysReads({kDecodedRgbStack, kRgbStack, kLights, kInputImages});
  // The threshold is the audit's own (`surrogate audit --threshold`): recorded in the step it was
  // given for, so that re-execution repeats that audit, but no standing decision; a later audit
  // without it judges at the default.
  info.perCommand = {kThresholdParameter};
  return info;
}

void AuditStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const AuditStageOptions recorded = AuditStageOptions::fromParameters(parametersOf(step));
  // The frames as decoded, not as cropped or resized for Surrogate's fit: another tool fitted
  // the whole frames (a crop of its own shows as a size that differs).
  const auto rgb = ctx.get<ImageStack>(ctx.has(kDecodedRgbStack) ? kDecodedRgbStack : kRgbStack);
  const auto lights = ctx.get<std::vector<std::array<double, 3>>>(kLights);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  ctx.progress("Auditing prior work", 0);

  audit::AuditInputs in;
  audit::RecordedIds ids;
  for (const carrier::FileRecord& f : ctx.carrier.files) {
    if (f.role != "prior" || !isAudited(f.priorKind)) continue;
    (f.priorKind == "lp" ? in.priorLightFiles : in.priorModels).push_back(ctx.capture / fs::u8path(f.path));
    ids.priorFiles[f.path] = f.id;
  }
  if (in.priorLightFiles.empty() && in.priorModels.empty())
    throw Error(ErrorKind::Input, "carrier", "audit",
                "the carrier lists no prior light file or result (.lp, .ptm, .rti) to audit");
  for (const InputImage& image : *inputs) {
    in.photographs.files.push_back(ctx.capture / fs::u8path(image.relativePath));
    ids.photographs[fs::u8path(image.relativePath).filename().u8string()] = image.fileId;
  }
  in.photographs.stack = rgb.get();
  if (lightsFromSpheres(ctx.carrier)) {
    in.surrogateLights = *lights;
    in.surrogateUncertainty = lightUncertainties(ctx.carrier, *inputs);
  } else if (in.priorLightFiles.empty()) {
    // A dome capture: its .lp came with the dome and is what a prior fit used too, unless the
    // prior work brought a light file of its own. The fits are compared at those lights.
    for (const carrier::FileRecord& f : ctx.carrier.files) {
      if (f.role != "lp") continue;
      in.priorLightFiles.push_back(ctx.capture / fs::u8path(f.path));
      ids.priorFiles[f.path] = f.id;
    }
  }

  audit::AuditOptions options;
  options.angleThresholdDegrees = recorded.angleThresholdDegrees;
  options.reproducedDb = recorded.reproducedMarginDb;
  options.threads = ctx.settings.threads;
  options.memoryBudgetBytes = ctx.settings.fitBudget();
  options.memoryOption = ctx.settings.memoryBudget;
  std::vector<std::string> photographs;
  for (const InputImage& image : *inputs) photographs.push_back(image.relativePath);
  options.differenceAt = photographsNamed(recorded.differenceImages, photographs);
  options.differenceFolder = ctx.outputPath(kDifferenceFolder);
  fs::create_directories(options.differenceFolder);
  audit::AuditReport report = auditReadable(in, options, step, ctx);

  for (audit::ModelCheck& m : report.models)
    for (audit::DifferenceImage& d : m.differences) {
      const std::string relative = std::string(kDifferenceFolder) + "/" + d.file.filename().u8string();
      recordOutput(ctx, step, result, checkedOutputPath(relative), "assembly", "PNG", "difference", "image/png");
      d.file = relative;
    }
  relativise(report, ctx.capture);
  auditLogs(report, ids, *rgb, *inputs, step, ctx);
  audit::recordAudit(report, ids, result);
  for (const audit::Verdict& v : report.verdicts)
    ctx.carrier.addLog("info", step.id, "audit of " + (v.model.empty() ? v.lightFile : v.model).generic_string() +
                                            ": " + v.sentence);
  ctx.progress("Auditing prior work", 1);
}

std::vector<int> photographsNamed(const std::vector<std::string>& names, const std::vector<std::string>& photographs) {
  std::vector<int> out;
  for (const std::string& name : names) {
    int found = -1;
    for (int pass = 0; pass < 2 && found < 0; ++pass)
      for (std::size_t i = 0; i < photographs.size() && found < 0; ++i) {
        const fs::path p = fs::u8path(photographs[i]);
        if ((pass == 0 ? p.filename() : p.stem()).u8string() == name) found = static_cast<int>(i);
      }
    if (found >= 0) {
      if (std::find(out.begin(), out.end(), found) == out.end()) out.push_back(found);  // one picture each
      continue;
    }
    std::string some;
    for (std::size_t i = 0; i < photographs.size() && i < kNamesListed; ++i)
      some += (i ? ", " : "") + fs::u8path(photographs[i]).filename().u8string();
    if (photographs.size() > kNamesListed) some += ", ... (" + std::to_string(photographs.size()) + " in all)";
    throw Error(ErrorKind::Usage, name, "audit",
                "is not one of the photographs of this capture (" + some +
                    "); name a photograph by its file name to make a difference image at it");
  }
  return out;
}

std::vector<std::string> priorWorkToAudit(const fs::path& capture, const carrier::Carrier* previous,
                                          const std::vector<std::string>& planned) {
  std::vector<std::string> out;
  for (const std::string& path : capture::listOutputFolderFiles(capture)) {
    if (!isPriorWork(path, previous, planned)) continue;
    const carrier::FileRecord* known = previous ? previous->findFileByPath(path) : nullptr;
    const std::string kind = known && known->role == "prior" && !known->priorKind.empty()
                                 ? known->priorKind
                                 : describePriorFile(capture / fs::u8path(path), path).kind;
    if (isAudited(kind)) out.push_back(path);
  }
  return out;
}

}  // namespace surrogate::stages
