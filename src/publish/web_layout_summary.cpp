// describeWebLayout (publish/web_layout.h): reading an info.json back.
#include <cmath>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "publish/info_json.h"
#include "publish/layout_files.h"
#include "publish/web_layout.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void missing(const std::string& file, const std::string& what) {
  throw Error(ErrorKind::Input, file, "info",
              "is not a web layout's info.json: " + what + " (docs/formats.md, \"The web layout\")");
}

JsonValue member(const JsonValue& o, const std::string& key, JsonValue::Kind kind, const std::string& file) {
  const std::optional<JsonValue> v = o.find(key);
  if (!v || v->kind() != kind) missing(file, "it has no \"" + key + "\" of the right kind");
  return *v;
}

int wholeNumber(const JsonValue& o, const std::string& key, const std::string& file, int min, int max) {
  const double v = member(o, key, JsonValue::Kind::Number, file).number();
  if (v != std::floor(v) || v < min || v > max)
    missing(file, "\"" + key + "\" is not a whole number from " + std::to_string(min) + " to " + std::to_string(max));
  return static_cast<int>(v);
}

std::string basisName(const WebLayoutSummary& s) {
  if (s.type == "ptm" && s.colorspace == "lrgb" && s.nplanes == 9) return "ptm-lrgb";
  if (s.type == "ptm" && s.colorspace == "rgb" && s.nplanes == 18) return "ptm-rgb";
  if (s.type == "hsh" && s.colorspace == "rgb" && s.nplanes == 12) return "hsh2";
  if (s.type == "hsh" && s.colorspace == "rgb" && s.nplanes == 27) return "hsh3";
  // Learned bases (learned_reader.h): a JPEG holds three coefficients, so planes come in threes.
  if (s.colorspace == "mrgb" && s.nplanes % 3 == 0 && s.type == "rbf") return "rbf";
  if (s.colorspace == "mrgb" && s.nplanes % 3 == 0 && s.type == "bilinear") return "bln";
  return "";
}

// The "mycc" colour space counts its planes per channel ("yccplanes": three numbers).
int yccPlanes(const JsonValue& info, const std::string& file) {
  const JsonValue list = member(info, "yccplanes", JsonValue::Kind::Array, file);
  if (list.size() != 3) missing(file, "\"yccplanes\" is not three plane counts");
  double n = 0;
  for (const JsonValue& v : list.items()) n += v.kind() == JsonValue::Kind::Number ? v.number() : 0;
  if (n != std::floor(n) || n < 1 || n > 3 * 1024) missing(file, "\"yccplanes\" is not three plane counts");
  return static_cast<int>(n);
}

void checkMaterial(const JsonValue& info, int nplanes, const std::string& file) {
  const JsonValue materials = member(info, "materials", JsonValue::Kind::Array, file);
  const JsonValue first = materials.item(0);
  if (first.kind() != JsonValue::Kind::Object) missing(file, "\"materials\" holds no object");
  for (const char* key : {"scale", "bias"}) {
    const JsonValue list = member(first, key, JsonValue::Kind::Array, file);
    if (list.size() != static_cast<std::size_t>(nplanes))
      missing(file, std::string("\"") + key + "\" has " + std::to_string(list.size()) + " values for " +
                        std::to_string(nplanes) + " planes");
    for (const JsonValue& v : list.items())
      if (v.kind() != JsonValue::Kind::Number) missing(file, std::string("\"") + key + "\" holds a value that is not a number");
  }
}
// A plane in one of the tiled forms the viewers also read: Deep Zoom (plane_j.dzi) or
// relight's tarzoom (plane_j.tzi); its tiles are not counted.
bool tiledPlane(const fs::path& folder, int j, std::string* tiles) {
  std::error_code ec;
  const std::string stem = "plane_" + std::to_string(j);
  if (fs::exists(folder / (stem + ".dzi"), ec)) *tiles = "deepzoom";
  else if (fs::exists(folder / (stem + ".tzi"), ec)) *tiles = "tarzoom";
  else return false;
  return true;
}
}  // namespace

WebLayoutSummary describeWebLayout(const fs::path& infoJson) {
  const std::string file = infoJson.string();
  // Never through a link, and no larger than any info.json (publish/layout_files.h).
  std::string text = readLayoutFile(infoJson, kMaxInfoJsonBytes, "info");
  const JsonValue info = readJsonObject(text, file);
  const std::uintmax_t size = text.size();
  std::string().swap(text);
  WebLayoutSummary s;
  s.type = member(info, "type", JsonValue::Kind::String, file).text();
  s.colorspace = member(info, "colorspace", JsonValue::Kind::String, file).text();
  s.width = wholeNumber(info, "width", file, 1, 1 << 20);
  s.height = wholeNumber(info, "height", file, 1, 1 << 20);
  s.nplanes = info.find("nplanes") ? wholeNumber(info, "nplanes", file, 1, 3 * 1024) : yccPlanes(info, file);
  if (info.find("quality")) s.quality = wholeNumber(info, "quality", file, 1, 100);
  s.format = info.find("format") ? member(info, "format", JsonValue::Kind::String, file).text() : "jpg";
  checkMaterial(info, s.nplanes, file);
  s.basis = basisName(s);
  if (s.type == "bilinear" && info.find("resolution")) {
    s.resolution = wholeNumber(info, "resolution", file, 2, 256);
    s.nodes = s.resolution * s.resolution;
  }
  if (s.type == "rbf")
    if (const std::optional<JsonValue> lights = info.find("lights"); lights && lights->kind() == JsonValue::Kind::Array)
      s.nodes = static_cast<int>(lights->size() / 3);
  s.bytes = size;
  for (int j = 0; j * 3 < s.nplanes; ++j) {
    const std::string name = "plane_" + std::to_string(j) + "." + s.format;
    s.planes.push_back(name);
    const fs::path plane = infoJson.parent_path() / name;
    std::error_code pe;
    const std::uintmax_t bytes = fs::file_size(plane, pe);
    if (!pe) {
      s.bytes += bytes;
    } else if (!tiledPlane(infoJson.parent_path(), j, &s.tiles)) {
      s.missingPlanes.push_back(name);
    }
  }
  return s;
}

}  // namespace surrogate::publish
