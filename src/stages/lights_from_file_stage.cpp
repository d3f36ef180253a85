#include "stages/lights_from_file_stage.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <memory>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/lp.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/light_directions_stage.h"
#include "stages/light_estimation.h"
#include "stages/outputs.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

pipeline::Parameters LightsFromFileOptions::toParameters() const { return {{"lightDistance", lightDistance}}; }

LightsFromFileOptions LightsFromFileOptions::fromParameters(const pipeline::Parameters& parameters) {
  LightsFromFileOptions o;
  for (const auto& [name, value] : parameters) {
    if (name != "lightDistance")
      throw Error(ErrorKind::Input, name + "=" + value, "lights from file",
                  "is not a parameter of LightsFromFile (lightDistance)");
    const StatedDistance d = StatedDistance::parse(value, "lightDistance");
    if (d.kind == StatedDistance::Kind::Millimetres)
      throw Error(ErrorKind::Usage, "--light-distance " + value, "lights from file",
                  "is a length, and a dome capture has no spheres to give the frame's scale: give the dome's "
                  "radius in frame widths (the radius over the width the frame covers on the object), e.g. "
                  "--light-distance 2.5");
    o.lightDistance = value;
  }
  return o;
}

pipeline::StageInfo LightsFromFileStage::info() {
  // 2: lights.lp names images relative to its own folder
  // 3: lights.lp holds each component as the shortest text that reads back exactly (it had six
  //    decimals), so the file's bytes differ from version 2's for the same lights
  // 4: parameter lightDistance: the dome's radius stated, each light placed at it (nearLight)
  pipeline::StageInfo info = pipeline::withOptions<LightsFromFileOptions>(
      {kComponent, "4", "Light directions given by the capture's .lp file", pipeline::PlanSlot::LightsFromFile});
  info.outputs = lightsFileOutput;
  info.reads = pipeline::alwaysReads({kInputImages, kStackFrame});
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
  // The dome's radius stated: every light on the dome, at that distance from the frame's centre
  // along its direction, as relight-cli -3 places them.
  const LightsFromFileOptions options = LightsFromFileOptions::fromParameters(parametersOf(step));
  const StatedDistance stated = StatedDistance::parse(options.lightDistance, "lightDistance");
  auto places = std::make_shared<LightPlaces>();
  if (ctx.has(kStackFrame)) {
    const StackFrame& frame = *ctx.get<StackFrame>(kStackFrame);
    places->frameWidth = frame.fullWidth;
    places->frameHeight = frame.fullHeight;
  }
  if (stated.kind == StatedDistance::Kind::FrameWidths && places->frameWidth > 0) {
    const double d = stated.value * places->frameWidth;
    for (std::size_t n = 0; n < inputs->size(); ++n) {
      const auto& l = (*lights)[n];
      const double norm = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
      LightPlace place{true, {d * l[0] / norm, d * l[1] / norm, d * l[2] / norm}};
      if (!(place.position[2] > 0))
        throwInputError(lpPath.string(), "lights from file",
                        "gives " + (*inputs)[n].relativePath + " a light at or below the object's plane, which a dome "
                        "of stated radius cannot place; check its line");
      places->lights.push_back(place);
      result.add("nearLight").set("image", (*inputs)[n].fileId).set("x", place.position[0])
          .set("y", place.position[1]).set("z", place.position[2]).set("distance", stated.value)
          .set("source", "stated-distance");
    }
    ctx.carrier.addLog("info", step.id,
                       "light positions: the " + std::to_string(inputs->size()) + " lights on a dome of radius " +
                           formatNumber(stated.value) + " frame widths; the fit gives each pixel its own light "
                           "direction and brings its values to the frame centre's light (inverse square)");
    writeLightsDome(ctx, step, result, *inputs, *lights, *places);
  } else {
    places->lights.assign(inputs->size(), LightPlace{});
  }
  ctx.put(kLights, lights);
  ctx.put(kLightPlaces, places);
}

}  // namespace surrogate::stages
