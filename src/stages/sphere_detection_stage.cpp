#include "stages/sphere_detection_stage.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/sphere_reference.h"
#include "core/text.h"
#include "hrti/drawing.h"
#include "hrti/sphere_detection.h"
#include "hrti/stack_median.h"
#include "pipeline/context.h"
#include "stages/frame_checks.h"
#include "stages/inputs.h"
#include "stages/light_estimation.h"
#include "stages/outputs.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

// The file this stage writes: named once, for the stage and for its info() (what the plan
// will write, checked against prior work before a run).
const std::string kSphereOverlay = std::string(capture::kAssemblyDir) + "/spheres.png";

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

}  // namespace

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
  // 7: the overlay PNG carries an iTXt chunk (PNG 1.2, fmt/13) and its PRONOM identifier is
  //    recorded (formats/pronom.h); the pixels are the same
  // 8: the overlay labels a sphere given by hand "by hand", not "conf 1.00" (a confidence it
  //    did not earn), so its bytes differ from version 7's for such a sphere
  // 9: a circle given by hand that the frame's edge cuts is fitted to its visible rim (and may
  //    be larger than half the frame's smaller side when half its disc is inside); rays whose
  //    rim lies outside the frame are not searched for an edge
  pipeline::StageInfo info = pipeline::withOptions<hrti::SphereDetectionOptions>(
      {kComponent, "9",
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
  // The reduced median of the stack is most of the work; the circle search follows it. The
  // search finds the rim in an upper quantile of the stack (hrti/sphere_detection.h), made in the
  // same reading; with fewer than four images that is nearly the brightest, which keeps the
  // highlights: the median then.
  ctx.progress("Sphere detection", 0);
  const auto manual = step.interventionsOfKind("manual-sphere");
  std::shared_ptr<hrti::StackMedian> median, rim;
  if (manual.empty() && lum->size() >= 4)
    std::tie(median, rim) =
        hrti::StackMedian::medianAnd(lum, hrti::kRimQuantile, options.coarseWidth, ctx.settings.threads);
  else
    median = std::make_shared<hrti::StackMedian>(lum, options.coarseWidth, ctx.settings.threads);

  auto spheres = std::make_shared<Spheres>();
  if (!manual.empty()) {
    for (const carrier::Intervention* i : manual) {
      const std::vector<double> v = recordedNumbers(i->value, 3, "manual sphere");
      // Checked here too, not only on the command line: a recorded carrier (re-execution) or
      // a standing decision meets images of another size than it was given for.
      const std::string why = sphereCircleProblem(v[0], v[1], v[2], median->width(), median->height());
      if (!why.empty())
        throw Error(ErrorKind::Input, personsSphereTarget(i->target) + " given by hand (" + i->value + ")",
                    "sphere detection", why + "; give the sphere's circle again with --sphere CX,CY,R");
      hrti::DetectedSphere given{v[0], v[1], v[2], 1.0, 1.0, true};
      std::string fitted;
      if (v[0] - v[2] < 0 || v[1] - v[2] < 0 || v[0] + v[2] > median->width() - 1 || v[1] + v[2] > median->height() - 1) {
        // Cut by the frame's edge: fitted to its visible rim (hrti::fitVisibleRim). The fit is
        // kept when its rim is a clean edge and it stays within the margin searched of the circle
        // given; otherwise the circle stays as given, and the log says why.
        const hrti::StackMedian rim(lum, options.coarseWidth, ctx.settings.threads, hrti::StackMedian::kCoarseBudget,
                                    lum->size() >= 4 ? hrti::kRimQuantile : 0.5);
        const hrti::DetectedSphere f = hrti::fitVisibleRim(rim, given);
        const double margin = std::max(hrti::kGivenRimMargin, hrti::kGivenRimMarginShare * v[2]);
        const std::string share = std::to_string(static_cast<int>(
            std::lround(100 * discShareInFrame(v[0], v[1], v[2], median->width(), median->height()))));
        if (f.confidence >= options.minConfidence && std::hypot(f.cx - v[0], f.cy - v[1]) <= margin &&
            std::abs(f.r - v[2]) <= margin) {
          given = f;
          given.confidence = 1;  // by hand: the overlay and the record show no earned confidence
          fitted = "; " + share + " % of its disc in the frame, fitted to its visible rim: " +
                   fixedDecimals(f.cx, 2) + "," + fixedDecimals(f.cy, 2) + "," + fixedDecimals(f.r, 2) +
                   " (" + fixedDecimals(100 * f.confidence, 0) + " % of the visible rim on it)";
        } else {
          fitted = "; " + share + " % of its disc in the frame; its visible rim was not fitted (" +
                   fixedDecimals(100 * f.confidence, 0) + " % of it a clean edge near the circle): used as given";
        }
      }
      spheres->push_back(given);
      ctx.carrier.addLog("intervention", step.id,
                         personsSphereTarget(i->target) + " set by hand to " + i->value + ": " + i->reason + fitted, i->who);
    }
  } else {
    ctx.progress("Sphere detection", 0.6);
    try {
      *spheres = rim ? hrti::detectSpheres(*median, *rim, options) : hrti::detectSpheres(*median, options);
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
  // Drawn and encoded on one thread: work earlier steps left for later runs beside it.
  WrittenFile written;
  ctx.besideOneThread([&] {
    written = writePicture(
        ctx, hrti::drawSphereOverlay(displayable(median->coarse(), *lum), *spheres, median->factor()), overlay);
  });
  recordOutput(ctx, step, result, overlay, written, "assembly", "PNG", "sphere-overlay", "image/png");
  ctx.put(kSpheres, spheres);
  ctx.put(kStackMedian, median);
  ctx.progress("Sphere detection", 1);
}

}  // namespace surrogate::stages
