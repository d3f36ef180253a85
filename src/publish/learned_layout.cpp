#include "publish/learned_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "publish/deep_zoom.h"
#include "publish/rgb_jpeg.h"

namespace surrogate::publish {

namespace {
const char* const kStep = "publish";
const char* const kModel = "the learned model";

// The largest side a baseline JPEG can describe (libjpeg's JPEG_MAX_DIMENSION).
constexpr int kMaxJpegSide = 65500;
constexpr int kMinTileSize = 16, kMaxTileSize = 4096;

[[noreturn]] void badModel(const std::string& what) {
  throw Error(ErrorKind::Input, kModel, kStep, what + "; it cannot be published (fit it again)");
}

// 9 significant digits: the shortest count that reads back as the same float for every float.
std::string floatText(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(v));
  return buffer;
}

// relight's precision for the light directions (QString::number(v, 'f', 3)); "-0.000" as 0.
std::string lightText(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", v);
  const std::string s = buffer;
  return s == "-0.000" ? "0.000" : s;
}

void checkModel(const fit::LearnedModel& m) {
  if (m.width < 1 || m.height < 1) badModel("has no texels");
  if (m.width > kMaxJpegSide || m.height > kMaxJpegSide)
    badModel("is " + std::to_string(m.width) + "x" + std::to_string(m.height) +
             " texels; a JPEG plane holds at most 65500 on a side");
  if (m.planes < 3 || m.planes % 3 != 0) badModel("has " + std::to_string(m.planes) + " planes, not a multiple of 3");
  if (m.kind == fit::LearnedKind::Bilinear && m.resolution < 2) badModel("has a bilinear grid of side below 2");
  if (m.kind == fit::LearnedKind::Rbf && m.lights.empty()) badModel("has no lights for its rbf nodes");
  const auto p = static_cast<std::size_t>(m.planes);
  const std::size_t basis = (p + 1) * static_cast<std::size_t>(m.nodes()) * 3;
  if (m.basis.size() != basis)
    badModel("holds " + std::to_string(m.basis.size()) + " basis bytes for " + std::to_string(basis));
  if (m.range.size() != p || m.scale.size() != p || m.bias.size() != p)
    badModel("has range, scale and bias of other lengths than its planes");
  if (m.coefficients.size() != static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height) * p)
    badModel("holds a number of coefficient bytes other than width x height x planes");
  for (std::size_t i = 0; i < p; ++i) {
    if (!std::isfinite(m.range[i]) || m.range[i] == 0) badModel("has a range of 0 or not finite");
    if (!std::isfinite(m.scale[i]) || !std::isfinite(m.bias[i])) badModel("has a scale or bias that is not finite");
  }
  for (const auto& l : m.lights)
    for (double v : l)
      if (!std::isfinite(v)) badModel("has a light that is not finite");
}

template <typename T, typename Format>
void numberList(std::string* out, const std::vector<T>& values, Format format) {
  *out += "[";
  for (std::size_t i = 0; i < values.size(); ++i) *out += (i ? "," : "") + format(values[i]);
  *out += "]";
}

// Plane image j: coefficients 3j, 3j + 1, 3j + 2 of every texel as its three components.
std::vector<std::uint8_t> planeImage(const fit::LearnedModel& m, int j) {
  const std::size_t texels = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height);
  const auto p = static_cast<std::size_t>(m.planes);
  std::vector<std::uint8_t> rgb(texels * 3);
  for (std::size_t t = 0; t < texels; ++t)
    for (std::size_t k = 0; k < 3; ++k) rgb[t * 3 + k] = m.coefficients[t * p + static_cast<std::size_t>(3 * j) + k];
  return rgb;
}
}  // namespace

std::vector<int> planeQualitiesOf(const PublishOptions& options, int jpegs) {
  std::vector<int> q = options.planeQualities;
  if (q.empty()) {
    const int last = options.lastQuality > 0 ? options.lastQuality : options.quality;
    for (int j = 0; j < jpegs; ++j)
      q.push_back(jpegs < 2 ? options.quality
                            : static_cast<int>(std::lround(options.quality + double(last - options.quality) * j / (jpegs - 1))));
  }
  if (q.size() != static_cast<std::size_t>(jpegs))
    throw Error(ErrorKind::Usage, "--quality", kStep,
                "gives " + std::to_string(q.size()) + " plane qualities for " + std::to_string(jpegs) +
                    " JPEG planes; give one per plane, or one quality for all");
  for (int v : q)
    if (v < 1 || v > 100)
      throw Error(ErrorKind::Usage, "--quality " + std::to_string(v), kStep, "needs a JPEG quality from 1 to 100");
  return q;
}

std::string learnedInfoJson(const fit::LearnedModel& m, int quality) {
  checkModel(m);
  const bool rbf = m.kind == fit::LearnedKind::Rbf;
  std::string j = "{\n\"width\": " + std::to_string(m.width) + ", \"height\": " + std::to_string(m.height) +
                  ",\n\"format\": \"jpg\",\n\"type\": \"" + (rbf ? "rbf" : "bilinear") + "\",\n";
  if (!rbf) j += "\"resolution\": " + std::to_string(m.resolution) + ",\n";
  j += "\"colorspace\": \"mrgb\",\n";
  // relight's default; its own desktop renderer reads it, OpenLIME (whose weights Surrogate
  // fits, fit/learned.h) does not.
  if (rbf) j += "\"sigma\": 0.125,\n";
  if (!m.lights.empty()) {
    std::vector<double> flat;
    for (const auto& l : m.lights) flat.insert(flat.end(), l.begin(), l.end());
    j += "\"lights\": ";
    numberList(&j, flat, lightText);
    j += ",\n";
  }
  j += "\"nplanes\": " + std::to_string(m.planes) + ",\n\"quality\": " + std::to_string(quality) + ",\n\"basis\": [";
  // One node's three bytes at a time, a plane to a line: readable, and a few kilobytes.
  const std::size_t perPlane = static_cast<std::size_t>(m.nodes()) * 3;
  for (std::size_t i = 0; i < m.basis.size(); ++i)
    j += (i == 0 ? "\n" : i % perPlane == 0 ? ",\n" : ",") + std::to_string(m.basis[i]);
  j += "],\n\"materials\": [{\n \"range\": ";
  numberList(&j, m.range, floatText);
  j += ",\n \"scale\": ";
  numberList(&j, m.scale, floatText);
  j += ",\n \"bias\": ";
  numberList(&j, m.bias, floatText);
  j += "\n}]\n}\n";
  return j;
}

WebLayoutFiles webLayoutOf(const fit::LearnedModel& model, const PublishOptions& options) {
  if (options.tileSize < kMinTileSize || options.tileSize > kMaxTileSize)
    throw Error(ErrorKind::Usage, "--tile-size " + std::to_string(options.tileSize), kStep,
                "needs a tile side from 16 to 4096 texels");
  checkModel(model);
  const int jpegs = model.planes / 3;
  const std::vector<int> qualities = planeQualitiesOf(options, jpegs);
  WebLayoutFiles out;
  PublishedModel& m = out.model;
  m.type = model.kind == fit::LearnedKind::Rbf ? "rbf" : "bilinear";
  m.colorspace = "mrgb";
  m.width = model.width;
  m.height = model.height;
  m.nplanes = model.planes;
  out.files.emplace_back("info.json", learnedInfoJson(model, *std::max_element(qualities.begin(), qualities.end())));
  const bool tiles = options.tiles == TileLayout::DeepZoom ||
                     (options.tiles == TileLayout::Auto && (m.width > kAutoTileSide || m.height > kAutoTileSide));
  if (tiles) {
    m.tiles = "deepzoom";
    m.levels = deepZoomLevelCount(m.width, m.height, options.tileSize);
  }
  for (int j = 0; j < jpegs; ++j) {
    const std::string stem = "plane_" + std::to_string(j);
    const int q = qualities[static_cast<std::size_t>(j)];
    if (tiles) {
      const PlaneRaster raster{m.width, m.height, planeImage(model, j)};
      for (auto& file : deepZoomFiles(raster, stem, options.tileSize, q, options.threads)) out.files.push_back(std::move(file));
    } else {
      out.files.emplace_back(stem + ".jpg", encodeRgbJpeg(planeImage(model, j), m.width, m.height, q));
    }
  }
  for (const auto& f : out.files) m.files.push_back(f.first);
  return out;
}

}  // namespace surrogate::publish
