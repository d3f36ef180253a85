#include "stages/highlight_detection_stage.h"

#include "carrier/advice.h"
#include "core/sphere_reference.h"

#include <algorithm>
#include <cstdlib>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"
#include "hrti/drawing.h"
#include "hrti/frame_registration.h"
#include "hrti/highlight_consistency.h"
#include "hrti/highlight_detection.h"
#include "hrti/highlight_refusal.h"
#include "hrti/light_checks.h"
#include "hrti/stack_median.h"
#include "pipeline/context.h"
#include "stages/frame_checks.h"
#include "stages/inputs.h"
#include "stages/light_directions_stage.h"
#include "stages/light_estimation.h"
#include "stages/outputs.h"
#include "stages/recorded_checks.h"
#include "stages/sphere_detection_stage.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

// The last version that registered frames with cv::phaseCorrelate: its steps still run that way.
constexpr const char* kOpenCvCorrelationVersion = "11";

// The overview this stage writes for each sphere: named once, for the stage and for its
// info() (with "*" for the sphere).
std::string highlightOverview(const std::string& sphere) {
  return std::string(capture::kAssemblyDir) + "/highlights-sphere" + sphere + ".png";
}

std::string confidenceText(double c) { return fixedDecimals(c, 2); }

// Up to `most` items joined by "; ", then "and N more": for an image's reasons; frames are
// named in full (listedInFull).
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
                              std::to_string(images) + " images (" + listedInFull(refused, "; ") + ")";
  const std::string circle = fixedDecimals(s.cx, 1) + "," + fixedDecimals(s.cy, 1) + "," + fixedDecimals(s.r, 1);
  for (const carrier::Intervention* i : sphereStep.interventionsOfKind("manual-sphere")) {
    if (i->target != std::to_string(k)) continue;
    throw hrti::HighlightRefusal(
        Error(ErrorKind::Input, "--sphere " + i->value, "highlight detection",
              "the circle given by hand for sphere " + std::to_string(k + 1) + " " + counted +
                  ": it is probably not where the sphere is in the images. Give the sphere's circle "
                  "again, as it appears in the images, with --sphere CX,CY,R --reason \"...\", or "
                  "withdraw it with --forget-sphere " + sphereReference(static_cast<int>(k)) +
                  " --reason \"...\" to let Surrogate find the sphere. (If the circle is right, these "
                  "images show no highlight: leave them out with --exclude or give their highlights by "
                  "hand with --highlight.)"),
        hrti::HighlightRefusal::Subject::CircleByHand, k, refused, images);
  }
  throw hrti::HighlightRefusal(
      Error(ErrorKind::Input, "sphere " + std::to_string(k + 1) + " at " + circle, "highlight detection",
            "the circle found for sphere " + std::to_string(k + 1) + " " + counted +
                ": it is probably not a sphere. Give the sphere's circle by hand with --sphere CX,CY,R "
                "--reason \"...\", or restrict the search to the sphere with --sphere-roi X,Y,W,H. (If "
                "the circle is right, these images show no highlight: leave them out with --exclude or "
                "give their highlights by hand with --highlight.)"),
      hrti::HighlightRefusal::Subject::CircleFound, k, refused, images);
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
  // 7: the overview PNG carries an iTXt chunk (PNG 1.2, fmt/13) and its PRONOM identifier is
  //    recorded (formats/pronom.h); the pixels are the same
  // 8: the overview's labels never overlap (hrti::placeLabels): one crowded out of its place
  //    goes further out, joined to its highlight by a line, so the bytes differ from version 7's
  // 9: a clipped highlight's centre is the deepest point of its saturated plateau (a glare streak
  //    through it pulled the centroid 2 to 8 px on PSBox's light probes), and the core's centroid
  //    is weighted by the height above its edge: positions differ from version 8's
  // 10: each highlight judged against the other images (flags fixed and faint refused,
  //    hrti/highlight_consistency.h), and every frame registered to the stack: check frame-moved
  // 11: with the lights' distance stated (LightDirections' lightDistance), the faint rule brings
  //    each highlight's light to the sphere's median distance (a near flash on the far side of
  //    the frame gives a sphere less light, and was refused as faint)
  // 12: frame-moved's phase correlations by hrti/phase_correlation.h (the median's spectra
  //    computed once), not cv::phaseCorrelate: shifts and peaks differ in the last bits, and by
  //    half a pixel where a quarter's padded width or height is odd (cv::phaseCorrelate's offset);
  //    frame-moved's verdicts and pixels on the test captures unchanged. Version 11 steps are
  //    still run as they ran (cv::phaseCorrelate), so that records made before re-execute.
  pipeline::StageInfo info = pipeline::withOptions<hrti::HighlightOptions>(
      {kComponent, "12",
       "Find the specular highlight on each sphere in each image: the peak of the image's rise "
       "above the stack's median, blurred; the centroid of its core, or the deepest point of its "
       "saturated plateau when clipped",
       pipeline::PlanSlot::LightsFromSpheres});
  info.outputs = [](const carrier::Step&) { return std::vector<std::string>{highlightOverview("*")}; };
  info.reads = pipeline::alwaysReads({kLuminanceStack, kInputImages, kSpheres, kStackMedian});
  info.alsoRuns = {kOpenCvCorrelationVersion};
  return info;
}

namespace {

// The lights' distance the plan states (LightDirections' lightDistance, docs/hrti-math.md "Near
// lights") in pixels of the frame; 0 when none is stated (auto, infinity) or a length cannot be
// scaled (no sphere diameter). The faint rule corrects each highlight's light by it.
double statedLightDistancePx(const carrier::Carrier& plan, const Spheres& spheres, int width) {
  for (const carrier::Step& s : plan.process) {
    if (s.component != LightDirectionsStage::kComponent) continue;
    try {
      const LightDirectionsOptions o = LightDirectionsOptions::fromParameters(parametersOf(s));
      const StatedDistance d = StatedDistance::parse(o.lightDistance, "lightDistance");
      if (d.kind == StatedDistance::Kind::FrameWidths) return d.value * width;
      if (d.kind != StatedDistance::Kind::Millimetres || o.sphereDiameterMm <= 0 || spheres.empty()) return 0;
      double r = 0;
      for (const hrti::DetectedSphere& sphere : spheres) r += sphere.r / spheres.size();
      return d.value * 2 * r / o.sphereDiameterMm;
    } catch (const Error&) {
      return 0;  // LightDirections refuses its own parameters, naming them
    }
  }
  return 0;
}

}  // namespace

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
  // A spot that rises in the other images too, or is bright in most of them, is not this image's
  // highlight; one that rises far less than the others' highlights is not one either
  // (hrti/highlight_consistency.h). Exposures compared in linear light, like exposure-outlier's.
  std::vector<double> linearMeans;
  for (double m : median->imageMeans())
    linearMeans.push_back(linearOf(m, median->transfer()));
  hrti::judgeAcrossImages(*lum, *median, *spheres, *highlights, linearMeans, ctx.settings.threads,
                          statedLightDistancePx(ctx.carrier, *spheres, lum->width()));
  // Every frame registered to the stack (hrti/frame_registration.h): a frame that moved is named
  // as such before its highlight is judged, whatever its highlight looks like.
  std::vector<double> movedPx;
  const hrti::PhaseCorrelator correlator =
      step.version == kOpenCvCorrelationVersion ? hrti::PhaseCorrelator::OpenCv : hrti::PhaseCorrelator::Own;
  for (const hrti::FrameMotion& m : hrti::registerFrames(*lum, ctx.settings.threads, correlator))
    movedPx.push_back(m.measured ? m.largestPx : -1);

  // Manual highlights: target "IMAGE:SPHERE" (sphere index from 0), value "x,y".
  for (const carrier::Intervention* i : step.interventionsOfKind("manual-highlight")) {
    const auto colon = i->target.rfind(':');
    const std::string name = colon == std::string::npos ? i->target : i->target.substr(0, colon);
    const int sphere = colon == std::string::npos ? 0 : std::atoi(i->target.c_str() + colon + 1);
    const int image = inputIndexOf(*inputs, name);
    if (image < 0 || sphere < 0 || sphere >= static_cast<int>(spheres->size()))
      throw Error(ErrorKind::Usage, i->target, "highlight detection",
                  "a manual highlight names an image or sphere that is not processed");
    const std::vector<double> v = recordedNumbers(i->value, 2, "manual highlight");
    const hrti::DetectedSphere& on = (*spheres)[sphere];
    const std::string why =
        highlightPointProblem(v[0], v[1], lum->width(), lum->height(), SphereCircle{on.cx, on.cy, on.r});
    if (!why.empty())
      throw Error(ErrorKind::Input, "highlight of " + personsSphereTarget(i->target) + " given by hand (" + i->value + ")",
                  "highlight detection", why + "; give it again with --highlight " + personsSphereTarget(i->target) + "=X,Y");
    hrti::Highlight& h = (*highlights)[image][sphere];
    h.x = v[0];
    h.y = v[1];
    h.flag = hrti::HighlightFlag::Manual;
    h.confidence = 1;
    h.reason = "given by hand: " + i->reason;
    ctx.carrier.addLog("intervention", step.id,
                       "highlight of " + personsSphereTarget(i->target) + " set by hand to " + i->value + ": " + i->reason, i->who);
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
      // Spheres as people count them, from 1 (the overview files are highlights-sphere1.png...).
      const std::string on = spheres->size() > 1 ? " on sphere " + std::to_string(k + 1) : " on the sphere";
      const std::string overview = "look at it on the highlight overview (assembly-files/highlights-sphere" +
                                   std::to_string(k + 1) + ".png); if the wrong spot was taken, place the highlight "
                                   "in surrogate review (or with --highlight, see the user guide)";
      if (hrti::isUsable(h.flag)) {
        usable = true;
        if (h.flag == hrti::HighlightFlag::Multiple)
          carrier::addWarning(ctx.carrier, step.id,
                              {in.relativePath + ": several bright spots" + on +
                                   "; the one nearest the sphere's centre was taken as the flash's highlight",
                               carrier::Usable::WithCare,
                               "if another spot was the flash, this photograph's light direction is wrong", overview,
                               "confidence " + confidenceText(h.confidence)});
        else if (h.flag == hrti::HighlightFlag::Ok && h.confidence < 0.5)
          carrier::addWarning(ctx.carrier, step.id,
                              {in.relativePath + ": the highlight" + on + " is faint or unclear",
                               carrier::Usable::WithCare, "this photograph's light direction may be off", overview,
                               "confidence " + confidenceText(h.confidence) + ", below 0.5"});
      } else {
        refusedOn[k].push_back(in.stem);
        why.push_back(std::string(hrti::flagName(h.flag)) + (spheres->size() > 1 ? on : std::string()) + ": " + h.reason);
      }
    }
    if (!usable) {
      unusable.push_back(in.relativePath + " (" + listed(why, 2) + ")");
      unusableImages.push_back(&in);
    } else if (!why.empty()) {
      carrier::addWarning(ctx.carrier, step.id,
                          {in.relativePath + ": no trustworthy highlight on one of the spheres",
                           carrier::Usable::Yes, "its light direction comes from the other sphere(s)",
                           "nothing, unless the overview shows a clear highlight there: then place it in surrogate "
                           "review (or with --highlight)",
                           listed(why, 2)});
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
    // Drawn and encoded on one thread: work earlier steps left for later runs beside it.
    WrittenFile written;
    ctx.besideOneThread([&] {
      written = writePicture(ctx,
                             hrti::drawHighlightOverview(median->width(), median->height(), crop, (*spheres)[k],
                                                         perImage, imageLabels),
                             overview);
    });
    recordOutput(ctx, step, result, overview, written, "assembly", "PNG", "highlight-overview", "image/png");
  }

  // Refused by default: never a confident light direction from a highlight that is not one.
  const carrier::Step* sphereStep = nullptr;
  for (const carrier::Step& s : ctx.carrier.process)
    if (s.component == SphereDetectionStage::kComponent) sphereStep = &s;
  recordChecks(step, ctx, result, {hrti::frameMovedCheck(movedPx, hrti::movedLimitPx(lum->width()), imageLabels)},
               {"highlight detection", "the frames", "they do not show the same scene"},
               [&](const hrti::LightCheck& c) { return excludeImagesFix(c, imageLabels); });
  for (std::size_t k = 0; k < spheres->size(); ++k)
    if (2 * refusedOn[k].size() > inputs->size() && refusedOn[k].size() >= kSphereRefusals && sphereStep)
      refuseSphereWithoutHighlights(*sphereStep, (*spheres)[k], k, refusedOn[k], inputs->size());
  if (!unusable.empty()) {
    const bool one = unusable.size() == 1;
    const std::string& stem = unusableImages.front()->stem;
    std::vector<std::string> frames;
    for (const InputImage* in : unusableImages) frames.push_back(in->stem);
    throw hrti::HighlightRefusal(
        Error(ErrorKind::Input, one ? unusableImages.front()->relativePath : "", "highlight detection",
              (one ? std::string("this image has") : std::to_string(unusable.size()) + " images have") +
                  " no trustworthy highlight on any sphere, so " + (one ? "its" : "their") +
                  " light direction cannot be measured: " + listedInFull(unusable, "; ") + ". Leave each out with "
                  "--exclude " + stem + " --reason \"...\", or give its highlight by hand with --highlight " +
                  stem + ":sphere1=X,Y --reason \"...\" (X,Y in pixels of the full frame)"),
        hrti::HighlightRefusal::Subject::Frames, 0, frames, inputs->size());
  }
  ctx.put(kHighlights, highlights);
  ctx.progress("Highlight detection", 1);
}

}  // namespace surrogate::stages
