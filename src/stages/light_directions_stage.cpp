#include "stages/light_directions_stage.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "hrti/light_checks.h"
#include "hrti/light_direction.h"
#include "hrti/light_position.h"
#include "hrti/light_uncertainty.h"
#include "hrti/stack_median.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/light_estimation.h"
#include "stages/light_places.h"
#include "stages/outputs.h"
#include "stages/recorded_checks.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

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
constexpr const char* kLightDistanceParameter = "lightDistance";

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
  p.push_back(lightDistanceParameter());
  return p;
}

std::pair<std::string, std::string> LightDirectionsOptions::lightDistanceParameter() const {
  return {kLightDistanceParameter, lightDistance};
}

StatedDistance StatedDistance::parse(const std::string& text, const std::string& where) {
  StatedDistance d;
  if (text == "auto") return d;
  if (text == "infinity" || text == "inf") {
    d.kind = Kind::Infinity;
    return d;
  }
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  const std::string unit = end ? std::string(end) : std::string();
  const bool number = !text.empty() && end != text.c_str() && std::isfinite(v) && v > 0 &&
                      !std::isspace(static_cast<unsigned char>(text[0]));
  if (number && unit.empty() && v >= kMinLightDistanceWidths && v <= kMaxLightDistanceWidths) {
    d.kind = Kind::FrameWidths;
    d.value = v;
    return d;
  }
  const double mm = unit == "mm" ? 1 : unit == "cm" ? 10 : unit == "m" ? 1000 : 0;
  if (number && mm > 0 && v * mm >= 10 && v * mm <= 1e6) {
    d.kind = Kind::Millimetres;
    d.value = v * mm;
    return d;
  }
  throw Error(ErrorKind::Usage, where + " " + text, "light directions",
              "is not a light distance: give frame widths from the frame's centre (a number from " +
                  shown(kMinLightDistanceWidths) + " to " + shown(kMaxLightDistanceWidths) +
                  ", e.g. 3), a length with its unit (e.g. 1.2m, 80cm, 950mm; with --sphere-diameter), "
                  "infinity (every light a direction) or auto");
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
    if (name == kLightDistanceParameter) {
      StatedDistance::parse(value, "lightDistance");  // Error(Usage) naming it
      o.lightDistance = value;
      continue;
    }
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
                  "sphereDiameterMm, lightDistance)");
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
  // 6: each light records its uncertainty, uncertaintyDegrees (hrti/light_uncertainty.h), and
  //    the light checks are given it (LightCheckInput::uncertaintyDeg: lights-below-horizon's
  //    margin); exposure-outlier also compares each highlight's clipped area (a frame too bright)
  // 7: where the lights were (parameter lightDistance; light_places.h): two spheres place a
  //    light where their uncertainty allows, a stated distance places the others; a placed
  //    light's direction is the one from the frame's centre, recorded with a nearLight item
  pipeline::StageInfo info = pipeline::withOptions<LightDirectionsOptions>(
      {kComponent, "7",
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

  // Each image's light, its uncertainty (hrti/light_uncertainty.cpp: most of this step's time)
  // and its position are independent of the others': measured in parallel, each written at its
  // own index, then recorded in image order, so the results are the same at any thread count.
  // An error is the first image's in order, as when they were measured one after another.
  struct ImageLight {
    std::vector<std::optional<std::array<double, 3>>> perSphere;
    MeasuredLight measured;
    std::string from;
    double bound = 0;
    std::optional<hrti::LightPosition> position;
  };
  std::vector<ImageLight> images(inputs->size());
  const int threads = effectiveThreads(ctx.settings.threads);
  parallelFor(inputs->size(), 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t n = begin; n < end; ++n) {
      ImageLight& image = images[n];
      std::array<double, 3> sum{0, 0, 0};
      std::string& from = image.from;
      std::vector<hrti::SphereEvidence>& evidence = image.measured.evidence;
      image.perSphere.resize(spheres->size());
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
        image.perSphere[k] = std::array<double, 3>{l.x, l.y, l.z};
        evidence.push_back({(*spheres)[k], h});
        image.measured.perSphere.push_back({l.x, l.y, l.z});
        image.measured.sphereNumbers.push_back(static_cast<int>(k));
        from += (from.empty() ? "sphere " : ",") + std::to_string(k);
      }
      const double norm = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
      if (from.empty() || norm == 0) {
        throwInputError((*inputs)[n].relativePath, "light directions",
                        "has no usable highlight on any sphere, so its light direction is unknown; "
                        "exclude it (--exclude " + (*inputs)[n].stem + " --reason ...) or give its "
                        "highlight by hand (--highlight " + (*inputs)[n].stem + ":sphere1=x,y --reason ...)");
      }
      image.measured.direction = {sum[0] / norm, sum[1] / norm, sum[2] / norm};
      image.bound = hrti::lightUncertaintyDeg(evidence, model == "perspective" ? &*intrinsics : nullptr);

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
          image.position = p;
        }
      }
    }
  });
  auto lights = std::make_shared<Lights>();
  hrti::LightCheckInput checks;
  std::vector<MeasuredLight> measured(inputs->size());
  std::vector<std::string> sources;
  for (std::size_t n = 0; n < inputs->size(); ++n) {
    ImageLight& image = images[n];
    checks.perSphere.push_back(std::move(image.perSphere));
    lights->push_back(image.measured.direction);
    checks.uncertaintyDeg.push_back(image.bound);
    measured[n] = std::move(image.measured);
    sources.push_back(std::move(image.from));
    if (const auto& p = image.position)
      result.add("lightPosition").set("image", (*inputs)[n].fileId).set("x", p->x).set("y", p->y)
          .set("z", p->z).set("residualMm", p->residualMm).set("nearParallel", p->nearParallel ? "true" : "false");
  }
  // Where the lights were (light_places.h): a placed light's direction is the one from the
  // frame's centre, with its own bound.
  auto places = std::make_shared<LightPlaces>();
  {
    PlacedLights placed = placeLights(options, measured, *inputs, lum->width(), lum->height(), ctx.carrier,
                                      step.id, result, threads);
    for (std::size_t n = 0; n < inputs->size(); ++n) {
      (*lights)[n] = placed.directions[n];
      if (placed.uncertaintyDeg[n] >= 0) checks.uncertaintyDeg[n] = placed.uncertaintyDeg[n];
      for (std::size_t k = 0; k < placed.perSphereFromCentre[n].size(); ++k)
        checks.perSphere[n][static_cast<std::size_t>(measured[n].sphereNumbers[k])] = placed.perSphereFromCentre[n][k];
      addLightItem(result, (*inputs)[n].fileId, (*lights)[n], sources[n], checks.uncertaintyDeg[n]);
    }
    *places = std::move(placed.places);
  }
  checks.lights = *lights;
  checks.spheres = *spheres;
  // exposure-outlier compares exposures, so values in linear light: a frame at 5 % of the
  // others' exposure has 29 % of their mean and a highlight at 52 % of their peak in sRGB.
  const hrti::StackMedian& median = *ctx.get<hrti::StackMedian>(kStackMedian);
  auto linear = [&median](double v) { return linearOf(v, median.transfer()); };
  for (double m : median.imageMeans()) checks.imageMeans.push_back(linear(m));
  for (const auto& row : *highlights) {
    double peak = 0;
    for (const hrti::Highlight& h : row)
      if (hrti::isUsable(h.flag) && h.flag != hrti::HighlightFlag::Manual) peak = std::max(peak, h.peak);
    checks.highlightPeaks.push_back(peak > 0 ? linear(peak) : 0);
    double clipped = 0;
    for (const hrti::Highlight& h : row)
      if (hrti::isUsable(h.flag)) clipped = std::max(clipped, h.clippedArea);
    checks.clippedAreas.push_back(clipped);
  }
  for (const InputImage& in : *inputs) checks.names.push_back(in.stem);
  recordChecks(step, ctx, result, hrti::checkLights(checks),
               {"light checks", "the light directions", "they cannot be trusted"},
               [&](const hrti::LightCheck& c) { return lightCheckFix(c, checks); });
  writeLights(ctx, step, result, *inputs, *lights);
  writeLightsDome(ctx, step, result, *inputs, *lights, *places);
  ctx.put(kLights, lights);
  ctx.put(kLightPlaces, places);
}

}  // namespace surrogate::stages
