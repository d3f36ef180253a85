#include "stages/light_stages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/lp.h"
#include "hrti/highlight_detection.h"
#include "hrti/light_checks.h"
#include "hrti/light_direction.h"
#include "hrti/light_position.h"
#include "hrti/drawing.h"
#include "hrti/sphere_detection.h"
#include "hrti/stack_median.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/recorded_checks.h"
#include "stages/request_checks.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

using Spheres = std::vector<hrti::DetectedSphere>;
using Highlights = std::vector<std::vector<hrti::Highlight>>;  // [image][sphere]
using Lights = std::vector<std::array<double, 3>>;

namespace {

// The files these stages write: named once, for the stage that writes them and for its info()
// (what the plan will write, checked against prior work before a run).
const std::string kSphereOverlay = std::string(capture::kAssemblyDir) + "/spheres.png";
const std::string kLightsFile = std::string(capture::kAssemblyDir) + "/lights.lp";
std::string highlightOverview(const std::string& sphere) {
  return std::string(capture::kAssemblyDir) + "/highlights-sphere" + sphere + ".png";
}

std::vector<std::string> lightsFileOutput(const carrier::Step&) { return {kLightsFile}; }

std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& what) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    try {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throwInputError("carrier", what, "\"" + text + "\" is not a list of " + std::to_string(count) + " numbers");
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (out.size() != count)
    throwInputError("carrier", what, "\"" + text + "\" is not a list of " + std::to_string(count) + " numbers");
  return out;
}

// The name of an .lp file at the top of the capture (a dome's light file), or "".
std::string lightFileInCapture(const fs::path& capture) {
  std::error_code ec;
  std::vector<std::string> names;
  for (fs::directory_iterator it(capture, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() == ".lp" && it->is_regular_file(ec)) names.push_back(p.filename().string());
  }
  std::sort(names.begin(), names.end());
  return names.empty() ? "" : names.front();
}

// The median image made viewable: camera-raw luminance is linear and would look black.
Image displayable(const Image& median, const ImageStack& lum) {
  return lum.transfer() == Transfer::Linear ? image::srgbEncode(median) : median;
}

}  // namespace

// ---- SphereDetection ----------------------------------------------------------------------

pipeline::StageInfo SphereDetectionStage::info() {
  // 2: the overlay numbers spheres from 1 and keeps its label inside the picture, so its bytes
  //    differ from version 1's for the same images
  // 3: the median is taken of the reduced images for the circle search and at full resolution
  //    only around the spheres (hrti/stack_median.h); the overlay is drawn on the reduced
  //    median, and PNG files are encoded with fixed Up filters and run-length deflate
  //    (src/image/png_encoder.h), so its bytes differ from version 2's
  // 4: PNG files compressed by libdeflate at level 1 (src/image/png_encoder.h)
  // 5: radii up to half the frame, and a circle is a sphere only if the images show a
  //    highlight moving in it (evidence, recorded); no darkness test (chrome spheres)
  // 6: circles searched and fitted in the stack's upper quartile (from four images), and the
  //    rim's confidence counts the edges within a pixel (1 % of the radius) of the circle
  pipeline::StageInfo info = pipeline::withOptions<hrti::SphereDetectionOptions>(
      {kComponent, "6",
       "Find the reflective spheres: circle Hough transform on the gradient of the stack's upper "
       "quartile, sub-pixel circle fit, highlights that move against the per-pixel median",
       pipeline::PlanSlot::LightsFromSpheres});
  info.outputs = [](const carrier::Step&) { return std::vector<std::string>{kSphereOverlay}; };
  info.reads = pipeline::alwaysReads({kLuminanceStack});
  return info;
}

void SphereDetectionStage::run(const carrier::Step& step, pipeline::Context& ctx,
                               carrier::Result& result) {
  const auto lum = ctx.get<ImageStack>(kLuminanceStack);
  hrti::SphereDetectionOptions options = hrti::SphereDetectionOptions::fromParameters(parametersOf(step));
  options.threads = ctx.settings.threads;
  // The reduced median of the stack is most of the work; the circle search follows it.
  ctx.progress("Sphere detection", 0);
  auto median = std::make_shared<hrti::StackMedian>(lum, options.coarseWidth, ctx.settings.threads);

  auto spheres = std::make_shared<Spheres>();
  const auto manual = step.interventionsOfKind("manual-sphere");
  if (!manual.empty()) {
    for (const carrier::Intervention* i : manual) {
      const std::vector<double> v = numbers(i->value, 3, "manual sphere");
      // Checked here too, not only on the command line: a recorded carrier (re-execution) or
      // a standing decision meets images of another size than it was given for.
      const std::string why = sphereCircleProblem(v[0], v[1], v[2], median->width(), median->height());
      if (!why.empty())
        throw Error(ErrorKind::Input, "sphere " + i->target + " given by hand (" + i->value + ")",
                    "sphere detection", why + "; give the sphere's circle again with --sphere CX,CY,R");
      spheres->push_back(hrti::DetectedSphere{v[0], v[1], v[2], 1.0, 1.0});
      ctx.carrier.addLog("intervention", step.id,
                         "sphere " + i->target + " set by hand to " + i->value + ": " + i->reason, i->who);
    }
  } else {
    ctx.progress("Sphere detection", 0.6);
    try {
      // The rim in an upper quantile of the stack (hrti/sphere_detection.h); with fewer than four
      // images that is nearly the brightest, which keeps the highlights: the median then.
      if (lum->size() >= 4) {
        const hrti::StackMedian rim(lum, options.coarseWidth, ctx.settings.threads, hrti::StackMedian::kCoarseBudget,
                                    hrti::kRimQuantile);
        *spheres = hrti::detectSpheres(*median, rim, options);
      } else {
        *spheres = hrti::detectSpheres(*median, options);
      }
    } catch (const Error& e) {
      // Last in the list of what to do: a dome capture's own light file, when there is one.
      const std::string lp = lightFileInCapture(ctx.capture);
      if (lp.empty() || e.kind() != ErrorKind::Input) throw;
      throw Error(ErrorKind::Input, e.file(), e.step(),
                  e.message() + "; the capture has a light file, " + lp + ": if its lights are this capture's, "
                  "use them instead of spheres with --lp " + lp);
    }
  }
  for (std::size_t k = 0; k < spheres->size(); ++k) {
    const hrti::DetectedSphere& s = (*spheres)[k];
    result.add("sphere").set("index", static_cast<int>(k)).set("cx", s.cx).set("cy", s.cy)
        .set("r", s.r).set("confidence", s.confidence).set("evidence", s.evidence)
        .set("source", manual.empty() ? "detected" : "manual");
  }
  result.add("value").set("name", "spheres").set("value", std::to_string(spheres->size()));

  const std::string& overlay = kSphereOverlay;
  writePicture(ctx, hrti::drawSphereOverlay(displayable(median->coarse(), *lum), *spheres, median->factor()),
               overlay);
  recordOutput(ctx, step, result, overlay, "assembly", "PNG", "sphere-overlay", "image/png");
  ctx.put(kSpheres, spheres);
  ctx.put(kStackMedian, median);
  ctx.progress("Sphere detection", 1);
}

// ---- HighlightDetection -------------------------------------------------------------------

namespace {

std::string confidenceText(double c) { return fixedDecimals(c, 2); }

// Up to `most` items joined by "; ", then "and N more".
std::string listed(const std::vector<std::string>& items, std::size_t most = 6) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < most; ++i) out += (i ? "; " : "") + items[i];
  if (items.size() > most) out += "; and " + std::to_string(items.size() - most) + " more";
  return out;
}

// A sphere on which most images (more than half, and at least kSphereRefusals) show no
// trustworthy highlight is not a sphere: a circle given by hand in the wrong place, or a
// detection that found something else.
constexpr std::size_t kSphereRefusals = 3;
void refuseSphereWithoutHighlights(const carrier::Step& sphereStep, const hrti::DetectedSphere& s, std::size_t k,
                                   const std::vector<std::string>& refused, std::size_t images) {
  const std::string counted = "shows no trustworthy highlight in " + std::to_string(refused.size()) + " of " +
                              std::to_string(images) + " images (" + listed(refused, 3) + ")";
  const std::string circle = fixedDecimals(s.cx, 1) + "," + fixedDecimals(s.cy, 1) + "," + fixedDecimals(s.r, 1);
  for (const carrier::Intervention* i : sphereStep.interventionsOfKind("manual-sphere")) {
    if (i->target != std::to_string(k)) continue;
    throw Error(ErrorKind::Input, "--sphere " + i->value, "highlight detection",
                "the circle given by hand for sphere " + std::to_string(k) + " " + counted +
                    ": it is probably not where the sphere is in the images. Give the sphere's circle "
                    "again, as it appears in the images, with --sphere CX,CY,R --reason \"...\", or "
                    "withdraw it with --forget-sphere " + std::to_string(k) +
                    " --reason \"...\" to let Surrogate find the sphere. (If the circle is right, these "
                    "images show no highlight: leave them out with --exclude or give their highlights by "
                    "hand with --highlight.)");
  }
  throw Error(ErrorKind::Input, "sphere " + std::to_string(k) + " at " + circle, "highlight detection",
              "the circle found for sphere " + std::to_string(k) + " " + counted +
                  ": it is probably not a sphere. Give the sphere's circle by hand with --sphere CX,CY,R "
                  "--reason \"...\", or restrict the search to the sphere with --sphere-roi X,Y,W,H. (If "
                  "the circle is right, these images show no highlight: leave them out with --exclude or "
                  "give their highlights by hand with --highlight.)");
}

}  // namespace

pipeline::StageInfo HighlightDetectionStage::info() {
  // 2: every highlight judged (confidence, reason, refused flags), refusals stop the run
  // 3: the overview labels each highlight with its image's file name (it numbered them by
  //    position among the processed images), larger and kept inside the picture
  // 4: PNG files encoded with fixed Up filters and run-length deflate (src/image/png_encoder.h)
  // 5: PNG files compressed by libdeflate at level 1 (src/image/png_encoder.h)
  // 6: the highlight is the core of the image's rise above the stack's median (blurred), not
  //    the spot nearest the centre; specks and streaks refused by compactness and roundness
  pipeline::StageInfo info = pipeline::withOptions<hrti::HighlightOptions>(
      {kComponent, "6",
       "Find the specular highlight on each sphere in each image: the peak of the image's rise "
       "above the stack's median, blurred; the weighted centroid of its core",
       pipeline::PlanSlot::LightsFromSpheres});
  info.outputs = [](const carrier::Step&) { return std::vector<std::string>{highlightOverview("*")}; };
  info.reads = pipeline::alwaysReads({kLuminanceStack, kInputImages, kSpheres, kStackMedian});
  return info;
}

void HighlightDetectionStage::run(const carrier::Step& step, pipeline::Context& ctx,
                                  carrier::Result& result) {
  const auto lum = ctx.get<ImageStack>(kLuminanceStack);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const auto spheres = ctx.get<Spheres>(kSpheres);
  const auto median = ctx.get<hrti::StackMedian>(kStackMedian);
  const hrti::HighlightOptions options = hrti::HighlightOptions::fromParameters(parametersOf(step));
  ctx.progress("Highlight detection", 0);
  auto highlights = std::make_shared<Highlights>(
      hrti::detectHighlights(*lum, *spheres, options, ctx.settings.threads, median.get()));

  // Manual highlights: target "IMAGE:SPHERE" (sphere index from 0), value "x,y".
  for (const carrier::Intervention* i : step.interventionsOfKind("manual-highlight")) {
    const auto colon = i->target.rfind(':');
    const std::string name = colon == std::string::npos ? i->target : i->target.substr(0, colon);
    const int sphere = colon == std::string::npos ? 0 : std::atoi(i->target.c_str() + colon + 1);
    const std::string stem = fs::path(name).stem().string();
    auto it = std::find_if(inputs->begin(), inputs->end(),
                           [&](const InputImage& in) { return in.stem == stem || in.stem == name; });
    if (it == inputs->end() || sphere < 0 || sphere >= static_cast<int>(spheres->size()))
      throw Error(ErrorKind::Usage, i->target, "highlight detection",
                  "a manual highlight names an image or sphere that is not processed");
    const std::vector<double> v = numbers(i->value, 2, "manual highlight");
    const hrti::DetectedSphere& on = (*spheres)[sphere];
    const std::string why =
        highlightPointProblem(v[0], v[1], lum->width(), lum->height(), SphereCircle{on.cx, on.cy, on.r});
    if (!why.empty())
      throw Error(ErrorKind::Input, "highlight of " + i->target + " given by hand (" + i->value + ")",
                  "highlight detection", why + "; give it again with --highlight " + i->target + "=X,Y");
    hrti::Highlight& h = (*highlights)[it - inputs->begin()][sphere];
    h.x = v[0];
    h.y = v[1];
    h.flag = hrti::HighlightFlag::Manual;
    h.confidence = 1;
    h.reason = "given by hand: " + i->reason;
    ctx.carrier.addLog("intervention", step.id,
                       "highlight of " + i->target + " set by hand to " + i->value + ": " + i->reason, i->who);
  }

  // The record: every highlight with its flag, confidence and, when refused or doubtful, why.
  std::vector<std::string> unusable;  // images without any usable highlight, with why
  std::vector<const InputImage*> unusableImages;
  std::vector<std::vector<std::string>> refusedOn(spheres->size());  // per sphere
  for (std::size_t n = 0; n < inputs->size(); ++n) {
    const InputImage& in = (*inputs)[n];
    bool usable = false;
    std::vector<std::string> why;
    for (std::size_t k = 0; k < spheres->size(); ++k) {
      const hrti::Highlight& h = (*highlights)[n][k];
      carrier::DataItem& item = result.add("highlight");
      item.set("image", in.fileId).set("sphere", static_cast<int>(k)).set("x", h.x).set("y", h.y)
          .set("flag", hrti::flagName(h.flag)).set("peak", h.peak).set("components", h.components)
          .set("confidence", h.confidence);
      if (!h.reason.empty()) item.set("reason", h.reason);
      const std::string on = spheres->size() > 1 ? " on sphere " + std::to_string(k) : "";
      if (hrti::isUsable(h.flag)) {
        usable = true;
        if (h.flag == hrti::HighlightFlag::Multiple)
          ctx.carrier.addLog("warning", step.id, in.relativePath + ": several strong highlights" + on +
                             "; the one nearest the centre was used (confidence " + confidenceText(h.confidence) +
                             "), check the highlight overview");
        else if (h.flag == hrti::HighlightFlag::Ok && h.confidence < 0.5)
          ctx.carrier.addLog("warning", step.id, in.relativePath + ": the highlight" + on + " has confidence " +
                             confidenceText(h.confidence) + " only; check it on the highlight overview");
      } else {
        refusedOn[k].push_back(in.stem);
        why.push_back(std::string(hrti::flagName(h.flag)) + on + ": " + h.reason);
      }
    }
    if (!usable) {
      unusable.push_back(in.relativePath + " (" + listed(why, 2) + ")");
      unusableImages.push_back(&in);
    } else if (!why.empty()) {
      ctx.carrier.addLog("warning", step.id, in.relativePath + ": no trustworthy highlight " + listed(why, 2) +
                         "; its light comes from the other sphere(s)");
    }
  }
  // Highlights labelled by the image's file name, as every table of the report names them.
  std::vector<std::string> imageLabels;
  for (const InputImage& in : *inputs) imageLabels.push_back(in.stem);
  // Only the sphere's surroundings of the median are read, at full resolution.
  const hrti::MedianCrop crop = [&](const hrti::Rect& r) { return displayable(median->window(r), *lum); };
  for (std::size_t k = 0; k < spheres->size(); ++k) {
    std::vector<hrti::Highlight> perImage;
    for (const auto& row : *highlights) perImage.push_back(row[k]);
    const std::string overview = highlightOverview(std::to_string(k + 1));
    writePicture(ctx,
                 hrti::drawHighlightOverview(median->width(), median->height(), crop, (*spheres)[k], perImage,
                                             imageLabels),
                 overview);
    recordOutput(ctx, step, result, overview, "assembly", "PNG", "highlight-overview", "image/png");
  }

  // Refused by default: never a confident light direction from a highlight that is not one.
  const carrier::Step* sphereStep = nullptr;
  for (const carrier::Step& s : ctx.carrier.process)
    if (s.component == SphereDetectionStage::kComponent) sphereStep = &s;
  for (std::size_t k = 0; k < spheres->size(); ++k)
    if (2 * refusedOn[k].size() > inputs->size() && refusedOn[k].size() >= kSphereRefusals && sphereStep)
      refuseSphereWithoutHighlights(*sphereStep, (*spheres)[k], k, refusedOn[k], inputs->size());
  if (!unusable.empty()) {
    const bool one = unusable.size() == 1;
    const std::string& stem = unusableImages.front()->stem;
    throw Error(ErrorKind::Input, one ? unusableImages.front()->relativePath : "", "highlight detection",
                (one ? std::string("this image has") : std::to_string(unusable.size()) + " images have") +
                    " no trustworthy highlight on any sphere, so " + (one ? "its" : "their") +
                    " light direction cannot be measured: " + listed(unusable, 8) + ". Leave each out with "
                    "--exclude " + stem + " --reason \"...\", or give its highlight by hand with --highlight " +
                    stem + ":0=X,Y --reason \"...\" (X,Y in pixels of the full frame)");
  }
  ctx.put(kHighlights, highlights);
  ctx.progress("Highlight detection", 1);
}

// ---- LightDirections ----------------------------------------------------------------------

namespace {

// A number as a message shows it: "50", "0.006", "1e+20".
std::string shown(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// The lengths of LightDirectionsOptions: each name once, with the option that sets it.
struct Length {
  const char* name;
  double LightDirectionsOptions::*field;
  const char* option;
};
constexpr Length kLengths[] = {
    {"focalLengthMm", &LightDirectionsOptions::focalLengthMm, "--focal-length"},
    {"pixelPitchMm", &LightDirectionsOptions::pixelPitchMm, "--pixel-pitch"},
    {"sphereDiameterMm", &LightDirectionsOptions::sphereDiameterMm, "--sphere-diameter"},
};
constexpr const char* kModelParameter = "model";

const Length& lengthOf(double LightDirectionsOptions::*field) {
  for (const Length& l : kLengths)
    if (l.field == field) return l;
  throw Error(ErrorKind::Internal, "", "light directions", "not a length of LightDirectionsOptions");
}

// Camera intrinsics from the options, else from the first image's EXIF.
std::optional<hrti::CameraIntrinsics> intrinsicsFor(const LightDirectionsOptions& options, pipeline::Context& ctx,
                                                    const InputImages& inputs, const ImageStack& stack) {
  double focal = options.focalLengthMm;
  double pitch = options.pixelPitchMm;
  const carrier::FileRecord* f = ctx.carrier.findFile(inputs.front().fileId);
  auto cam = [&](const char* key) -> std::optional<double> {
    for (const auto& [k, v] : f->camera) {
      if (k != key) continue;
      char* end = nullptr;
      const double d = std::strtod(v.c_str(), &end);
      if (!v.empty() && end == v.c_str() + v.size() && std::isfinite(d)) return d;
    }
    return std::nullopt;
  };
  if (focal <= 0) focal = cam("focalLengthMm").value_or(0);
  if (pitch <= 0) {
    const auto resolution = cam("focalPlaneXResolution");
    const auto unit = cam("focalPlaneResolutionUnit").value_or(2);  // EXIF: 2 inch, 3 cm, 4 mm
    const double unitMm = unit == 3 ? 10.0 : unit == 4 ? 1.0 : 25.4;
    if (resolution && *resolution > 0) pitch = unitMm / *resolution;
  }
  if (focal <= 0 || pitch <= 0) return std::nullopt;
  return hrti::CameraIntrinsics{focal, pitch, (stack.width() - 1) / 2.0, (stack.height() - 1) / 2.0};
}

// Writes assembly-files/lights.lp. Like every .lp, it names the images relative to its own
// folder ("../original-captures/IMG_0001.dng"), as RTIBuilder and relight expect; the names
// are made from the capture-relative paths alone, lexically, so the file's bytes do not
// depend on where the capture is (the verifier re-executes elsewhere and compares hashes).
void writeLights(pipeline::Context& ctx, const carrier::Step& step, carrier::Result& result,
                 const InputImages& inputs, const Lights& lights) {
  std::vector<formats::LightEntry> entries;
  for (std::size_t n = 0; n < inputs.size(); ++n) {
    const std::string name =
        fs::path(inputs[n].relativePath).lexically_relative(capture::kAssemblyDir).generic_string();
    entries.push_back({name, lights[n][0], lights[n][1], lights[n][2]});
  }
  const std::string& lp = kLightsFile;
  formats::writeLp(ctx.outputPath(lp), entries);
  recordOutput(ctx, step, result, lp, "assembly", "LP", "lp", "text/plain");
}

void addLightItem(carrier::Result& result, const std::string& fileId, const std::array<double, 3>& l,
                  const std::string& source) {
  const double elevation = std::asin(std::clamp(l[2], -1.0, 1.0)) * 180.0 / M_PI;
  const double azimuth = std::atan2(l[1], l[0]) * 180.0 / M_PI;
  result.add("light").set("image", fileId).set("x", l[0]).set("y", l[1]).set("z", l[2])
      .set("elevationDeg", elevation).set("azimuthDeg", azimuth).set("source", source);
}

// What to do about a failed check on the lights: leave out the images it names, or correct
// the circles used (which it gives).
std::string lightCheckFix(const hrti::LightCheck& c, const hrti::LightCheckInput& input) {
  if (!c.images.empty() && c.name == hrti::kCheckExposureOutlier) return excludeImagesFix(c, input.names);
  std::string circles;
  for (std::size_t k = 0; k < input.spheres.size(); ++k)
    circles += (k ? ", " : "") + std::to_string(k) + " at " + fixedDecimals(input.spheres[k].cx, 0) + "," +
               fixedDecimals(input.spheres[k].cy, 0) + " radius " + fixedDecimals(input.spheres[k].r, 0);
  return "the spheres used are " + circles + " (CX,CY in pixels of the full frame); if a circle is wrong, give "
         "the sphere's circle with --sphere CX,CY,R --reason \"...\" or restrict the search to it with "
         "--sphere-roi X,Y,W,H";
}

}  // namespace

pipeline::Parameters LightDirectionsOptions::toParameters() const {
  pipeline::Parameters p = {modelParameter()};
  for (const Length& l : kLengths) p.push_back(parameter(l.field));
  return p;
}

std::pair<std::string, std::string> LightDirectionsOptions::modelParameter() const {
  return {kModelParameter, model};
}

std::pair<std::string, std::string> LightDirectionsOptions::parameter(double LightDirectionsOptions::*length) const {
  return {lengthOf(length).name, formatNumber(this->*length)};
}

LightDirectionsOptions LightDirectionsOptions::fromParameters(const pipeline::Parameters& parameters) {
  LightDirectionsOptions o;
  for (const auto& [name, value] : parameters) {
    if (name == kModelParameter) {
      if (value != "orthographic" && value != "perspective")
        throw Error(ErrorKind::Usage, value, "light directions", "unknown light model; use orthographic or perspective");
      o.model = value;
      continue;
    }
    const Length* length = nullptr;
    for (const Length& l : kLengths)
      if (name == l.name) length = &l;
    if (!length)
      throw Error(ErrorKind::Input, name + "=" + value, "light directions",
                  "is not a parameter of LightDirections (model, focalLengthMm, pixelPitchMm, "
                  "sphereDiameterMm)");
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(v) || v < 0)
      throw Error(ErrorKind::Input, name + "=" + value, "light directions",
                  std::string("is not a length in millimetres (a finite number above 0); give ") +
                      length->option + " MM");
    o.*(length->field) = v;
  }
  return o;
}

pipeline::StageInfo LightDirectionsStage::info() {
  // 2: lights.lp names images relative to its own folder
  // 3: lights.lp holds each component as the shortest text that reads back exactly (it had six
  //    decimals), so the file's bytes differ from version 2's for the same lights
  // 4: the lights are checked (hrti/light_checks.h) and a failed check stops the run unless
  //    accepted (intervention accept-check); the checks are recorded
  // 5: exposure-outlier compares exposures in linear light (it compared sRGB values, and let a
  //    frame at 5 % exposure through)
  pipeline::StageInfo info = pipeline::withOptions<LightDirectionsOptions>(
      {kComponent, "5",
       "Light direction of each image from its highlights by the law of reflection, checked for "
       "plausibility",
       pipeline::PlanSlot::LightsFromSpheres});
  info.outputs = lightsFileOutput;
  info.reads = pipeline::alwaysReads({kLuminanceStack, kInputImages, kSpheres, kHighlights, kStackMedian});
  return info;
}

void LightDirectionsStage::run(const carrier::Step& step, pipeline::Context& ctx,
                               carrier::Result& result) {
  const auto lum = ctx.get<ImageStack>(kLuminanceStack);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const auto spheres = ctx.get<Spheres>(kSpheres);
  const auto highlights = ctx.get<Highlights>(kHighlights);
  const LightDirectionsOptions options = LightDirectionsOptions::fromParameters(parametersOf(step));
  const std::string& model = options.model;
  const auto intrinsics = intrinsicsFor(options, ctx, *inputs, *lum);
  if (model == "perspective" && !intrinsics)
    throw Error(ErrorKind::Usage, ctx.carrier.findFile(inputs->front().fileId)->path, "light directions",
                "the perspective light model needs the focal length and the sensor's pixel pitch, and "
                "the image's EXIF does not give them; add --focal-length MM and --pixel-pitch MM");
  result.add("value").set("name", "model").set("value", model);
  const double diameter = options.sphereDiameterMm;

  auto lights = std::make_shared<Lights>();
  hrti::LightCheckInput checks;
  for (std::size_t n = 0; n < inputs->size(); ++n) {
    std::array<double, 3> sum{0, 0, 0};
    std::string from;
    checks.perSphere.emplace_back(spheres->size());
    for (std::size_t k = 0; k < spheres->size(); ++k) {
      const hrti::Highlight& h = (*highlights)[n][k];
      if (!hrti::isUsable(h.flag)) continue;
      const hrti::LightDirection l =
          model == "perspective" ? hrti::lightFromHighlightPerspective((*spheres)[k], h.x, h.y, *intrinsics)
                                 : hrti::lightFromHighlight((*spheres)[k], h.x, h.y);
      // Never a NaN in the record: a direction that is not a number comes from the values it
      // was computed with (a lens so long the rays are parallel to machine precision).
      if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z))
        throw Error(ErrorKind::Input, (*inputs)[n].relativePath, "light directions",
                    "the " + model + " light model gives no finite light direction for the highlight at (" +
                        fixedDecimals(h.x, 2) + ", " + fixedDecimals(h.y, 2) + ") on sphere " + std::to_string(k) +
                        (model == "perspective"
                             ? " with focal length " + shown(intrinsics->focalLengthMm) +
                                   " mm (focalLengthMm, --focal-length) and pixel pitch " +
                                   shown(intrinsics->pixelPitchMm) +
                                   " mm (pixelPitchMm, --pixel-pitch); check both"
                             : std::string("; check the sphere's circle and the highlight")));
      sum[0] += l.x;
      sum[1] += l.y;
      sum[2] += l.z;
      checks.perSphere.back()[k] = std::array<double, 3>{l.x, l.y, l.z};
      from += (from.empty() ? "sphere " : ",") + std::to_string(k);
    }
    const double norm = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (from.empty() || norm == 0) {
      throwInputError((*inputs)[n].relativePath, "light directions",
                      "has no usable highlight on any sphere, so its light direction is unknown; "
                      "exclude it (--exclude " + (*inputs)[n].stem + " --reason ...) or give its "
                      "highlight by hand (--highlight " + (*inputs)[n].stem + ":0=x,y --reason ...)");
    }
    lights->push_back({sum[0] / norm, sum[1] / norm, sum[2] / norm});
    addLightItem(result, (*inputs)[n].fileId, lights->back(), from);

    if (spheres->size() >= 2 && diameter > 0 && intrinsics) {
      std::vector<hrti::SphereGeometry> geometry;
      std::vector<hrti::Highlight> perSphere;
      for (std::size_t k = 0; k < spheres->size(); ++k) {
        if (!hrti::isUsable((*highlights)[n][k].flag)) continue;
        geometry.push_back({(*spheres)[k], diameter});
        perSphere.push_back((*highlights)[n][k]);
      }
      if (geometry.size() >= 2) {
        const hrti::LightPosition p = hrti::lightPositionFromSpheres(geometry, perSphere, *intrinsics);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.residualMm))
          throw Error(ErrorKind::Input, (*inputs)[n].relativePath, "light directions",
                      "the light's position is not a finite point with sphere diameter " +
                          shown(diameter) + " mm (sphereDiameterMm, --sphere-diameter), "
                          "focal length " + shown(intrinsics->focalLengthMm) +
                          " mm and pixel pitch " + shown(intrinsics->pixelPitchMm) +
                          " mm; check these values");
        result.add("lightPosition").set("image", (*inputs)[n].fileId).set("x", p.x).set("y", p.y)
            .set("z", p.z).set("residualMm", p.residualMm).set("nearParallel", p.nearParallel ? "true" : "false");
      }
    }
  }
  checks.lights = *lights;
  checks.spheres = *spheres;
  // exposure-outlier compares exposures, so values in linear light: a frame at 5 % of the
  // others' exposure has 29 % of their mean and a highlight at 52 % of their peak in sRGB.
  const hrti::StackMedian& median = *ctx.get<hrti::StackMedian>(kStackMedian);
  auto linear = [&median](double v) {
    return toLinear(static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 1.0) * 65535)), median.transfer());
  };
  for (double m : median.imageMeans()) checks.imageMeans.push_back(linear(m));
  for (const auto& row : *highlights) {
    double peak = 0;
    for (const hrti::Highlight& h : row)
      if (hrti::isUsable(h.flag) && h.flag != hrti::HighlightFlag::Manual) peak = std::max(peak, h.peak);
    checks.highlightPeaks.push_back(peak > 0 ? linear(peak) : 0);
  }
  for (const InputImage& in : *inputs) checks.names.push_back(in.stem);
  recordChecks(step, ctx, result, hrti::checkLights(checks),
               {"light checks", "the light directions", "they cannot be trusted"},
               [&](const hrti::LightCheck& c) { return lightCheckFix(c, checks); });
  writeLights(ctx, step, result, *inputs, *lights);
  ctx.put(kLights, lights);
}

// ---- LightsFromFile -----------------------------------------------------------------------

pipeline::StageInfo LightsFromFileStage::info() {
  // 2: lights.lp names images relative to its own folder
  // 3: lights.lp holds each component as the shortest text that reads back exactly (it had six
  //    decimals), so the file's bytes differ from version 2's for the same lights
  pipeline::StageInfo info = pipeline::withOptions<pipeline::NoOptions>(
      {kComponent, "3", "Light directions given by the capture's .lp file", pipeline::PlanSlot::LightsFromFile});
  info.outputs = lightsFileOutput;
  info.reads = pipeline::alwaysReads({kInputImages});
  return info;
}

void LightsFromFileStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const carrier::FileRecord* lpRecord = nullptr;
  for (const carrier::FileRecord& f : ctx.carrier.files)
    if (f.role == "lp") lpRecord = &f;
  if (!lpRecord)
    throwInputError(ctx.capture.string(), "lights from file", "has no .lp file to read the lights from");
  const fs::path lpPath = ctx.capture / lpRecord->path;
  // Lines are paired with shots by formats::matchLpLines (name, then letter case, then
  // extension; ambiguity refused), among every shot of the capture, excluded ones too, so that
  // an excluded shot's line never lights another shot whose name differs only by case.
  const std::vector<formats::LightEntry> lines = formats::readLp(lpPath);
  std::vector<std::string> stems;
  for (const carrier::FileRecord& f : ctx.carrier.files)
    if (f.role == "original" || f.role == "export") stems.push_back(fs::path(f.path).stem().string());
  for (const InputImage& in : *inputs) stems.push_back(in.stem);
  std::sort(stems.begin(), stems.end());
  stems.erase(std::unique(stems.begin(), stems.end()), stems.end());
  const formats::LpMatch match = formats::matchLpLines(lpPath.string(), lines, stems);
  result.add("input").set("file", lpRecord->id).set("kind", "lp");
  auto lights = std::make_shared<Lights>();
  for (const InputImage& in : *inputs) {
    const auto shot = std::lower_bound(stems.begin(), stems.end(), in.stem) - stems.begin();
    const auto line = match.lineOfImage[static_cast<std::size_t>(shot)];
    if (!line)
      throwInputError(lpPath.string(), "lights from file",
                      "gives no light for " + in.relativePath + "; add a line for it or exclude the image");
    const formats::LightEntry& e = lines[*line];
    const std::array<double, 3> light = {e.x, e.y, e.z};
    lights->push_back(light);
    addLightItem(result, in.fileId, light, "lp");
  }
  ctx.carrier.addLog("info", step.id, "light directions read from " + lpRecord->path +
                     " (dome capture): sphere and highlight detection skipped");
  writeLights(ctx, step, result, *inputs, *lights);
  ctx.put(kLights, lights);
}

}  // namespace surrogate::stages
