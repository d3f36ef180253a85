#include "cli/pipeline_options.h"

#include <algorithm>
#include <cctype>
#include <optional>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "cli/option_checks.h"
#include "core/error.h"
#include "core/sphere_reference.h"
#include "hrti/light_checks.h"
#include "stages/learned_fit_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/highlight_detection_stage.h"
#include "stages/light_directions_stage.h"
#include "stages/recorded_checks.h"
#include "stages/sphere_detection_stage.h"
#include "stages/preprocess.h"
#include "stages/colour_chart_options.h"
#include "stages/colour_chart_stage.h"
#include "stages/crop_stage.h"
#include "stages/resize_stage.h"
#include "stages/white_balance_stage.h"
#include "stages/web_copy_stage.h"
#include "core/text.h"

namespace surrogate::cli {

std::vector<OptionSpec> pipelineOptions(bool withFit) {
  std::vector<OptionSpec> specs = {
      {"title", true, false, "title of the project (default: the folder name)", "TEXT"},
      {"creator", true, true, "a creator, e.g. \"Ana Silva\" or \"Ana Silva:photographer\"", "NAME"},
      {"meta", true, true, "user metadata recorded in the carrier and the bag", "KEY=VALUE"},
      {"rights", true, false, "who may do what with the capture, in your words (recorded; METS rights)", "TEXT"},
      {"license", true, false, "the licence of the capture, as a URI, e.g. https://creativecommons.org/licenses/by/4.0/", "URI"},
      {"operator", true, false, "who runs this (recorded with interventions; default $USER)", "NAME"},
      {"exclude", true, true, "leave an image out (needs --reason after it)", "IMAGE"},
      {"reason", true, true, "why: follows --exclude, --sphere, --highlight, --colour-chart, --accept-... or --forget-...", "TEXT"},
      {"source", true, false, "images to use: auto (raw if present), original, export", "WHICH"},
      {"raw", true, true, "LibRaw setting, e.g. demosaic=AHD, whiteBalance=camera", "NAME=VALUE"},
      {"sphere-roi", true, true, "search a sphere only in this region (one per sphere)", "X,Y,W,H"},
      {"sphere", true, true, "give a sphere's circle by hand instead of detecting it", "CX,CY,R"},
      {"highlight", true, true, "give a highlight by hand: IMAGE:sphereN=X,Y (sphere1 is the first sphere; a bare number counts from 0)", "SPEC"},
      {"highlight-threshold", true, false, "fraction of the brightest pixel (default 0.8)", "T"},
      {"light-model", true, false, "orthographic (default) or perspective", "MODEL"},
      {"focal-length", true, false, "lens focal length for the perspective model (default: EXIF)", "MM"},
      {"pixel-pitch", true, false, "sensor pixel pitch for the perspective model (default: EXIF)", "MM"},
      {"sphere-diameter", true, false, "real sphere diameter: with 2 spheres, gives light positions", "MM"},
      {"light-distance", true, false, "how far the lights were from the frame's centre: frame widths (3), a length (1.2m, with --sphere-diameter), infinity or auto (default: two spheres place each light where they can)", "D"},
      // The capture's memory: decisions recorded by earlier runs stand until withdrawn.
      {"lp", true, false, "dome capture: take the lights from this .lp file in the capture (none: back to the spheres)", "FILE.lp"},
      {"forget-exclusion", true, true, "withdraw a recorded exclusion (needs --reason after it)", "IMAGE"},
      {"forget-sphere", true, true, "withdraw a sphere given by hand: sphere1 is the first --sphere (a bare number counts from 0; needs --reason)", "sphereN"},
      {"forget-highlight", true, true, "withdraw a highlight given by hand (needs --reason)", "IMAGE:sphereN"},
      {"reset", false, false, "withdraw every recorded processing decision (needs --reason after it)"},
      {"accept-changed", true, true, "accept that a recorded original changed or was removed (needs --reason)", "PATH"},
      {"accept-damaged", true, true, "decode an image although its decoder reports damaged data (needs --reason)", "IMAGE"},
      {"forget-damaged", true, true, "withdraw an accepted damaged image (needs --reason)", "IMAGE"},
      {"accept", true, true, "accept a failed check by name, e.g. lights-clustered (needs --reason)", "CHECK"},
      {"forget-accept", true, true, "withdraw an accepted check (needs --reason)", "CHECK"},
  };
  if (withFit) {
    // Colour from a chart (the ColourCorrection step, stages/colour_chart_stage.h), a standing
    // decision like the others.
    specs.push_back({"colour-chart", true, false, "the ColorChecker: auto (default: looked for, used if found), none, the image it is in (IMG_0003), or with its corners IMG_0003:X1,Y1,...,X4,Y4 (dark skin, bluish green, black, white)", "IMAGE[:X1,Y1,...]"});
    specs.push_back({"chart-reference", true, false, "the chart's edition: colorchecker-classic-2014 (default: charts made since November 2014) or colorchecker-classic-pre-2014", "ID"});
    specs.push_back({"colour-model", true, false, "the correction fitted to the chart: matrix (3x3, default) or root-polynomial", "MODEL"});
    specs.push_back({"basis", true, true, "model to fit, repeatable: ptm-lrgb, ptm-rgb, hsh2, hsh3, or a learned basis rbf, bln (a web layout in finished-files/BASIS/) (default: ptm-lrgb and hsh2)", "BASIS"});
    // The learned fit's options (LearnedFit steps, stages/learned_fit_stage.h), as `surrogate fit` names them.
    specs.push_back({"planes", true, false, "rbf, bln: coefficients per pixel, a multiple of 3 (default " + std::to_string(stages::kLearnedPlanes) + ")", "N"});
    specs.push_back({"resolution", true, false, "bln: the side of the grid over the light directions (default " + std::to_string(stages::kLearnedResolution) + ")", "R"});
    specs.push_back({"quality", true, false, "rbf, bln: JPEG quality of the planes, 1..100, or Q:LAST from the first plane to the last (default " +
                                             std::to_string(stages::kLearnedQuality) + ":" + std::to_string(stages::kLearnedLastQuality) + ")", "Q[:LAST]"});
    specs.push_back({"holdout", true, false, "every fit: also fit without K photographs and record PSNR/SSIM at their lights (0: not measured)", "K"});
    // Pre-processing of the images the fit reads (recorded steps WhiteBalance, Crop, Resize,
    // planned in that order after light estimation, which always reads the full frame).
    specs.push_back({"wb", true, false, "white balance for the fit: as-shot, region:X,Y,W,H (a grey area, full-frame pixels) or multipliers:R,G,B", "MODE"});
    specs.push_back({"wb-region", true, false, "white balance from this grey area (same as --wb region:X,Y,W,H)", "X,Y,W,H"});
    specs.push_back({"output-space", true, false, "values the fit reads: srgb (default) or linear (proportional to light)", "SPACE"});
    specs.push_back({"crop", true, false, "fit only this rectangle of the frame (pixels), or auto: the largest one clear of the spheres", "X,Y,W,H|auto"});
    specs.push_back({"crop-margin", true, false, "with --crop auto: clearance around each sphere, fraction of its radius (default 0.25)", "F"});
    specs.push_back({"resize", true, false, "reduce the fitted result: a factor (0.5) or a size (WxH), area averaging", "FACTOR|WxH"});
    // The web copy of each model (WebCopy steps, stages/web_copy_stage.h), a standing decision.
    specs.push_back({"publish", false, false, "also write each model's web copy to finished-files/web/ (kept for later runs; rbf and bln are web layouts already)"});
    specs.push_back({"no-publish", false, false, "withdraw the web copy (its files go to superseded-files/)"});
    specs.push_back({"publish-quality", true, false, "JPEG quality 1..100 of the web copy's planes (default 95)", "Q"});
    specs.push_back({"publish-tiles", true, false, "web copy tiles: auto (default), none or deepzoom", "LAYOUT"});
    specs.push_back({"publish-tile-size", true, false, "side of the web copy's Deep Zoom tiles, 16..4096 (default 256)", "N"});
  }
  // The heading each option is listed under in --help (processing unless named here).
  const std::pair<OptionGroup, std::vector<std::string>> groups[] = {
      {OptionGroup::Input, {"source", "raw", "lp"}},
      {OptionGroup::Description, {"title", "creator", "meta", "rights", "license"}},
      {OptionGroup::Decisions,
       {"operator", "exclude", "reason", "sphere", "highlight", "forget-exclusion", "forget-sphere",
        "forget-highlight", "reset", "accept-changed", "accept-damaged", "forget-damaged", "accept",
        "forget-accept"}},
      {OptionGroup::Output, {"publish", "no-publish", "publish-quality", "publish-tiles", "publish-tile-size"}},
  };
  for (OptionSpec& spec : specs)
    for (const auto& [group, names] : groups)
      if (std::find(names.begin(), names.end(), spec.name) != names.end()) spec.group = group;
  return specs;
}

std::vector<OptionSpec> runOptionsForAnotherCommand() {
  std::vector<OptionSpec> specs = pipelineOptions(true);
  for (OptionSpec& spec : specs) spec.fromRun = true;
  return specs;
}

std::vector<OptionSpec> runtimeOptions() {
  return {
      {"threads", true, false, "worker threads (default: all cores); results do not depend on it", "N"},
      {"memory", true, false, "memory budget for streaming work (default 2G)", "SIZE"},
      {"quiet", false, false, "no progress bar, and at most one summary line", "", OptionGroup::Output},
      {"verbose", false, false, "list every file written and every warning", "", OptionGroup::Output},
      {"json", false, false, "print the summary as JSON", "", OptionGroup::Output},
  };
}

namespace {

// "IMAGE:sphereN" or "IMAGE:N" (index from 0) or "IMAGE" (the first sphere) as the carrier's
// target "IMAGE:INDEX" (core/sphere_reference.h).
std::string highlightTarget(const std::string& typed, const std::string& option) {
  const auto colon = typed.rfind(':');
  if (colon == std::string::npos) return typed + ":0";
  const auto index = sphereIndexOfReference(typed.substr(colon + 1));
  if (!index)
    throw Error(ErrorKind::Usage, option, "command line",
                "names no sphere after the colon: give IMAGE:sphere1 for the first sphere, IMAGE:sphere2 for the second");
  return typed.substr(0, colon) + ":" + std::to_string(*index);
}

std::pair<std::string, std::string> splitKeyValue(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(ErrorKind::Usage, option + " " + text, "command line", "needs the form KEY=VALUE");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void param(run::RunRequest& r, const char* component, const std::pair<std::string, std::string>& p) {
  r.stageParams.push_back({component, p.first, p.second});
}

// --light-model, --focal-length, --pixel-pitch, --sphere-diameter, --light-distance: the LightDirections
// parameters given, each recorded on its own (a standing decision for the others stays).
void lightDirections(run::RunRequest& r, const Args& args) {
  using stages::LightDirectionsOptions;
  const char* component = stages::LightDirectionsStage::kComponent;
  LightDirectionsOptions given;
  if (const auto m = args.value("light-model")) {
    given.model = *m;
    param(r, component, given.modelParameter());
  }
  const std::pair<const char*, double LightDirectionsOptions::*> lengths[] = {
      {"focal-length", &LightDirectionsOptions::focalLengthMm},
      {"pixel-pitch", &LightDirectionsOptions::pixelPitchMm},
      {"sphere-diameter", &LightDirectionsOptions::sphereDiameterMm},
  };
  for (const auto& [option, field] : lengths) {
    const auto text = args.value(option);
    if (!text) continue;
    given.*field = parseNumberList(*text, 1, std::string("--") + option)[0];
    param(r, component, given.parameter(field));
  }
  if (const auto d = args.value("light-distance")) {
    stages::StatedDistance::parse(*d, "--light-distance");  // Error(Usage) before any work
    given.lightDistance = *d;
    param(r, component, given.lightDistanceParameter());
  }
}

// --colour-chart, --chart-reference, --colour-model: the ColourCorrection parameters given,
// checked as the stage reads them; --colour-chart sets the chart and its corners together (so
// corners given earlier go when the chart changes).
void colourChart(run::RunRequest& r, const Args& args) {
  const char* component = stages::ColourChartStage::kComponent;
  if (const auto text = args.value("colour-chart")) {
    stages::ColourChartOptions o;
    stages::ColourChartOptions::parseChartText(*text, "--colour-chart", o);
    param(r, component, {"chart", o.chart});
    param(r, component, {"corners", o.cornersText()});
  }
  if (const auto ref = args.value("chart-reference")) {
    stages::ColourChartOptions::fromParameters({{"reference", *ref}}, "--chart-reference");
    param(r, component, {"reference", *ref});
  }
  if (const auto model = args.value("colour-model")) {
    stages::ColourChartOptions::fromParameters({{"model", *model}}, "--colour-model");
    param(r, component, {"model", *model});
  }
}

// --wb, --wb-region, --output-space, --crop, --crop-margin, --resize: the pre-processing steps,
// each with its full parameters, in the order WhiteBalance, Crop, Resize.
void preprocessing(run::RunRequest& r, const Args& args) {
  if (args.has("wb") && args.has("wb-region"))
    throw Error(ErrorKind::Usage, "--wb-region", "command line",
                "give either --wb or --wb-region, not both (--wb-region X,Y,W,H is --wb region:X,Y,W,H)");
  std::optional<stages::WhiteBalanceOptions> wb;
  if (const auto text = args.value("wb")) wb = stages::WhiteBalanceOptions::fromText(*text, "--wb");
  if (const auto text = args.value("wb-region"))
    wb = stages::WhiteBalanceOptions::fromText("region:" + *text, "--wb-region");
  if (const auto space = args.value("output-space")) {
    if (*space != "srgb" && *space != "linear")
      throw Error(ErrorKind::Usage, "--output-space " + *space, "command line", "use srgb or linear");
    if (!wb) wb = stages::WhiteBalanceOptions{};
    wb->outputSpace = *space;
  }
  if (wb) r.preprocessing.push_back({stages::WhiteBalanceStage::kComponent, wb->toParameters()});

  if (args.has("crop-margin") && args.value("crop", "") != "auto")
    throw Error(ErrorKind::Usage, "--crop-margin", "command line", "only applies with --crop auto");
  if (const auto text = args.value("crop")) {
    stages::CropOptions crop = stages::CropOptions::fromText(*text, "--crop");
    if (const auto m = args.value("crop-margin")) {
      const double v = parseNumberList(*m, 1, "--crop-margin")[0];
      if (!(v >= 0 && v <= 10))
        throw Error(ErrorKind::Usage, "--crop-margin " + *m, "command line",
                    "needs a fraction of the sphere radius from 0 to 10");
      crop.margin = v;
    }
    r.preprocessing.push_back({stages::CropStage::kComponent, crop.toParameters()});
  }
  if (const auto text = args.value("resize"))
    r.preprocessing.push_back(
        {stages::ResizeStage::kComponent, stages::ResizeOptions::fromText(*text, "--resize").toParameters()});
  if (!r.preprocessing.empty() && r.bases && r.bases->empty())
    throw Error(ErrorKind::Usage, "--crop/--resize/--wb", "command line", "pre-processing needs a fit (--basis)");
}

// --publish, --no-publish and the web copy's options, checked as WebCopy reads them.
void webCopy(run::RunRequest& r, const Args& args) {
  if (args.has("publish") && args.has("no-publish"))
    throw Error(ErrorKind::Usage, "--no-publish", "command line", "contradicts --publish: give one of them");
  if (args.has("publish")) r.publish = true;
  if (args.has("no-publish")) r.publish = false;
  const char* component = stages::WebCopyStage::kComponent;
  for (const auto& [option, name] : {std::pair<const char*, const char*>{"publish-quality", "quality"},
                                     {"publish-tiles", "tiles"},
                                     {"publish-tile-size", "tileSize"}}) {
    const auto value = args.value(option);
    if (!value) continue;
    try {
      stages::WebCopyOptions::fromParameters({{name, *value}});
    } catch (const Error& e) {
      throw Error(ErrorKind::Usage, std::string("--") + option + " " + *value, "command line", e.message());
    }
    param(r, component, {name, *value});
  }
}

// --planes, --resolution, --quality, --holdout: the learned fit's options, checked as LearnedFit
// reads them, for every LearnedFit step (one per learned basis).
void learnedFit(run::RunRequest& r, const Args& args) {
  for (const char* option : {"planes", "resolution", "quality", "holdout"}) {
    const auto value = args.value(option);
    if (!value) continue;
    try {
      stages::LearnedFitOptions::fromParameters({{option, *value}});
    } catch (const Error& e) {
      throw Error(ErrorKind::Usage, std::string("--") + option + " " + *value, "command line", e.message());
    }
    param(r, stages::LearnedFitStage::kComponent, {option, *value});
    // --holdout measures every fit, the PTM and HSH ones too (RtiFit's parameter of that name).
    if (std::string(option) == "holdout") param(r, stages::RtiFitStage::kComponent, {option, *value});
  }
}

}  // namespace

run::RunRequest requestFrom(const Args& args) {
  checkPipelineOptionValues(args);  // every value that needs no capture, before any work
  run::RunRequest r;
  r.title = args.value("title", "");
  for (const std::string& c : args.values("creator")) {
    const auto colon = c.rfind(':');
    if (colon != std::string::npos && colon > 0 && colon + 1 < c.size())
      r.creators.push_back({c.substr(0, colon), c.substr(colon + 1)});
    else
      r.creators.push_back({c, "creator"});
  }
  for (const std::string& m : args.values("meta")) r.meta.push_back(splitKeyValue(m, "--meta"));
  r.rights = args.value("rights", "");
  r.license = args.value("license", "");
  if (!r.license.empty()) {
    // A URI with a scheme ("https:", "urn:"), no spaces: what a repository can resolve.
    const auto colon = r.license.find(':');
    bool uri = colon != std::string::npos && colon > 0 && std::isalpha(static_cast<unsigned char>(r.license[0]));
    for (std::size_t i = 0; uri && i < r.license.size(); ++i) {
      const auto c = static_cast<unsigned char>(r.license[i]);
      if (c <= 0x20 || c == 0x7f || (i < colon && !(std::isalnum(c) || c == '+' || c == '-' || c == '.'))) uri = false;
    }
    if (!uri)
      throw Error(ErrorKind::Usage, "--license " + r.license, "command line",
                  "needs the licence as a URI, e.g. https://creativecommons.org/licenses/by/4.0/");
  }
  r.who = args.value("operator", "");
  r.source = args.value("source", "");
  if (!r.source.empty()) capture::parseSource(r.source);  // an unknown source is a usage error now
  if (const auto lp = args.value("lp")) r.lp = *lp == "none" ? std::string() : *lp;
  for (const auto& [name, value] : args.ordered()) {
    r.arguments.push_back(optionName(name));
    if (name != "quiet" && name != "json" && name != "no-report" && name != "reset" && name != "publish" &&
        name != "no-publish")
      r.arguments.push_back(value);
  }
  for (const std::string& s : args.values("raw")) r.decodeSettings.push_back(splitKeyValue(s, "--raw"));

  std::string regions;
  for (const std::string& roi : args.values("sphere-roi")) {
    parseNumberList(roi, 4, "--sphere-roi");
    regions += (regions.empty() ? "" : ";") + roi;
  }
  // The names are those of hrti::SphereDetectionOptions and hrti::HighlightOptions.
  if (!regions.empty()) param(r, stages::SphereDetectionStage::kComponent, {"regions", regions});
  if (const auto t = args.value("highlight-threshold")) {
    const double v = parseNumberList(*t, 1, "--highlight-threshold")[0];
    if (!(v > 0 && v < 1))
      throw Error(ErrorKind::Usage, "--highlight-threshold", "command line", "needs a fraction between 0 and 1");
    param(r, stages::HighlightDetectionStage::kComponent, {"threshold", formatNumber(v)});
  }
  lightDirections(r, args);
  colourChart(r, args);
  if (args.has("basis")) r.bases = args.values("basis");
  learnedFit(r, args);
  preprocessing(r, args);
  webCopy(r, args);

  // Interventions, in the order given; a --reason belongs to the one just before it.
  int spheres = 0;
  carrier::Intervention* last = nullptr;
  bool lastIsExclusion = false;
  std::string* lastReason = nullptr;  // of a withdrawal, --reset or --accept-changed
  for (const auto& [name, value] : args.ordered()) {
    if (name == "light-distance") {
      // The distance is a decision like a circle: its reason, if given, is recorded with it.
      for (run::RunRequest::StageParam& p : r.stageParams)
        if (p.component == stages::LightDirectionsStage::kComponent && p.name == "lightDistance")
          lastReason = &p.reason;
      last = nullptr;
      lastIsExclusion = false;
      continue;
    }
    if (name == "colour-chart") {
      // The chart, like the distance: its reason, if given, goes with it into the run's note.
      for (run::RunRequest::StageParam& p : r.stageParams)
        if (p.component == stages::ColourChartStage::kComponent && p.name == "chart") lastReason = &p.reason;
      last = nullptr;
      lastIsExclusion = false;
      continue;
    }
    if (name == "accept" || name == "forget-accept") {
      const auto& known = hrti::lightCheckNames();
      if (std::find(known.begin(), known.end(), value) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw Error(ErrorKind::Usage, "--" + name + " " + value, "command line", "is not a check; the checks are " + list);
      }
    }
    if (name == "accept") {
      // The residual check runs after each fit, frame-moved with the highlights, the others with
      // the lights.
      const char* component = value == hrti::kCheckResidualOutlier ? stages::RtiFitStage::kComponent
                              : value == hrti::kCheckFrameMoved    ? stages::HighlightDetectionStage::kComponent
                                                                   : stages::LightDirectionsStage::kComponent;
      r.stageInterventions.push_back({component, {stages::kAcceptCheck, value, "", "", "", ""}});
      last = &r.stageInterventions.back().intervention;
      lastIsExclusion = false;
      lastReason = nullptr;
      continue;
    }
    if (name == "forget-exclusion" || name == "forget-sphere" || name == "forget-highlight" ||
        name == "forget-damaged" || name == "forget-accept") {
      // Spheres as typed (sphere1, or an index from 0), recorded as the carrier's index.
      std::string target = value;
      if (name == "forget-highlight") target = highlightTarget(value, "--forget-highlight " + value);
      if (name == "forget-sphere") {
        const auto index = sphereIndexOfReference(value);
        if (!index)
          throw Error(ErrorKind::Usage, "--forget-sphere " + value, "command line",
                      "names no sphere: give sphere1 for the first circle given by hand (--sphere), sphere2 for "
                      "the second");
        target = std::to_string(*index);
      }
      r.withdrawals.push_back({name == "forget-exclusion" ? "exclude-image"
                               : name == "forget-sphere"  ? "manual-sphere"
                               : name == "forget-damaged" ? "accept-decoder-warning"
                               : name == "forget-accept"  ? stages::kAcceptCheck
                                                          : "manual-highlight",
                               target, ""});
      lastReason = &r.withdrawals.back().reason;
      last = nullptr;
      lastIsExclusion = false;
      continue;
    }
    if (name == "reset" || name == "accept-changed" || name == "accept-damaged") {
      if (name == "reset") {
        r.resetReason = "";
        lastReason = &*r.resetReason;
      } else if (name == "accept-damaged") {
        r.acceptedDamage.push_back({value, ""});
        lastReason = &r.acceptedDamage.back().reason;
      } else {
        r.acceptedChanges.push_back({value, ""});
        lastReason = &r.acceptedChanges.back().reason;
      }
      last = nullptr;
      lastIsExclusion = false;
      continue;
    }
    if (name == "reason" && lastReason && lastReason->empty()) {
      *lastReason = value;
      lastReason = nullptr;
      continue;
    }
    if (name == "exclude" || name == "sphere" || name == "highlight") lastReason = nullptr;
    if (name == "exclude") {
      r.exclusions.push_back({value, "", "", ""});
      lastIsExclusion = true;
      last = nullptr;
    } else if (name == "sphere") {
      parseNumberList(value, 3, "--sphere");
      r.stageInterventions.push_back({stages::SphereDetectionStage::kComponent,
                                      {"manual-sphere", std::to_string(spheres++), value, "", "", ""}});
      last = &r.stageInterventions.back().intervention;
      lastIsExclusion = false;
    } else if (name == "highlight") {
      const auto eq = value.find('=');
      if (eq == std::string::npos)
        throw Error(ErrorKind::Usage, "--highlight " + value, "command line", "needs the form IMAGE:sphereN=X,Y");
      parseNumberList(value.substr(eq + 1), 2, "--highlight");
      const std::string target = highlightTarget(value.substr(0, eq), "--highlight " + value);
      r.stageInterventions.push_back({stages::HighlightDetectionStage::kComponent,
                                      {"manual-highlight", target, value.substr(eq + 1), "", "", ""}});
      last = &r.stageInterventions.back().intervention;
      lastIsExclusion = false;
    } else if (name == "reason") {
      if (lastIsExclusion && r.exclusions.back().reason.empty()) {
        r.exclusions.back().reason = value;
      } else if (last && last->reason.empty()) {
        last->reason = value;
      } else {
        throw Error(ErrorKind::Usage, "--reason", "command line",
                    "must follow the --exclude, --sphere, --highlight, --light-distance, --colour-chart or --accept it "
                    "explains");
      }
    }
  }
  auto needReason = [](const std::string& what, const std::string& reason) {
    if (reason.empty())
      throw Error(ErrorKind::Usage, what, "command line",
                  "withdrawing a recorded decision, or accepting a changed original or a damaged "
                  "image, needs a reason: add --reason \"why\" after it; it is recorded with who and when");
  };
  for (const run::Withdrawal& w : r.withdrawals) needReason("--forget " + w.target, w.reason);
  if (r.resetReason) needReason("--reset", *r.resetReason);
  for (const run::AcceptedChange& a : r.acceptedChanges) needReason("--accept-changed " + a.path, a.reason);
  for (const run::AcceptedDamage& a : r.acceptedDamage) needReason("--accept-damaged " + a.image, a.reason);
  for (const run::Exclusion& e : r.exclusions)
    if (e.reason.empty())
      throw Error(ErrorKind::Usage, "--exclude " + e.image, "command line",
                  "every excluded image needs a reason: add --reason \"why\" after it; the "
                  "reason is recorded as a human intervention");
  // A circle or highlight set by hand is an intervention too; when no reason is given, the
  // record says so plainly rather than inventing one.
  for (auto& i : r.stageInterventions) {
    // Accepting a failed check overrides a safeguard: like an exclusion, it needs its reason.
    if (i.intervention.kind == stages::kAcceptCheck && i.intervention.reason.empty())
      throw Error(ErrorKind::Usage, "--accept " + i.intervention.target, "command line",
                  "accepting a failed check needs a reason: add --reason \"why\" after it; it is recorded with "
                  "who and when");
    if (i.intervention.reason.empty()) i.intervention.reason = "given on the command line (no reason stated)";
  }
  return r;
}

pipeline::RunSettings settingsFrom(const Args& args) {
  pipeline::RunSettings s;
  s.threads = threadsOption(args);  // 0 (all cores) to kMaxThreads
  if (const auto m = args.value("memory")) s.memoryBudget = parseByteSize(*m, "--memory");
  s.who = args.value("operator", "");
  return s;
}

pipeline::RunSettings settingsFrom(const Args& args, ProgressBar& bar) {
  pipeline::RunSettings s = settingsFrom(args);
  s.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  return s;
}

}  // namespace surrogate::cli
