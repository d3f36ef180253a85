#include "stages/light_estimation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "capture/capture.h"
#include "core/error.h"
#include "formats/lp.h"
#include "image/decode.h"
#include "stages/outputs.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

const std::string kLightsFile = std::string(capture::kAssemblyDir) + "/lights.lp";

}  // namespace

std::vector<std::string> lightsFileOutput(const carrier::Step&) { return {kLightsFile}; }

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

void addLightItem(carrier::Result& result, const std::string& fileId, const std::array<double, 3>& l,
                  const std::string& source, double uncertaintyDeg) {
  const double elevation = std::asin(std::clamp(l[2], -1.0, 1.0)) * 180.0 / M_PI;
  const double azimuth = std::atan2(l[1], l[0]) * 180.0 / M_PI;
  result.add("light").set("image", fileId).set("x", l[0]).set("y", l[1]).set("z", l[2])
      .set("elevationDeg", elevation).set("azimuthDeg", azimuth).set("source", source);
  if (uncertaintyDeg >= 0) result.items.back().set("uncertaintyDegrees", uncertaintyDeg);
}

}  // namespace surrogate::stages
