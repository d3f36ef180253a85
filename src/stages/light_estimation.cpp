#include "stages/light_estimation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "formats/lp.h"
#include "image/decode.h"
#include "stages/outputs.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

const std::string kLightsFile = std::string(capture::kAssemblyDir) + "/lights.lp";

}  // namespace

const std::string kLightsDomeFile = std::string(capture::kAssemblyDir) + "/lights.dome";

std::vector<std::string> lightsFileOutput(const carrier::Step&) { return {kLightsFile, kLightsDomeFile}; }

std::vector<double> recordedNumbers(const std::string& text, std::size_t count,
                                    const std::string& what) {
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

Image displayable(const Image& median, const ImageStack& lum) {
  return lum.transfer() == Transfer::Linear ? image::srgbEncode(median) : median;
}

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

void writeLightsDome(pipeline::Context& ctx, const carrier::Step& step, carrier::Result& result,
                     const InputImages& inputs, const Lights& lights, const LightPlaces& places) {
  if (!places.anyNear()) return;
  const double w = places.frameWidth;
  std::vector<double> distances;
  for (const LightPlace& p : places.lights)
    if (p.near) distances.push_back(std::hypot(p.position[0], p.position[1], p.position[2]));
  std::sort(distances.begin(), distances.end());
  const double median = distances[distances.size() / 2];
  auto xyz = [](JsonWriter& j, double x, double y, double z) {
    j.beginObject().key("x").value(x).key("y").value(y).key("z").value(z).endObject();
  };
  JsonWriter j;
  j.beginObject().key("label").value("lights of " + inputs.front().relativePath + " and the others, by Surrogate")
      .key("notes").value("positions in pixels of the full frame (imageWidth), origin at the frame's centre on the "
                          "object's plane, x right, y up, z towards the camera; a light at infinity is put at " +
                          formatNumber(kFarLightWidths) + " frame widths")
      .key("imageWidth").value(w).key("domeDiameter").value(2 * median).key("verticalOffset").value(0.0)
      .key("lightConfiguration").value("lights3d").key("directions").beginArray();
  for (const auto& l : lights) xyz(j, l[0], l[1], l[2]);
  j.endArray().key("positionsSphere").beginArray();
  for (const auto& l : lights) xyz(j, l[0] * median, l[1] * median, l[2] * median);
  j.endArray().key("positions3d").beginArray();
  for (std::size_t n = 0; n < lights.size(); ++n) {
    const LightPlace& p = places.lights[n];
    const double far = kFarLightWidths * w;
    if (p.near) xyz(j, p.position[0], p.position[1], p.position[2]);
    else xyz(j, lights[n][0] * far, lights[n][1] * far, lights[n][2] * far);
  }
  j.endArray().key("ledAdjust").beginArray().endArray().endObject();
  writeFileAtomically(ctx.outputPath(kLightsDomeFile), j.str() + "\n");
  recordOutput(ctx, step, result, kLightsDomeFile, "assembly", "relight dome", "dome", "application/json");
}

void addLightItem(carrier::Result& result, const std::string& fileId, const std::array<double, 3>& l,
                  const std::string& source, double uncertaintyDeg) {
  const double elevation = std::asin(std::clamp(l[2], -1.0, 1.0)) * 180.0 / M_PI;
  const double azimuth = std::atan2(l[1], l[0]) * 180.0 / M_PI;
  result.add("light").set("image", fileId).set("x", l[0]).set("y", l[1]).set("z", l[2])
      .set("elevationDeg", elevation).set("azimuthDeg", azimuth).set("source", source);
  if (uncertaintyDeg >= 0) result.items.back().set("uncertaintyDegrees", uncertaintyDeg);
}

}  // namespace surrogate::stages
