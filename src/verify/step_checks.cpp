// carrier.steps: every recorded step is one this build can run, as recorded. Checked without
// running anything, by the stages' own parameter parsers (the ones re-execution uses), so that
// a carrier whose steps cannot run is an invalid package (exit 2) for plain `verify`, and
// `--reexecute` never starts on it.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "archive/bag_text.h"
#include "capture/capture.h"
#include "core/error.h"
#include "fit/basis.h"
#include "fit/fit.h"
#include "fit/learned.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"
#include "image/raw_settings.h"
#include "pipeline/stage.h"
#include "stages/outputs.h"
#include "stages/registry.h"
#include "stages/frame_checks.h"
#include "stages/learned_fit_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/light_directions_stage.h"
#include "stages/lights_from_file_stage.h"
#include "stages/preprocess.h"
#include "verify/checks.h"

namespace surrogate::verify {

namespace {

using Parameters = std::vector<std::pair<std::string, std::string>>;

Parameters parametersOf(const carrier::Step& step) {
  Parameters out;
  for (const carrier::Param& p : step.params) out.emplace_back(p.name, p.value);
  return out;
}

std::string listed(const Parameters& params) {
  std::string out;
  for (const auto& [name, value] : params)
    out += (out.empty() ? "" : ", ") + name + "=" + value.substr(0, 80);
  return out.empty() ? "none" : out;
}

// A finite number written in full ("0.5", not "0.5abc" or "nan").
bool finiteNumber(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(value);
}

// Comma-separated finite numbers, exactly `count` of them.
bool numbers(const std::string& text, std::size_t count, std::vector<double>& out) {
  out.clear();
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    double v = 0;
    if (!finiteNumber(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start), v))
      return false;
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out.size() == count;
}

// The problems of one step's parameters (each a sentence naming the parameter).
std::vector<std::string> parameterProblems(const carrier::Step& step,
                                           const std::set<std::string>& fittedBases) {
  std::vector<std::string> out;
  const Parameters params = parametersOf(step);
  auto parse = [&](const std::function<void(const Parameters&)>& parser) {
    try {
      parser(params);
    } catch (const Error& e) {
      out.push_back(e.text() + " (recorded: " + listed(params) + ")");
    } catch (const std::exception& e) {
      out.push_back(std::string("the parameters cannot be read: ") + e.what() + " (recorded: " +
                    listed(params) + ")");
    }
  };
  auto only = [&](const std::set<std::string>& names) {
    for (const auto& [name, value] : params)
      if (!names.count(name))
        out.push_back("parameter " + name + "=" + value.substr(0, 80) + " is not one " +
                      step.component + " takes");
  };
  const std::string& c = step.component;
  if (c == "CaptureIngest") {
    only({"source", "lp"});
    if (step.hasParam("source")) parse([&](const Parameters&) { capture::parseSource(step.param("source")); });
    if (step.hasParam("lp") && !step.param("lp").empty()) {
      std::string why;
      if (!safeBagPath("data/" + step.param("lp"), &why))  // as it lies in the bag
        out.push_back("parameter lp=" + step.param("lp").substr(0, 200) + ": " + why);
    }
  } else if (c == "ImageDecode") {
    parse([](const Parameters& p) { image::RawDecodeSettings::fromParameters(p); });
  } else if (c == "SphereDetection") {
    parse([](const Parameters& p) { hrti::SphereDetectionOptions::fromParameters(p); });
  } else if (c == "HighlightDetection") {
    parse([](const Parameters& p) { hrti::HighlightOptions::fromParameters(p); });
  } else if (c == "LightDirections") {
    only({"model", "focalLengthMm", "pixelPitchMm", "sphereDiameterMm", "lightDistance"});
    if (step.hasParam("lightDistance")) {
      try {
        stages::StatedDistance::parse(step.param("lightDistance"), "lightDistance");
      } catch (const Error& e) {
        out.push_back("parameter lightDistance=" + step.param("lightDistance").substr(0, 80) + ": " + e.message());
      }
    }
    const std::string model = step.param("model", "orthographic");
    if (model != "orthographic" && model != "perspective")
      out.push_back("parameter model=" + model.substr(0, 80) +
                    " is not a light model (orthographic or perspective)");
    for (const char* name : {"focalLengthMm", "pixelPitchMm", "sphereDiameterMm"}) {
      double v = 0;
      if (step.hasParam(name) && (!finiteNumber(step.param(name), v) || v < 0))
        out.push_back(std::string("parameter ") + name + "=" + step.param(name).substr(0, 80) +
                      " is not a length in millimetres (a finite number, 0 or more)");
    }
  } else if (c == "LightsFromFile") {
    only({"lightDistance"});
    parse([](const Parameters& p) { stages::LightsFromFileOptions::fromParameters(p); });
  } else if (c == "WhiteBalance") {
    parse([](const Parameters& p) { stages::WhiteBalanceOptions::fromParameters(p, "carrier"); });
  } else if (c == "Crop") {
    parse([](const Parameters& p) { stages::CropOptions::fromParameters(p, "carrier"); });
  } else if (c == "Resize") {
    parse([](const Parameters& p) { stages::ResizeOptions::fromParameters(p, "carrier"); });
  } else if (c == "RtiFit") {
    Parameters fitParams;
    for (const auto& p : params)
      if (p.first != "output") fitParams.push_back(p);
    try {
      stages::RtiFitOptions::fromParameters(fitParams);  // the fit's and holdout (RtiFit 7)
    } catch (const Error& e) {
      out.push_back(e.text() + " (recorded: " + listed(params) + ")");
    }
    if (step.hasParam("output")) {
      try {
        stages::checkedOutputPath(step.param("output"));
      } catch (const Error& e) {
        out.push_back("parameter output=" + step.param("output").substr(0, 200) + ": " + e.message());
      }
    }
  } else if (c == "LearnedFit") {
    parse([](const Parameters& p) { stages::LearnedFitOptions::fromParameters(p); });
  } else if (c == "DerivedMaps") {
    only({"model"});
    const std::string model = step.param("model", "ptm-lrgb");
    try {
      const std::string name = fit::isLearnedBasisName(model) ? model : fit::basisName(fit::parseBasis(model));
      if (!fittedBases.count(name))
        out.push_back("parameter model=" + model + " names a model no earlier RtiFit or LearnedFit step fits");
    } catch (const Error&) {
      out.push_back("parameter model=" + model.substr(0, 80) + " is not a model basis (ptm-lrgb, "
                    "ptm-rgb, hsh2, hsh3, rbf, bln)");
    }
  }

  // Values chosen by hand, checked as the stages check them (with no frame: what needs none).
  for (const carrier::Intervention& i : step.interventions) {
    std::vector<double> v;
    if (i.kind == "manual-sphere") {
      const std::string why = !numbers(i.value, 3, v)
                                  ? "is not CX,CY,R (three finite numbers)"
                                  : stages::sphereCircleProblem(v[0], v[1], v[2]);
      if (!why.empty())
        out.push_back("intervention manual-sphere " + i.target.substr(0, 80) + " = " +
                      i.value.substr(0, 80) + ": " + why);
    } else if (i.kind == "manual-highlight") {
      const std::string why = !numbers(i.value, 2, v) ? "is not X,Y (two finite numbers)"
                                                      : stages::highlightPointProblem(v[0], v[1]);
      if (!why.empty())
        out.push_back("intervention manual-highlight " + i.target.substr(0, 80) + " = " +
                      i.value.substr(0, 80) + ": " + why);
    }
  }
  return out;
}

}  // namespace

bool checkSteps(const carrier::Carrier& c, std::vector<Check>& checks) {
  stages::registerBuiltinStages();
  const pipeline::StageRegistry& registry = pipeline::StageRegistry::instance();
  std::vector<std::string> problems;
  std::set<std::string> fittedBases;
  std::map<std::string, std::string> versions;  // of this build, by component
  for (const carrier::Step& step : c.process) {
    const std::string name = "step " + step.id + " (" + step.component.substr(0, 80) + ")";
    if (!registry.has(step.component)) {
      std::string known;
      for (const std::string& k : registry.components()) known += (known.empty() ? "" : ", ") + k;
      problems.push_back(name + ": no stage of this build has that name (it has " + known + ")");
      continue;
    }
    auto [it, fresh] = versions.emplace(step.component, "");
    if (fresh) it->second = registry.create(step.component)->version();
    if (!registry.runsAsRecorded(step.component, step.version))
      problems.push_back(name + ": version " + step.version.substr(0, 40) + " is recorded, this build has " +
                         step.component + " version " + it->second +
                         " only, whose results may differ; verify with the Surrogate that made it "
                         "(see the carrier's header)");
    for (const std::string& p : parameterProblems(step, fittedBases)) problems.push_back(name + ": " + p);
    if (step.component == "RtiFit") {
      Parameters fitParams;
      for (const carrier::Param& p : step.params)
        if (p.name != "output") fitParams.emplace_back(p.name, p.value);
      try {
        fittedBases.insert(fit::basisName(stages::RtiFitOptions::fromParameters(fitParams).fit.basis));
      } catch (const Error&) {
      }
    } else if (step.component == "LearnedFit") {
      try {
        fittedBases.insert(stages::LearnedFitOptions::fromParameters(parametersOf(step)).basis);
      } catch (const Error&) {
      }
    }
  }
  // Every file a step made is inside assembly-files/ or finished-files/, where re-execution
  // writes.
  for (const carrier::FileRecord& f : c.files) {
    if (f.createdBy.empty() && f.role != "assembly" && f.role != "result") continue;
    try {
      stages::checkedOutputPath(f.path);
    } catch (const Error& e) {
      problems.push_back("file " + f.id + " (" + f.role + ", made by " +
                         (f.createdBy.empty() ? std::string("a step") : f.createdBy) + ") " +
                         f.path.substr(0, 200) + ": " + e.message());
    }
  }
  checks.push_back(makeCheck(
      "carrier.steps", Severity::Invalid,
      std::to_string(c.process.size()) +
          " recorded steps can run in this build as recorded (known stages and versions, valid "
          "parameters, outputs inside assembly-files/ and finished-files/)",
      "the carrier records steps this build cannot run as recorded", problems));
  return problems.empty();
}

}  // namespace surrogate::verify
