#include "run/request_checks.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/sphere_reference.h"
#include "core/text.h"
#include "stages/frame_checks.h"
#include "stages/highlight_detection_stage.h"
#include "stages/preprocess.h"
#include "stages/crop_stage.h"
#include "stages/resize_stage.h"
#include "stages/white_balance_stage.h"
#include "stages/sphere_detection_stage.h"

namespace surrogate::run {

using stages::CropOptions;
using stages::CropStage;
using stages::HighlightDetectionStage;
using stages::PixelRect;
using stages::ResizeOptions;
using stages::ResizeStage;
using stages::SphereCircle;
using stages::SphereDetectionStage;
using stages::WhiteBalanceOptions;
using stages::WhiteBalanceStage;
using stages::frameRegionProblem;
using stages::highlightPointProblem;
using stages::sphereCircleProblem;

namespace {

constexpr const char* kStep = "command line";

std::optional<std::vector<double>> numbers(const std::string& text, std::size_t count) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size()) return std::nullopt;
    out.push_back(v);
  }
  if (out.size() != count || (!text.empty() && text.back() == ',')) return std::nullopt;
  return out;
}

[[noreturn]] void usage(const std::string& option, const std::string& message) {
  throw Error(ErrorKind::Usage, option, kStep, message);
}

// The sphere index of a highlight's target "IMAGE:SPHERE" (0 when absent), -1 when malformed.
int sphereIndexOf(const std::string& target) {
  const auto colon = target.rfind(':');
  return colon == std::string::npos ? 0 : bareSphereIndex(target.substr(colon + 1)).value_or(-1);
}

}  // namespace

void checkRequestAgainstFrame(const RunRequest& request, int width, int height) {
  // Sphere search regions: "x,y,w,h;x,y,w,h".
  for (const RunRequest::StageParam& p : request.stageParams) {
    if (p.component != SphereDetectionStage::kComponent || p.name != "regions") continue;
    std::stringstream ss(p.value);
    for (std::string region; std::getline(ss, region, ';');) {
      if (region.empty()) continue;
      const std::string option = "--sphere-roi " + region;
      const auto v = numbers(region, 4);
      if (!v) usage(option, "needs 4 comma-separated numbers X,Y,W,H");
      const std::string why = frameRegionProblem((*v)[0], (*v)[1], (*v)[2], (*v)[3], width, height);
      if (!why.empty()) usage(option, why + "; give a region of the frame around the sphere");
    }
  }

  // Circles given by hand, in the order the sphere detection takes them (sphere 0, 1, ...).
  std::vector<SphereCircle> circles;
  for (const RunRequest::StageIntervention& s : request.stageInterventions) {
    if (s.component != SphereDetectionStage::kComponent || s.intervention.kind != "manual-sphere") continue;
    const std::string option = "--sphere " + s.intervention.value;
    const auto v = numbers(s.intervention.value, 3);
    if (!v) usage(option, "needs 3 comma-separated numbers CX,CY,R (pixels)");
    const std::string why = sphereCircleProblem((*v)[0], (*v)[1], (*v)[2], width, height);
    if (!why.empty())
      usage(option, why + "; give the sphere's circle as it appears in the images (CX,CY,R in pixels)");
    circles.push_back({(*v)[0], (*v)[1], (*v)[2]});
  }

  // Highlights given by hand: target "IMAGE:SPHERE", value "x,y".
  for (const RunRequest::StageIntervention& s : request.stageInterventions) {
    if (s.component != HighlightDetectionStage::kComponent || s.intervention.kind != "manual-highlight") continue;
    const int sphere = sphereIndexOf(s.intervention.target);
    const std::string option = "--highlight " + personsSphereTarget(s.intervention.target) + "=" + s.intervention.value;
    if (sphere < 0) usage(option, "needs the form IMAGE:sphereN=X,Y (sphere1 is the first sphere)");
    const auto v = numbers(s.intervention.value, 2);
    if (!v) usage(option, "needs 2 comma-separated numbers X,Y (pixels)");
    std::optional<SphereCircle> circle;
    if (!circles.empty()) {
      if (sphere >= static_cast<int>(circles.size()))
        usage(option, "names sphere " + std::to_string(sphere + 1) + ", but only " + std::to_string(circles.size()) +
                          " circle(s) are given by hand (--sphere): sphere1" +
                          (circles.size() > 1 ? " to " + sphereReference(static_cast<int>(circles.size()) - 1) : ""));
      circle = circles[sphere];
    }
    const std::string why = highlightPointProblem((*v)[0], (*v)[1], width, height, circle);
    if (!why.empty()) usage(option, why + "; give the highlight's X,Y in pixels of the full frame");
  }

  // Pre-processing rectangles, while they are still in full-frame pixels (before a crop or a
  // resize changes the images the later steps receive), and a resize while the size it
  // reduces is known (after a rectangle crop, not an automatic one). The stages check again.
  bool fullFrame = true;
  int w = width, h = height;  // of the images the next step receives; 0 when not known
  for (const PlannedStage& step : request.preprocessing) {
    if (step.component == WhiteBalanceStage::kComponent) {
      const WhiteBalanceOptions wb = WhiteBalanceOptions::fromParameters(step.params, "--wb");
      if (wb.mode == "region" && fullFrame) {
        const PixelRect& r = wb.region;
        const std::string why = frameRegionProblem(r.x, r.y, r.width, r.height, width, height);
        if (!why.empty()) usage("--wb-region " + r.text(), why + "; give a grey area of the frame");
      }
    } else if (step.component == CropStage::kComponent) {
      const CropOptions crop = CropOptions::fromParameters(step.params, "--crop");
      if (crop.method == "user" && fullFrame) {
        const PixelRect& r = crop.rect;
        const std::string why = frameRegionProblem(r.x, r.y, r.width, r.height, width, height);
        if (!why.empty()) usage("--crop " + r.text(), why + "; give a rectangle of the frame, or --crop auto");
      }
      w = crop.method == "user" ? crop.rect.width : 0;
      h = crop.method == "user" ? crop.rect.height : 0;
      fullFrame = false;
    } else if (step.component == ResizeStage::kComponent) {
      if (w > 0 && h > 0) {
        const auto [ow, oh] = ResizeOptions::fromParameters(step.params, "--resize").outputSize(w, h, "--resize");
        w = ow;
        h = oh;
      }
      fullFrame = false;
    } else {
      fullFrame = false;
      w = h = 0;
    }
  }
}

namespace {
// The name the user most likely meant for an image name that names no shot: the shot's file
// whose name differs from `given` only in case (with its extension when `given` has one, as
// the user typed it), else the nearest shot name.
std::optional<std::string> nearestImageName(const std::string& given, const capture::CaptureLayout& layout) {
  const std::string base = given.substr(given.find_last_of('/') == std::string::npos ? 0 : given.find_last_of('/') + 1);
  const bool withExtension = base.find('.') != std::string::npos;
  for (const capture::Shot& shot : layout.shots)
    for (const std::optional<capture::ImageFile>& f : {shot.original, shot.exported}) {
      if (!f) continue;
      const std::string file = f->relativePath.substr(f->relativePath.find_last_of('/') + 1);
      if (lowerCase(file) == lowerCase(base)) return file;
      if (!withExtension && lowerCase(shot.stem) == lowerCase(base)) return shot.stem;
    }
  std::vector<std::string> stems;
  for (const capture::Shot& shot : layout.shots) stems.push_back(shot.stem);
  const std::string stem = withExtension ? base.substr(0, base.rfind('.')) : base;
  return nearestName(stem, stems);
}
}  // namespace

void checkRequestNames(const RunRequest& request, const capture::CaptureLayout& layout) {
  for (const Exclusion& e : request.exclusions) {
    if (capture::findShotStem(layout, e.image)) continue;
    const std::optional<std::string> near = nearestImageName(e.image, layout);
    usage("--exclude " + escapedText(e.image),
          "names no image of the capture" + (near ? "; did you mean " + *near + "?" : std::string(".")) +
              " Give the file name as it is in original-captures/ or jpeg-exports/ (case matters), "
              "or the shot's name without its extension");
  }
  // Highlights given by hand: target "IMAGE:SPHERE"; the highlight detection finds the image
  // by the same rule, but only once the run is under way.
  for (const RunRequest::StageIntervention& s : request.stageInterventions) {
    if (s.component != HighlightDetectionStage::kComponent || s.intervention.kind != "manual-highlight") continue;
    const std::string& target = s.intervention.target;
    const std::string image = target.substr(0, target.rfind(':'));
    if (capture::findShotStem(layout, image)) continue;
    const std::optional<std::string> near = nearestImageName(image, layout);
    usage("--highlight " + escapedText(personsSphereTarget(target)) + "=" + escapedText(s.intervention.value),
          "names no image of the capture" + (near ? "; did you mean " + *near + "?" : std::string(".")) +
              " Give the image as its file or shot name (case matters), e.g. IMG_0004:sphere1=326,70");
  }
}

}  // namespace surrogate::run
