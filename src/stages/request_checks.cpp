#include "stages/request_checks.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "stages/light_stages.h"
#include "stages/preprocess.h"
#include "stages/preprocess_stages.h"

namespace surrogate::stages {

namespace {

constexpr const char* kStep = "command line";

// A number as a person wrote it: "45", "57.5", "-5".
std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string frameText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height) + " frame";
}

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
  if (colon == std::string::npos) return 0;
  const std::string digits = target.substr(colon + 1);
  if (digits.empty() || digits.size() > 6 ||
      !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
    return -1;
  return std::atoi(digits.c_str());
}

}  // namespace

std::string sphereCircleProblem(double cx, double cy, double r, int width, int height) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(r))
    return "CX, CY and R must be finite numbers (pixels)";
  if (r <= 0) return "the radius R is " + num(r) + "; it must be above 0";
  if (r < kMinSphereRadius)
    return "the radius R is " + num(r) + " pixels; a sphere needs a radius of at least " +
           num(kMinSphereRadius) + " pixels to show a highlight inside its rim";
  if (cx < 0 || cy < 0)
    return "the centre (" + num(cx) + ", " + num(cy) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (width <= 0 || height <= 0) return "";
  if (cx > width - 1 || cy > height - 1)
    return "the centre (" + num(cx) + ", " + num(cy) + ") is outside the " + frameText(width, height) +
           ": CX must be from 0 to " + std::to_string(width - 1) + " and CY from 0 to " +
           std::to_string(height - 1);
  const double largest = std::min(width, height) / 2.0;
  if (r > largest)
    return "the radius R is " + num(r) + " pixels, more than half the smaller side of the " +
           frameText(width, height) + " (" + num(largest) + " pixels): a sphere that size "
           "cannot be in the images";
  return "";
}

std::string highlightPointProblem(double x, double y, int width, int height,
                                  const std::optional<SphereCircle>& sphere) {
  if (!std::isfinite(x) || !std::isfinite(y)) return "X and Y must be finite numbers (pixels)";
  if (x < 0 || y < 0)
    return "the point (" + num(x) + ", " + num(y) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (width > 0 && height > 0 && (x > width - 1 || y > height - 1))
    return "the point (" + num(x) + ", " + num(y) + ") is outside the " + frameText(width, height) +
           ": X must be from 0 to " + std::to_string(width - 1) + " and Y from 0 to " +
           std::to_string(height - 1);
  if (sphere) {
    const double d = std::hypot(x - sphere->cx, y - sphere->cy);
    if (!(d <= sphere->r + 0.5))
      return "the point (" + num(x) + ", " + num(y) + ") is " + num(std::round(d * 10) / 10) +
             " pixels from the centre of its sphere's circle (" + num(sphere->cx) + "," +
             num(sphere->cy) + "," + num(sphere->r) + "): a highlight lies on the sphere, "
             "within its radius";
  }
  return "";
}

std::string frameRegionProblem(double x, double y, double w, double h, int width, int height) {
  constexpr double kLargest = 2147483647.0;
  for (const double v : {x, y, w, h})
    if (!std::isfinite(v) || v != std::floor(v) || std::abs(v) > kLargest)
      return "X, Y, W and H must be whole numbers of pixels";
  if (x < 0 || y < 0)
    return "the corner (" + num(x) + ", " + num(y) + ") has a negative coordinate; pixel "
           "coordinates start at 0 at the top-left pixel";
  if (w <= 0 || h <= 0) return "the width W and height H must be above 0";
  if (width > 0 && height > 0 && (x + w > width || y + h > height))
    return "the region reaches outside the " + frameText(width, height) + ": X+W must be at most " +
           std::to_string(width) + " and Y+H at most " + std::to_string(height);
  return "";
}

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
    const std::string option = "--highlight " + s.intervention.target + "=" + s.intervention.value;
    const int sphere = sphereIndexOf(s.intervention.target);
    if (sphere < 0) usage(option, "needs the form IMAGE:SPHERE=X,Y with SPHERE a number from 0");
    const auto v = numbers(s.intervention.value, 2);
    if (!v) usage(option, "needs 2 comma-separated numbers X,Y (pixels)");
    std::optional<SphereCircle> circle;
    if (!circles.empty()) {
      if (sphere >= static_cast<int>(circles.size()))
        usage(option, "names sphere " + std::to_string(sphere) + ", but the spheres are the " +
                          std::to_string(circles.size()) + " circle(s) given by hand (--sphere), "
                          "numbered from 0");
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

}  // namespace surrogate::stages
