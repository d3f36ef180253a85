#include "publish/web_reader.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "image/decode.h"
#include "publish/deep_zoom_reader.h"
#include "publish/info_json.h"
#include "publish/layout_files.h"
#include "publish/learned_reader.h"
#include "publish/plane_decode.h"
#include "publish/web_layout.h"
#include "publish/web_terms.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "render";

// The largest side a baseline JPEG can describe (libjpeg's JPEG_MAX_DIMENSION).
constexpr int kMaxJpegSide = 65500;
// A .ptm's web bias is its whole-number bias / 255: within this of a whole number after * 255
// it is one (17 significant digits written, far less lost).
constexpr double kWholeBiasTolerance = 1e-6;

[[noreturn]] void refuse(const fs::path& file, const std::string& message) {
  throw Error(ErrorKind::Input, file.string(), kStep, message);
}

fs::path infoJsonOf(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return path;
  if (!somethingAt(path / "info.json"))
    refuse(path, "is a folder without an info.json: give the folder `surrogate publish` wrote, or a .ptm or .rti file");
  return path / "info.json";
}

bool isLearnedType(const std::string& type) { return type == "rbf" || type == "bilinear"; }

// What render reads: the four bases Surrogate publishes, HSH order 4 as the same layout, and
// the learned bases (learned_reader.h, which says what is wrong with one it refuses).
void checkBasis(const WebLayoutSummary& s, const fs::path& info) {
  const bool hsh = s.type == "hsh" && s.colorspace == "rgb" && (s.nplanes == 12 || s.nplanes == 27 || s.nplanes == 48);
  if (s.basis.empty() && !hsh && !isLearnedType(s.type))
    refuse(info, "is a web layout of type \"" + s.type + "\", colour space \"" + s.colorspace + "\" with " +
                     std::to_string(s.nplanes) + " planes; render reads PTM (\"lrgb\", 9 planes, or \"rgb\", 18), "
                     "HSH (\"rgb\", 12 or 27 planes) and learned (\"rbf\" or \"bilinear\", \"mrgb\") layouts only");
  if (s.format != "jpg")
    refuse(info, "names planes in the format \"" + s.format +
                     "\"; render reads JPEG planes (\"format\": \"jpg\") only");
}

void checkSize(const WebLayoutSummary& s, const fs::path& info) {
  const std::uint64_t texels = static_cast<std::uint64_t>(s.width) * static_cast<std::uint64_t>(s.height);
  if (s.width > kMaxJpegSide || s.height > kMaxJpegSide || texels > image::kMaxImagePixels)
    refuse(info, "gives a size of " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " texels, beyond what render reads (65500 on a side, " +
                     std::to_string(image::kMaxImagePixels) + " texels): it is not a layout of a real model");
}

struct Material {
  std::vector<double> scale, bias;  // nplanes each, as info.json gives them
};

// describeWebLayout has checked that materials[0] holds nplanes numbers in each.
Material materialOf(const fs::path& info, int nplanes) {
  const JsonValue root = readJsonObject(readLayoutFile(info, kMaxInfoJsonBytes, kStep), info.string());
  const JsonValue first = root.find("materials")->item(0);
  Material m;
  const JsonValue scale = *first.find("scale"), bias = *first.find("bias");
  for (int p = 0; p < nplanes; ++p) {
    m.scale.push_back(scale.item(static_cast<std::size_t>(p)).number());
    m.bias.push_back(bias.item(static_cast<std::size_t>(p)).number());
  }
  return m;
}

// The largest file a plane of `texels` can be: at quality 100 pure noise takes under 1.5 bytes
// a value (plane_decode.h).
std::uintmax_t maxPlaneBytes(std::uintmax_t texels) { return texels * kMaxJpegBytesPerTexel + kJpegHeaderBytes; }

std::vector<std::uint8_t> readPlane(const fs::path& folder, const WebLayoutSummary& s, int j) {
  const fs::path file = folder / s.planes[static_cast<std::size_t>(j)];
  if (!somethingAt(file)) {
    const fs::path dzi = folder / ("plane_" + std::to_string(j) + ".dzi");
    if (somethingAt(dzi)) return readDeepZoomPlane(dzi, s.width, s.height);
    if (!s.tiles.empty())
      refuse(file, "is missing, and the plane is tiled only as " + s.tiles + ", which render does not read (it reads "
                   "whole planes, plane_N.jpg, and Deep Zoom tiles, plane_N.dzi)");
    refuse(file, "is missing: the layout's info.json names " + std::to_string(s.planes.size()) +
                     " planes; publish the model again");
  }
  const std::uintmax_t texels = static_cast<std::uintmax_t>(s.width) * static_cast<std::uintmax_t>(s.height);
  // Never through a link; too large, or too small to hold the plane's texels, refused before
  // anything is decoded (plane_decode.h).
  return decodePlaneJpeg(readLayoutFile(file, maxPlaneBytes(texels), kStep), s.width, s.height, file.string());
}

// What reading the layout takes at its peak (core/memory_budget.h), from what info.json
// declares: the decoded planes (three bytes a texel each) and the model made of them (as many
// bytes a texel as planes), libjpeg's coefficients of a progressive plane (six bytes a texel),
// the largest plane file read, and, when the terms are re-quantised, one term's values as
// doubles for every colour.
std::uint64_t layoutReadBytes(const WebLayoutSummary& s, const fs::path& folder, bool requantised,
                              const formats::ModelBudget& budget) {
  const std::uint64_t texels = static_cast<std::uint64_t>(s.width) * static_cast<std::uint64_t>(s.height);
  const auto nplanes = static_cast<std::uint64_t>(s.nplanes);
  std::uint64_t largestFile = 0;
  for (const std::string& name : s.planes) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(folder / name, ec);
    if (fs::is_regular_file(st))
      largestFile = std::max<std::uint64_t>(largestFile, std::min<std::uint64_t>(fs::file_size(folder / name, ec),
                                                                                 maxPlaneBytes(texels)));
  }
  return s.bytes + largestFile + texels * (2 * nplanes + 6 + (requantised ? 3 * 9 : 0) + budget.besidePerTexel);
}

// The decoded planes: plane p of texel t is images[p / 3][t * 3 + p % 3].
struct Planes {
  std::vector<std::vector<std::uint8_t>> images;
  std::size_t texels = 0;
  std::uint8_t byte(int p, std::size_t t) const {
    return images[static_cast<std::size_t>(p / 3)][t * 3 + static_cast<std::size_t>(p % 3)];
  }
};

// Coefficient p of texel t as the viewers compute it: (byte / 255 - bias) * scale.
double webCoefficient(const Planes& planes, const Material& m, int p, std::size_t t) {
  const auto i = static_cast<std::size_t>(p);
  return (planes.byte(p, t) / 255.0 - m.bias[i]) * m.scale[i];
}

bool sameForRgb(const Material& m, int first) {
  const auto i = static_cast<std::size_t>(first);
  return m.scale[i] == m.scale[i + 1] && m.scale[i] == m.scale[i + 2] && m.bias[i] == m.bias[i + 1] &&
         m.bias[i] == m.bias[i + 2];
}

// ---- PTM ----------------------------------------------------------------------------------

// The .ptm bias of a web bias (bias / 255 as Surrogate writes it), when it is a whole 0..255.
std::optional<int> ptmBias(double webBias) {
  const double b = webBias * 255.0, whole = std::round(b);
  if (std::fabs(b - whole) > kWholeBiasTolerance || whole < 0 || whole > 255) return std::nullopt;
  return static_cast<int>(whole);
}

bool ptmScale(double s) { return s == 0 || (std::isfinite(s) && std::fabs(s) >= 1e-12 && std::fabs(s) <= 1e12); }

// Web plane of PTM term j (viewer order) for colour c: LRGB planes 3..8 (one luminance),
// RGB plane 3j + c.
int ptmPlane(bool lrgb, int j, int c) { return lrgb ? 3 + j : 3 * j + c; }

bool ptmBytesCarryOver(const Material& m, bool lrgb) {
  if (lrgb)
    for (int p = 0; p < 3; ++p)
      if (m.scale[static_cast<std::size_t>(p)] != 1 || m.bias[static_cast<std::size_t>(p)] != 0) return false;
  for (int j = 0; j < 6; ++j) {
    const int p = ptmPlane(lrgb, j, 0);
    if ((!lrgb && !sameForRgb(m, p)) || !ptmBias(m.bias[static_cast<std::size_t>(p)]) ||
        !ptmScale(m.scale[static_cast<std::size_t>(p)]))
      return false;
  }
  return true;
}

// Where the byte of term k (.ptm order), colour c, texel t goes in PtmFile::coefficients.
std::size_t ptmIndex(const formats::PtmFile& ptm, int k, int c, std::size_t t) {
  return (static_cast<std::size_t>(c) * ptm.texels() + t) * 6 + static_cast<std::size_t>(k);
}

void copyPtmBytes(const Planes& planes, const Material& m, formats::PtmFile* ptm) {
  const bool lrgb = ptm->format == formats::PtmFile::Format::Lrgb;
  const int channels = lrgb ? 1 : 3;
  for (int j = 0; j < 6; ++j) {
    const int k = kWebPtmTerm[static_cast<std::size_t>(j)];
    const auto p0 = static_cast<std::size_t>(ptmPlane(lrgb, j, 0));
    ptm->scale[static_cast<std::size_t>(k)] = m.scale[p0];
    ptm->bias[static_cast<std::size_t>(k)] = *ptmBias(m.bias[p0]);
    for (int c = 0; c < channels; ++c)
      for (std::size_t t = 0; t < planes.texels; ++t)
        ptm->coefficients[ptmIndex(*ptm, k, c, t)] = planes.byte(ptmPlane(lrgb, j, c), t);
  }
}

// Quantises `values` (0..255 units) as a .ptm term: a = (byte - bias) * scale with a whole bias
// in 0..255, so the range held always contains 0; the error is at most half a step.
void quantisePtmTerm(const std::vector<double>& values, double* scale, int* bias, std::vector<std::uint8_t>* bytes) {
  const auto [lo_it, hi_it] = std::minmax_element(values.begin(), values.end());
  const double lo = std::min(0.0, *lo_it), hi = std::max(0.0, *hi_it);
  bytes->assign(values.size(), 0);
  *scale = 0;
  *bias = 0;
  if (hi - lo < 1e-9) return;  // all zero: scale 0 holds it
  *bias = static_cast<int>(std::lround(-lo / ((hi - lo) / 255.0)));
  double s = 0;
  if (*bias > 0) s = std::max(s, -lo / *bias);
  if (*bias < 255) s = std::max(s, hi / (255 - *bias));
  *scale = s;
  for (std::size_t i = 0; i < values.size(); ++i)
    (*bytes)[i] = static_cast<std::uint8_t>(std::clamp(std::lround(values[i] / s + *bias), 0L, 255L));
}

// Another tool's PTM layout: each term re-quantised over its range (all colours together, as
// a .ptm shares one scale and bias); an LRGB colour is stored as 0..255 (clamped).
void requantisePtm(const Planes& planes, const Material& m, formats::PtmFile* ptm) {
  const bool lrgb = ptm->format == formats::PtmFile::Format::Lrgb;
  const int channels = lrgb ? 1 : 3;
  const std::size_t n = planes.texels;
  if (lrgb)
    for (std::size_t t = 0; t < n; ++t)
      for (int c = 0; c < 3; ++c)
        ptm->rgb[t * 3 + static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>(std::clamp(std::lround(255.0 * webCoefficient(planes, m, c, t)), 0L, 255L));
  for (int j = 0; j < 6; ++j) {
    std::vector<double> values;
    values.reserve(n * static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c)
      for (std::size_t t = 0; t < n; ++t) values.push_back(255.0 * webCoefficient(planes, m, ptmPlane(lrgb, j, c), t));
    const int k = kWebPtmTerm[static_cast<std::size_t>(j)];
    std::vector<std::uint8_t> bytes;
    quantisePtmTerm(values, &ptm->scale[static_cast<std::size_t>(k)], &ptm->bias[static_cast<std::size_t>(k)], &bytes);
    for (int c = 0; c < channels; ++c)
      for (std::size_t t = 0; t < n; ++t)
        ptm->coefficients[ptmIndex(*ptm, k, c, t)] = bytes[static_cast<std::size_t>(c) * n + t];
  }
}

// The viewers' 0..1 values are a .ptm's 0..255 ones / 255: scale' = scale, bias' = bias / 255
// (docs/formats.md, "How Surrogate converts a model"), read here the other way.
formats::PtmFile ptmOf(const Planes& planes, const Material& m, const WebLayoutSummary& s, bool* requantised) {
  formats::PtmFile ptm;
  const bool lrgb = s.colorspace == "lrgb";
  ptm.format = lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb;
  ptm.width = s.width;
  ptm.height = s.height;
  ptm.coefficients.assign(planes.texels * 6 * (lrgb ? 1 : 3), 0);
  if (lrgb) ptm.rgb = planes.images[0];  // replaced when re-quantised
  *requantised = !ptmBytesCarryOver(m, lrgb);
  if (*requantised) requantisePtm(planes, m, &ptm);
  else copyPtmBytes(planes, m, &ptm);
  return ptm;
}

// ---- HSH ----------------------------------------------------------------------------------

// An .rti's coef = byte / 255 * scale + bias is the viewers' (byte / 255 - bias') * scale'
// with scale = scale' and bias = -bias' * scale'.
bool hshBytesCarryOver(const Material& m, int terms) {
  for (int k = 0; k < terms; ++k) {
    const auto p = static_cast<std::size_t>(3 * k);
    const double scale = m.scale[p], bias = -m.bias[p] * m.scale[p];
    if (!sameForRgb(m, 3 * k) || !std::isfinite(static_cast<float>(scale)) || !std::isfinite(static_cast<float>(bias)))
      return false;
  }
  return true;
}

// Each term over its range, all colours together (an .rti shares one scale and bias).
void requantiseHshTerm(const Planes& planes, const Material& m, int k, formats::HshFile* hsh) {
  const std::size_t n = planes.texels, terms = static_cast<std::size_t>(hsh->terms);
  std::vector<double> values;
  values.reserve(n * 3);
  for (std::size_t t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c) values.push_back(webCoefficient(planes, m, 3 * k + c, t));
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const float bias = static_cast<float>(*lo), scale = *hi > *lo ? static_cast<float>(*hi - *lo) : 0.0f;
  hsh->scale[static_cast<std::size_t>(k)] = scale;
  hsh->bias[static_cast<std::size_t>(k)] = bias;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const long b = scale == 0 ? 0 : std::lround((values[i] - bias) / scale * 255.0);
    hsh->coefficients[i * terms + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(std::clamp(b, 0L, 255L));
  }
}

formats::HshFile hshOf(const Planes& planes, const Material& m, const WebLayoutSummary& s, bool* requantised) {
  formats::HshFile hsh;
  hsh.width = s.width;
  hsh.height = s.height;
  hsh.terms = s.nplanes / 3;
  const auto terms = static_cast<std::size_t>(hsh.terms);
  hsh.scale.assign(terms, 0);
  hsh.bias.assign(terms, 0);
  hsh.coefficients.assign(planes.texels * 3 * terms, 0);
  *requantised = !hshBytesCarryOver(m, hsh.terms);
  for (int k = 0; k < hsh.terms; ++k) {
    if (*requantised) {
      requantiseHshTerm(planes, m, k, &hsh);
      continue;
    }
    const auto p = static_cast<std::size_t>(3 * k), term = static_cast<std::size_t>(k);
    hsh.scale[term] = static_cast<float>(m.scale[p]);
    hsh.bias[term] = static_cast<float>(-m.bias[p] * m.scale[p]);
    for (std::size_t t = 0; t < planes.texels; ++t)
      for (std::size_t c = 0; c < 3; ++c)
        hsh.coefficients[(t * 3 + c) * terms + term] = planes.byte(3 * k + static_cast<int>(c), t);
  }
  return hsh;
}
}  // namespace

bool isWebLayoutPath(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) || path.extension() == ".json";
}

WebLayoutModel readWebLayout(const fs::path& path, const formats::ModelBudget& budget) {
  WebLayoutModel out;
  out.infoJson = infoJsonOf(path);
  const WebLayoutSummary s = describeWebLayout(out.infoJson);
  checkBasis(s, out.infoJson);
  checkSize(s, out.infoJson);
  const bool learned = isLearnedType(s.type);
  // A learned layout's basis and materials are checked before anything else is read.
  if (learned) out.learned = learnedModelOf(out.infoJson, s);
  const Material material = materialOf(out.infoJson, s.nplanes);
  const bool requantised = learned ? false
                           : s.type == "ptm" ? !ptmBytesCarryOver(material, s.colorspace == "lrgb")
                                             : !hshBytesCarryOver(material, s.nplanes / 3);
  requireWithinMemory(out.infoJson.string(), kStep,
                      std::to_string(s.width) + "x" + std::to_string(s.height) + " texels in " +
                          std::to_string(s.nplanes) + " planes",
                      layoutReadBytes(s, out.infoJson.parent_path(), requantised, budget), budget.bytes);
  Planes planes;
  planes.texels = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  for (int j = 0; j * 3 < s.nplanes; ++j) planes.images.push_back(readPlane(out.infoJson.parent_path(), s, j));
  out.isPtm = s.type == "ptm";
  out.isLearned = learned;
  if (learned) {
    setLearnedCoefficients(planes.images, &out.learned);
  } else if (out.isPtm) {
    out.ptm = ptmOf(planes, material, s, &out.requantised);
    formats::validatePtm(out.ptm, out.infoJson.string());
  } else {
    out.hsh = hshOf(planes, material, s, &out.requantised);
    formats::validateHsh(out.hsh, out.infoJson.string());
  }
  return out;
}

}  // namespace surrogate::publish
