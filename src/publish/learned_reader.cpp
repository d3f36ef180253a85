#include "publish/learned_reader.h"

#include <cmath>
#include <limits>
#include <optional>

#include "core/error.h"
#include "publish/info_json.h"
#include "publish/layout_files.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "render";
const char* const kWhatIsRead =
    "Surrogate reads learned layouts of type \"rbf\" (with \"lights\") or \"bilinear\" (with \"resolution\") in "
    "the colour space \"mrgb\", with nplanes a multiple of 3, a \"basis\" of (nplanes + 1) x nodes x 3 "
    "values 0..255 and materials[0] holding \"range\", \"scale\" and \"bias\" of nplanes numbers each";

[[noreturn]] void refuse(const fs::path& info, const std::string& what) {
  throw Error(ErrorKind::Input, info.string(), kStep, what + "; " + kWhatIsRead);
}

// The numbers of `key` in `object`: an array of exactly `count` finite numbers (any count when
// `count` is npos).
std::vector<double> numbers(const fs::path& info, const JsonValue& object, const std::string& key, std::size_t count) {
  const std::optional<JsonValue> v = object.find(key);
  if (!v || v->kind() != JsonValue::Kind::Array) refuse(info, "it has no array \"" + key + "\"");
  if (count != std::string::npos && v->size() != count)
    refuse(info, "\"" + key + "\" has " + std::to_string(v->size()) + " values where " + std::to_string(count) +
                     " are needed");
  std::vector<double> out;
  out.reserve(v->size());
  for (const JsonValue& item : v->items()) {
    if (item.kind() != JsonValue::Kind::Number || !std::isfinite(item.number()) ||
        std::fabs(item.number()) > std::numeric_limits<float>::max())
      refuse(info, "\"" + key + "\" holds a value that is not a finite number");
    out.push_back(item.number());
  }
  return out;
}

std::vector<float> floats(const std::vector<double>& v) { return {v.begin(), v.end()}; }

std::vector<std::array<double, 3>> lightsOf(const fs::path& info, const JsonValue& root, bool required) {
  if (!root.find("lights")) {
    if (required) refuse(info, "it is of type \"rbf\" and has no \"lights\", the nodes of its interpolation");
    return {};
  }
  const std::vector<double> flat = numbers(info, root, "lights", std::string::npos);
  if (flat.empty() || flat.size() % 3 != 0) refuse(info, "\"lights\" is not a list of x, y, z triples");
  std::vector<std::array<double, 3>> lights;
  for (std::size_t i = 0; i < flat.size(); i += 3) {
    lights.push_back({flat[i], flat[i + 1], flat[i + 2]});
    if (required && std::hypot(flat[i], flat[i + 1], flat[i + 2]) < 1e-6)
      refuse(info, "light " + std::to_string(i / 3) + " of \"lights\" is not a direction (0, 0, 0)");
  }
  return lights;
}
}  // namespace

fit::LearnedModel learnedModelOf(const fs::path& info, const WebLayoutSummary& s) {
  if (s.colorspace != "mrgb")
    refuse(info, "it is a learned layout (\"" + s.type + "\") in the colour space \"" + s.colorspace +
                     "\"" + (s.colorspace == "mycc" ? " (relight's luminance and chroma PCA)" : "") +
                     ", which render does not read: build it with the colour space mrgb");
  if (s.nplanes % 3 != 0)
    refuse(info, "\"nplanes\" is " + std::to_string(s.nplanes) + ", not a multiple of 3 (each JPEG holds three)");
  const JsonValue root = readJsonObject(readLayoutFile(info, kMaxInfoJsonBytes, kStep), info.string());
  fit::LearnedModel m;
  m.kind = s.type == "rbf" ? fit::LearnedKind::Rbf : fit::LearnedKind::Bilinear;
  m.width = s.width;
  m.height = s.height;
  m.planes = s.nplanes;
  m.lights = lightsOf(info, root, m.kind == fit::LearnedKind::Rbf);
  if (m.kind == fit::LearnedKind::Bilinear) {
    const std::optional<JsonValue> r = root.find("resolution");
    const double v = r && r->kind() == JsonValue::Kind::Number ? r->number() : 0;
    if (v != std::floor(v) || v < kMinLearnedResolution || v > kMaxLearnedResolution)
      refuse(info, "it is of type \"bilinear\" without a \"resolution\" (the grid's side) from 2 to 256");
    m.resolution = static_cast<int>(v);
  }
  const auto planes = static_cast<std::size_t>(m.planes);
  const std::size_t basisSize = (planes + 1) * static_cast<std::size_t>(m.nodes()) * 3;
  for (double b : numbers(info, root, "basis", basisSize)) {
    if (b != std::floor(b) || b < 0 || b > 255) refuse(info, "\"basis\" holds a value that is not a whole number 0..255");
    m.basis.push_back(static_cast<std::uint8_t>(b));
  }
  // describeWebLayout has checked that materials[0] is an object.
  const JsonValue material = root.find("materials")->item(0);
  m.range = floats(numbers(info, material, "range", planes));
  m.scale = floats(numbers(info, material, "scale", planes));
  m.bias = floats(numbers(info, material, "bias", planes));
  for (std::size_t p = 0; p < planes; ++p)
    if (m.range[p] == 0 || !std::isfinite(1.0f / m.range[p]))
      refuse(info, "materials[0].range[" + std::to_string(p) + "] is 0: the basis plane it divides cannot be decoded");
  return m;
}

void setLearnedCoefficients(const std::vector<std::vector<std::uint8_t>>& images, fit::LearnedModel* m) {
  const std::size_t texels = static_cast<std::size_t>(m->width) * static_cast<std::size_t>(m->height);
  const auto planes = static_cast<std::size_t>(m->planes);
  m->coefficients.assign(texels * planes, 0);
  for (std::size_t p = 0; p < planes; ++p) {
    const std::vector<std::uint8_t>& image = images[p / 3];
    for (std::size_t t = 0; t < texels; ++t) m->coefficients[t * planes + p] = image[t * 3 + p % 3];
  }
}

}  // namespace surrogate::publish
