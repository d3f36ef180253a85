#include "stages/lights_from_file_stage.h"

#include <algorithm>
#include <array>
#include <memory>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/lp.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/light_estimation.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

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
