// Golden files from an independent implementation.
//
// This file holds its own small reader and writer of .ptm (PTM_1.2, PTM_FORMAT_LRGB and
// PTM_FORMAT_RGB) and .rti (HSH, RTI type 3), written from the published layouts that
// docs/formats.md restates (HP's "PTM File Format" 1.2; CHI's RTIViewer loaders and relight's
// writers for .rti), and its own renderer from the closed-form bases of
// tests/fit/reference_basis.h. None of it calls src/formats, and the renderer does not call
// src/fit. It is used both ways:
//   (a) files written HERE are read by Surrogate (formats::readPtm / readRti,
//       fit::openRelightable) and rendered by Surrogate (fit::render) at several lights; every
//       output pixel must be the nearest 8-bit value to what the closed form gives;
//   (b) files written by Surrogate (formats::writePtm / writeRti, from known coefficients and
//       from fit::fitPtm / fitHsh of synthetic photographs) are read HERE; header fields must be
//       exactly as the format prescribes, decoded coefficients must equal the known ones within
//       the format's quantisation, and an independent re-rendering at every captured light must
//       be within a fraction of a dB of an unquantised least-squares fit made here.
// A flipped row order, a swapped channel or term, or a wrong scale/bias convention on either
// side fails (a) or (b).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../fit/reference_basis.h"
#include "core/image.h"
#include "core/stack.h"
#include "core/temp_dir.h"
#include "fit/fit.h"
#include "fit/quantise.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace fs = std::filesystem;
namespace ref = surrogate::reference;
using namespace surrogate;

namespace {

// ===================================================================== independent format code
namespace indep {

using Bytes = std::string;

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// --- .ptm ---------------------------------------------------------------------------------
// Texel data is held by image position with rows counted from the TOP of the image; the file
// stores rows from the BOTTOM (first stored row = bottom image row), left to right.
struct Ptm {
  bool lrgb = true;  // PTM_FORMAT_LRGB, else PTM_FORMAT_RGB
  int width = 0, height = 0;
  std::array<double, 6> scale{};
  std::array<int, 6> bias{};
  // coef[channel][rowFromTop][column] -> a0..a5 bytes (LRGB: channel 0 only)
  std::vector<std::vector<std::vector<std::array<std::uint8_t, 6>>>> coef;
  // colour[rowFromTop][column] -> R, G, B bytes (LRGB only)
  std::vector<std::vector<std::array<std::uint8_t, 3>>> colour;
  std::array<std::string, 6> headerLines;  // as read

  void allocate() {
    coef.assign(lrgb ? 1 : 3, std::vector<std::vector<std::array<std::uint8_t, 6>>>(
                                  height, std::vector<std::array<std::uint8_t, 6>>(width)));
    colour.assign(lrgb ? height : 0, std::vector<std::array<std::uint8_t, 3>>(width));
  }
  // a_k = (byte - bias_k) * scale_k, 0..255 units.
  double a(int c, int x, int y, int k) const { return (coef[c][y][x][k] - bias[k]) * scale[k]; }
};

std::string decimal(double v) {  // plain decimal, no exponent, trailing zeros dropped
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

Bytes writePtm(const Ptm& p) {
  Bytes out = "PTM_1.2\n";
  out += p.lrgb ? "PTM_FORMAT_LRGB\n" : "PTM_FORMAT_RGB\n";
  out += std::to_string(p.width) + "\n" + std::to_string(p.height) + "\n";
  for (int k = 0; k < 6; ++k) out += (k ? " " : "") + decimal(p.scale[k]);
  out += "\n";
  for (int k = 0; k < 6; ++k) out += (k ? " " : "") + std::to_string(p.bias[k]);
  out += "\n";
  for (std::size_t c = 0; c < p.coef.size(); ++c)  // LRGB: one block; RGB: red, green, blue
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int k = 0; k < 6; ++k) out += static_cast<char>(p.coef[c][p.height - 1 - r][x][k]);
  if (p.lrgb)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int c = 0; c < 3; ++c) out += static_cast<char>(p.colour[p.height - 1 - r][x][c]);
  return out;
}

// Splits "a b c" on single spaces; an empty token (double, leading or trailing space) fails.
std::vector<std::string> singleSpaced(const std::string& line, const char* what) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t sp = line.find(' ', start);
    out.push_back(line.substr(start, sp == std::string::npos ? std::string::npos : sp - start));
    if (out.back().empty()) throw Failure(std::string(what) + ": empty token in \"" + line + "\"");
    if (sp == std::string::npos) break;
    start = sp + 1;
  }
  return out;
}

long integer(const std::string& s, const char* what) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
    throw Failure(std::string(what) + " is not a plain integer: \"" + s + "\"");
  return std::stol(s);
}

// The strictest reading of the format: the rules every viewer's parser is happy with.
Ptm readPtm(const Bytes& b) {
  Ptm p;
  std::size_t pos = 0;
  for (auto& line : p.headerLines) {
    const std::size_t nl = b.find('\n', pos);
    if (nl == std::string::npos) throw Failure("header ends early");
    line = b.substr(pos, nl - pos);
    if (line.find('\r') != std::string::npos) throw Failure("'\\r' in the header");
    pos = nl + 1;
  }
  if (p.headerLines[0] != "PTM_1.2") throw Failure("line 1 is not PTM_1.2");
  if (p.headerLines[1] == "PTM_FORMAT_LRGB") {
    p.lrgb = true;
  } else if (p.headerLines[1] == "PTM_FORMAT_RGB") {
    p.lrgb = false;
  } else {
    throw Failure("unexpected format line " + p.headerLines[1]);
  }
  p.width = static_cast<int>(integer(p.headerLines[2], "width (alone on line 3)"));
  p.height = static_cast<int>(integer(p.headerLines[3], "height (alone on line 4)"));
  const auto scales = singleSpaced(p.headerLines[4], "scale line");
  const auto biases = singleSpaced(p.headerLines[5], "bias line");
  if (scales.size() != 6 || biases.size() != 6) throw Failure("need 6 scales and 6 biases");
  for (int k = 0; k < 6; ++k) {
    if (scales[k].find_first_not_of("-.0123456789") != std::string::npos)
      throw Failure("scale \"" + scales[k] + "\" is not plain decimal notation");
    p.scale[k] = std::stod(scales[k]);
    p.bias[k] = static_cast<int>(integer(biases[k], "bias"));
    if (p.bias[k] > 255) throw Failure("bias above 255");
  }
  const std::size_t texels = static_cast<std::size_t>(p.width) * p.height;
  const std::size_t payload = texels * (p.lrgb ? 9 : 18);
  if (b.size() - pos != payload)
    throw Failure("payload is " + std::to_string(b.size() - pos) + " bytes, the header says " +
                  std::to_string(payload));
  p.allocate();
  auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(b[pos + i]); };
  std::size_t i = 0;
  for (std::size_t c = 0; c < p.coef.size(); ++c)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int k = 0; k < 6; ++k) p.coef[c][p.height - 1 - r][x][k] = byte(i++);
  if (p.lrgb)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int c = 0; c < 3; ++c) p.colour[p.height - 1 - r][x][c] = byte(i++);
  return p;
}

// --- .rti (HSH) ------------------------------------------------------------------------------
// Rows are stored from the TOP; per texel all terms of red, then green, then blue.
struct Rti {
  int width = 0, height = 0, terms = 0;
  std::vector<float> scale, bias;  // one per term, shared by R, G, B
  // coef[rowFromTop][column][channel][term]
  std::vector<std::vector<std::array<std::vector<std::uint8_t>, 3>>> coef;
  std::vector<std::string> headerLines;  // as read, comments included

  void allocate() {
    coef.assign(height, std::vector<std::array<std::vector<std::uint8_t>, 3>>(width));
    for (auto& row : coef)
      for (auto& texel : row)
        for (auto& channel : texel) channel.assign(terms, 0);
  }
  // coefficient = byte / 255 * SCALE_k + BIAS_k, 0..1 units.
  double a(int x, int y, int c, int k) const {
    return coef[y][x][c][k] / 255.0 * static_cast<double>(scale[k]) + static_cast<double>(bias[k]);
  }
};

void putFloat(Bytes& out, float f) {  // IEEE-754 binary32, little-endian
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  for (int i = 0; i < 4; ++i) out += static_cast<char>((u >> (8 * i)) & 0xFFu);
}

float getFloat(const Bytes& b, std::size_t at) {
  std::uint32_t u = 0;
  for (int i = 0; i < 4; ++i) u |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[at + i])) << (8 * i);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

Bytes writeRti(const Rti& r) {
  Bytes out = "#HSH1.2\n3\n" + std::to_string(r.width) + " " + std::to_string(r.height) +
              " 3\n" + std::to_string(r.terms) + " 2 1\n";
  for (float s : r.scale) putFloat(out, s);
  for (float s : r.bias) putFloat(out, s);
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < r.terms; ++k) out += static_cast<char>(r.coef[y][x][c][k]);
  return out;
}

Rti readRti(const Bytes& b) {
  Rti r;
  if (b.compare(0, 8, "#HSH1.2\n") != 0) throw Failure("does not start with \"#HSH1.2\\n\"");
  std::size_t pos = 0;
  std::vector<std::string> fields;  // the three non-comment lines
  while (fields.size() < 3) {
    const std::size_t nl = b.find('\n', pos);
    if (nl == std::string::npos) throw Failure("header ends early");
    const std::string line = b.substr(pos, nl - pos);
    r.headerLines.push_back(line);
    pos = nl + 1;
    if (line.find('\r') != std::string::npos) throw Failure("'\\r' in the header");
    if (!line.empty() && line[0] == '#') {
      if (!fields.empty()) throw Failure("a comment line after the RTI type line");
      continue;  // leading comment lines, "#HSH1.2" first
    }
    fields.push_back(line);
  }
  if (integer(fields[0], "RTI type") != 3) throw Failure("RTI type is not 3 (HSH)");
  const auto size = singleSpaced(fields[1], "size line");
  const auto basis = singleSpaced(fields[2], "basis line");
  if (size.size() != 3 || basis.size() != 3) throw Failure("size and basis lines need 3 fields");
  r.width = static_cast<int>(integer(size[0], "width"));
  r.height = static_cast<int>(integer(size[1], "height"));
  if (integer(size[2], "channels") != 3) throw Failure("channels is not 3");
  r.terms = static_cast<int>(integer(basis[0], "terms"));
  if (r.terms != 4 && r.terms != 9 && r.terms != 16) throw Failure("terms not 4, 9 or 16");
  if (basis[1] != "2" || basis[2] != "1") throw Failure("basis type and element size not \"2 1\"");
  const std::size_t payload = 8 * static_cast<std::size_t>(r.terms) +
                              static_cast<std::size_t>(r.width) * r.height * 3 * r.terms;
  if (b.size() - pos != payload)
    throw Failure("payload is " + std::to_string(b.size() - pos) + " bytes, the header says " +
                  std::to_string(payload));
  for (int k = 0; k < r.terms; ++k) r.scale.push_back(getFloat(b, pos + 4 * k));
  for (int k = 0; k < r.terms; ++k) r.bias.push_back(getFloat(b, pos + 4 * (r.terms + k)));
  pos += 8 * r.terms;
  r.allocate();
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < r.terms; ++k) r.coef[y][x][c][k] = static_cast<std::uint8_t>(b[pos++]);
  return r;
}

// --- rendering from the closed forms (0..255 units, unclamped, unrounded) -------------------
// PTM: L = sum_k a_k w_k(lu, lv), (lu, lv) = (lx, ly) of the unit light.
// LRGB shows colour_c * L / 255; RGB shows L_c. HSH shows 255 * sum_k coef_{c,k} H_k.
double ptmValue(const Ptm& p, int x, int y, int c, double lx, double ly, double lz) {
  const auto uv = ref::ptmArguments(lx, ly, lz);
  double l = 0;
  for (int k = 0; k < 6; ++k) l += p.a(p.lrgb ? 0 : c, x, y, k) * ref::ptmTerm(k, uv[0], uv[1]);
  return p.lrgb ? p.colour[y][x][c] * l / 255.0 : l;
}

double rtiValue(const Rti& r, int x, int y, int c, double lx, double ly, double lz) {
  double v = 0;
  for (int k = 0; k < r.terms; ++k) v += r.a(x, y, c, k) * ref::hshTerm(k, lx, ly, lz);
  return 255.0 * v;
}

}  // namespace indep

// ===================================================================== helpers

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

using Light = std::array<double, 3>;

// Lights for rendering: overhead, every quadrant, from the image's top and right edges,
// grazing, and unnormalised vectors.
const std::vector<Light> kRenderLights = {{0, 0, 1},        {0.5, 0.3, 0.81},  {-0.7, 0.2, 0.5},
                                          {0.1, -0.8, 0.6}, {-0.4, -0.5, 0.77}, {0, 1, 0.25},
                                          {1, 0, 0.25},     {1, 2, 2},          {0.97, -0.2, 0.1}};

// N lights over elevations 20..80 degrees and all azimuths (golden-angle spiral).
std::vector<Light> captureLights(int n) {
  std::vector<Light> out;
  for (int i = 0; i < n; ++i) {
    const double el = (20.0 + 60.0 * (i + 0.5) / n) * ref::kPi / 180.0, az = i * 2.399963229728653;
    out.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
  }
  return out;
}

// A deterministic byte in [lo, hi] that differs between neighbouring texels, rows, channels
// and terms.
std::uint8_t pattern(int x, int y, int c, int k, int lo, int hi) {
  const unsigned h = static_cast<unsigned>(x * 7919 + y * 104729 + c * 1299709 + k * 15485863 +
                                           x * y * 31 + 17);
  return static_cast<std::uint8_t>(lo + (h ^ (h >> 7)) % static_cast<unsigned>(hi - lo + 1));
}

// Surrogate's rendered 8-bit value (render() widens 8-bit values by 257).
double rendered(const Image& im, int x, int y, int c) { return im.at(x, y, c) / 257.0; }

// The nearest 8-bit value of a closed-form value: |got - clamp(v)| <= 0.5 (plus float noise).
void checkNearest(double got, double value, const std::string& where) {
  const double want = std::min(255.0, std::max(0.0, value));
  INFO(where << ": Surrogate " << got << ", closed form " << value);
  CHECK(std::fabs(got - want) <= 0.5 + 1e-6);
}

indep::Ptm knownPtm(bool lrgb, int w, int h) {
  indep::Ptm p;
  p.lrgb = lrgb;
  p.width = w;
  p.height = h;
  p.scale = {0.25, 0.25, 0.125, 0.5, 0.5, 1.0};
  p.bias = {200, 200, 128, 128, 128, 0};
  p.allocate();
  //                 a0 in [-20, 0]  a1 in [-20, 0]  a2 in [-8, 8]  a3, a4 in [-20, 20]  a5 in [120, 230]
  const int lo[6] = {120, 120, 64, 88, 88, 120}, hi[6] = {200, 200, 192, 168, 168, 230};
  for (std::size_t c = 0; c < p.coef.size(); ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < 6; ++k) p.coef[c][y][x][k] = pattern(x, y, static_cast<int>(c), k, lo[k], hi[k]);
  for (int y = 0; y < static_cast<int>(p.colour.size()); ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) p.colour[y][x][c] = pattern(x, y, c, 7, 40, 230);
  return p;
}

indep::Rti knownRti(int terms, int w, int h) {
  indep::Rti r;
  r.width = w;
  r.height = h;
  r.terms = terms;
  for (int k = 0; k < terms; ++k) {
    r.scale.push_back(k == 0 ? 1.0f : 0.25f);   // H0's coefficient in [0.5, 1.5]
    r.bias.push_back(k == 0 ? 0.5f : -0.125f);  // the others in [-0.125, 0.125]
  }
  r.allocate();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < terms; ++k) r.coef[y][x][c][k] = pattern(x, y, c, k, 0, 255);
  return r;
}

// Gaussian elimination with partial pivoting: solves m x = b (n x n), m and b overwritten.
std::vector<double> solve(std::vector<double> m, std::vector<double> b, int n) {
  for (int i = 0; i < n; ++i) {
    int best = i;
    for (int r = i + 1; r < n; ++r)
      if (std::fabs(m[r * n + i]) > std::fabs(m[best * n + i])) best = r;
    for (int j = 0; j < n; ++j) std::swap(m[i * n + j], m[best * n + j]);
    std::swap(b[i], b[best]);
    for (int r = i + 1; r < n; ++r) {
      const double f = m[r * n + i] / m[i * n + i];
      for (int j = i; j < n; ++j) m[r * n + j] -= f * m[i * n + j];
      b[r] -= f * b[i];
    }
  }
  std::vector<double> x(n);
  for (int i = n - 1; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < n; ++j) s -= m[i * n + j] * x[j];
    x[i] = s / m[i * n + i];
  }
  return x;
}

// Unquantised least-squares coefficients (normal equations) of samples s_i over rows w(l_i).
std::vector<double> leastSquares(const std::vector<std::vector<double>>& rows,
                                 const std::vector<double>& s) {
  const int t = static_cast<int>(rows[0].size());
  std::vector<double> ata(t * t, 0.0), atb(t, 0.0);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int a = 0; a < t; ++a) {
      atb[a] += rows[i][a] * s[i];
      for (int b = 0; b < t; ++b) ata[a * t + b] += rows[i][a] * rows[i][b];
    }
  return solve(ata, atb, t);
}

// A scene no PTM or HSH reproduces exactly: a Lambertian surface with ambient light and a
// Blinn-Phong highlight; the normal tilts with the column and, strongly, with the row (so
// that a flipped row order shows), the albedo differs per channel.
struct Scene {
  int w = 13, h = 9;
  std::array<double, 3> normal(int x, int y) const {
    const double nx = 0.45 * std::sin(0.7 * x - 2.0);
    const double ny = 0.6 * (2.0 * y / (h - 1) - 1.0);
    return {nx, ny, std::sqrt(1 - nx * nx - ny * ny)};
  }
  double albedo(int x, int y, int c) const { return 0.35 + 0.1 * c + 0.03 * ((x + 2 * y) % 5); }
  double value(int x, int y, int c, const Light& l) const {  // 0..255 units
    const auto n = normal(x, y);
    const double len = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const double lx = l[0] / len, ly = l[1] / len, lz = l[2] / len;
    const double ndotl = std::max(0.0, n[0] * lx + n[1] * ly + n[2] * lz);
    double hv[3] = {lx, ly, lz + 1};
    const double hl = std::sqrt(hv[0] * hv[0] + hv[1] * hv[1] + hv[2] * hv[2]);
    const double ndoth = std::max(0.0, (n[0] * hv[0] + n[1] * hv[1] + n[2] * hv[2]) / hl);
    return std::min(255.0, 255.0 * albedo(x, y, c) * (0.2 + 0.9 * ndotl) + 25.0 * std::pow(ndoth, 12));
  }
  // The photographs as 16-bit samples (the Image convention), and the same in 0..255 units.
  MemoryImageStack photographs(const std::vector<Light>& lights,
                               std::vector<std::vector<double>>* units) const {
    std::vector<Image> images;
    units->clear();
    for (const Light& l : lights) {
      Image im(w, h, 3);
      std::vector<double> u(static_cast<std::size_t>(w) * h * 3);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c) {
            const auto s = static_cast<std::uint16_t>(std::lround(value(x, y, c, l) * 257.0));
            im.at(x, y, c) = s;
            u[(static_cast<std::size_t>(y) * w + x) * 3 + c] = s / 257.0;
          }
      images.push_back(std::move(im));
      units->push_back(std::move(u));
    }
    return MemoryImageStack(std::move(images));
  }
};

// How far quantisation alone can move a rendered value: half a step of every coefficient times
// the largest |w_k| over the lights, in 0..255 units (`step` in the rendered units).
double quantisationBound(const std::vector<std::vector<double>>& rows, const std::vector<double>& step) {
  double bound = 0;
  for (std::size_t k = 0; k < step.size(); ++k) {
    double largest = 0;
    for (const auto& r : rows) largest = std::max(largest, std::fabs(r[k]));
    bound += step[k] / 2 * largest;
  }
  return bound + 1e-6;
}

double psnr(double sumSq, std::size_t count) {
  return 20 * std::log10(255.0 / std::sqrt(sumSq / static_cast<double>(count)));
}

}  // namespace

// ===================================================================== (a) ours -> Surrogate

TEST_CASE("independent .ptm LRGB and RGB files read and render in Surrogate as the closed form says") {
  surrogate::TempDir temp("independent-ptm");
  for (bool lrgb : {true, false}) {
    const indep::Ptm p = knownPtm(lrgb, 5, 4);
    const fs::path file = temp.path() / (lrgb ? "lrgb.ptm" : "rgb.ptm");
    spit(file, indep::writePtm(p));

    const formats::PtmFile s = formats::readPtm(file);
    REQUIRE(s.format == (lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb));
    REQUIRE(s.width == 5);
    REQUIRE(s.height == 4);
    for (int k = 0; k < 6; ++k) {
      CHECK(s.scale[k] == p.scale[k]);
      CHECK(s.bias[k] == p.bias[k]);
    }
    for (int c = 0; c < (lrgb ? 1 : 3); ++c)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int k = 0; k < 6; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " a" << k);
            CHECK(s.coefficient(x, y, k, c) == p.a(c, x, y, k));
          }

    const auto model = fit::openRelightable(file);
    CHECK(model->basis() == (lrgb ? "ptm-lrgb" : "ptm-rgb"));
    for (const Light& l : kRenderLights) {
      const Image a = fit::render(s, l);
      const Image b = model->render(l, {});
      REQUIRE(a.width == 5);
      REQUIRE(a.height == 4);
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int c = 0; c < 3; ++c) {
            const double want = indep::ptmValue(p, x, y, c, l[0], l[1], l[2]);
            const std::string where = std::string(lrgb ? "LRGB" : "RGB") + " light (" +
                                      std::to_string(l[0]) + ", " + std::to_string(l[1]) + ", " +
                                      std::to_string(l[2]) + ") pixel (" + std::to_string(x) +
                                      ", " + std::to_string(y) + ") channel " + std::to_string(c);
            checkNearest(rendered(a, x, y, c), want, where);
            checkNearest(rendered(b, x, y, c), want, where + " (openRelightable)");
          }
    }
  }
}

TEST_CASE("independent .rti HSH files of 4, 9 and 16 terms read and render in Surrogate as the closed form says") {
  surrogate::TempDir temp("independent-rti");
  for (int terms : {4, 9, 16}) {
    const indep::Rti r = knownRti(terms, 5, 4);
    const fs::path file = temp.path() / ("hsh" + std::to_string(terms) + ".rti");
    spit(file, indep::writeRti(r));

    const formats::HshFile s = formats::readRti(file);
    REQUIRE(s.terms == terms);
    REQUIRE(s.width == 5);
    REQUIRE(s.height == 4);
    for (int k = 0; k < terms; ++k) {
      CHECK(s.scale[k] == r.scale[k]);
      CHECK(s.bias[k] == r.bias[k]);
    }
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " H" << k);
            CHECK(s.coefficient(x, y, c, k) == r.a(x, y, c, k));
          }

    const auto model = fit::openRelightable(file);
    CHECK(model->basis() == (terms == 4 ? "hsh2" : terms == 9 ? "hsh3" : "hsh4"));
    int unclamped = 0;
    for (const Light& l : kRenderLights) {
      const Image a = fit::render(s, l);
      const Image b = model->render(l, {});
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int c = 0; c < 3; ++c) {
            const double want = indep::rtiValue(r, x, y, c, l[0], l[1], l[2]);
            if (want > 0.5 && want < 254.5) ++unclamped;
            const std::string where = std::to_string(terms) + " terms, light (" +
                                      std::to_string(l[0]) + ", " + std::to_string(l[1]) + ", " +
                                      std::to_string(l[2]) + ") pixel (" + std::to_string(x) +
                                      ", " + std::to_string(y) + ") channel " + std::to_string(c);
            checkNearest(rendered(a, x, y, c), want, where);
            checkNearest(rendered(b, x, y, c), want, where + " (openRelightable)");
          }
    }
    // The comparison means something only where the output is not clipped.
    CHECK(unclamped > static_cast<int>(kRenderLights.size()) * 5 * 4 * 3 * 3 / 4);
  }
}

// ===================================================================== (b) Surrogate -> ours

TEST_CASE("Surrogate's .ptm from known coefficients reads back here: header, pixel order, quantisation") {
  surrogate::TempDir temp("independent-ptm-back");
  const int w = 6, h = 5;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (bool lrgb : {true, false}) {
    const int channels = lrgb ? 1 : 3;
    // Known real coefficients (0..255 units), [channel][y][x][k], and colours.
    std::vector<std::array<double, 6>> truth(static_cast<std::size_t>(channels) * w * h);
    for (auto& a : truth)
      a = {-30 * u(rng), -30 * u(rng), -8 + 16 * u(rng), -25 + 50 * u(rng), -25 + 50 * u(rng),
           110 + 100 * u(rng)};
    auto at = [&](int c, int x, int y) -> const std::array<double, 6>& {
      return truth[(static_cast<std::size_t>(c) * h + y) * w + x];
    };
    // Surrogate's quantisation of them, into Surrogate's in-memory object.
    formats::PtmFile s;
    s.format = lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb;
    s.width = w;
    s.height = h;
    std::array<fit::PtmQuantisation, 6> q;
    for (int k = 0; k < 6; ++k) {
      double lo = 1e300, hi = -1e300;
      for (const auto& a : truth) {
        lo = std::min(lo, a[k]);
        hi = std::max(hi, a[k]);
      }
      q[k] = fit::choosePtmQuantisation(lo, hi);
      s.scale[k] = q[k].scale;
      s.bias[k] = q[k].bias;
    }
    s.coefficients.resize(static_cast<std::size_t>(w) * h * 6 * channels);
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int k = 0; k < 6; ++k)
            s.coefficients[((static_cast<std::size_t>(c) * h + y) * w + x) * 6 + k] =
                q[k].quantise(at(c, x, y)[k]);
    if (lrgb) {
      s.rgb.resize(static_cast<std::size_t>(w) * h * 3);
      for (std::size_t i = 0; i < s.rgb.size(); ++i) s.rgb[i] = static_cast<std::uint8_t>(30 + (i * 37) % 200);
    }
    const fs::path file = temp.path() / (lrgb ? "lrgb.ptm" : "rgb.ptm");
    formats::writePtm(file, s);

    indep::Ptm p;
    try {
      p = indep::readPtm(slurp(file));
    } catch (const indep::Failure& e) {
      FAIL("the independent reader rejects Surrogate's .ptm: " << e.what());
    }
    CHECK(p.headerLines[0] == "PTM_1.2");
    CHECK(p.headerLines[1] == (lrgb ? "PTM_FORMAT_LRGB" : "PTM_FORMAT_RGB"));
    CHECK(p.headerLines[2] == std::to_string(w));
    CHECK(p.headerLines[3] == std::to_string(h));
    for (int k = 0; k < 6; ++k) {
      CHECK(p.scale[k] == s.scale[k]);  // the text reads back to the very double
      CHECK(p.bias[k] == s.bias[k]);
    }
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int k = 0; k < 6; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " a" << k);
            CHECK(p.coef[c][y][x][k] == s.byte(x, y, k, c));
            CHECK(std::fabs(p.a(c, x, y, k) - at(c, x, y)[k]) <= p.scale[k] / 2 + 1e-9);
          }
    if (lrgb)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c)
            CHECK(p.colour[y][x][c] == s.rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c]);
    // And our own writer, given the same header numbers and texels, writes the same payload.
    const std::string ours = indep::writePtm(p), theirs = slurp(file);
    const std::size_t payload = static_cast<std::size_t>(w) * h * (lrgb ? 9 : 18);
    CHECK(ours.substr(ours.size() - payload) == theirs.substr(theirs.size() - payload));
  }
}

TEST_CASE("Surrogate's .rti from known coefficients reads back here: header, pixel order, quantisation") {
  surrogate::TempDir temp("independent-rti-back");
  const int w = 6, h = 5;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int terms : {4, 9, 16}) {
    std::vector<double> truth(static_cast<std::size_t>(w) * h * 3 * terms);  // [y][x][c][k]
    for (std::size_t i = 0; i < truth.size(); ++i)
      truth[i] = (i % terms == 0) ? 1.2 + 0.3 * u(rng) : 0.05 * u(rng);
    auto at = [&](int x, int y, int c, int k) {
      return truth[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k];
    };
    formats::HshFile s;
    s.width = w;
    s.height = h;
    s.terms = terms;
    std::vector<fit::HshQuantisation> q(terms);
    for (int k = 0; k < terms; ++k) {
      double lo = 1e300, hi = -1e300;
      for (std::size_t i = k; i < truth.size(); i += terms) {
        lo = std::min(lo, truth[i]);
        hi = std::max(hi, truth[i]);
      }
      q[k] = fit::chooseHshQuantisation(lo, hi);
      s.scale.push_back(q[k].scale);
      s.bias.push_back(q[k].bias);
    }
    s.coefficients.resize(truth.size());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k)
            s.coefficients[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k] =
                q[k].quantise(at(x, y, c, k));
    const fs::path file = temp.path() / ("hsh" + std::to_string(terms) + ".rti");
    formats::writeRti(file, s);

    indep::Rti r;
    try {
      r = indep::readRti(slurp(file));
    } catch (const indep::Failure& e) {
      FAIL("the independent reader rejects Surrogate's .rti: " << e.what());
    }
    REQUIRE(r.headerLines.size() == 4);
    CHECK(r.headerLines[0] == "#HSH1.2");
    CHECK(r.headerLines[1] == "3");
    CHECK(r.headerLines[2] == std::to_string(w) + " " + std::to_string(h) + " 3");
    CHECK(r.headerLines[3] == std::to_string(terms) + " 2 1");
    for (int k = 0; k < terms; ++k) {
      CHECK(r.scale[k] == s.scale[k]);
      CHECK(r.bias[k] == s.bias[k]);
    }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k) {
            INFO(terms << " terms, texel (" << x << ", " << y << ") channel " << c << " H" << k);
            CHECK(r.coef[y][x][c][k] == s.byte(x, y, c, k));
            // Half a step of SCALE/255, plus the float32 rounding of SCALE and BIAS.
            CHECK(std::fabs(r.a(x, y, c, k) - at(x, y, c, k)) <=
                  static_cast<double>(r.scale[k]) / 510.0 + 1e-6);
          }
    CHECK(indep::writeRti(r) == slurp(file));  // byte for byte
  }
}

TEST_CASE("Surrogate's fitted .ptm and .rti, read and re-rendered here, match an unquantised least-squares fit") {
  // The proof of docs/formats.md ("Testing a writer"): photographs of a scene no model
  // reproduces exactly, fitted by Surrogate and written to a file; that file read by the
  // independent reader and rendered from the closed form at every captured light is within a
  // fraction of a dB (PSNR against the photographs) of the same model fitted here, in double,
  // without quantisation.
  surrogate::TempDir temp("independent-fit");
  const Scene scene;
  const auto lights = captureLights(36);
  std::vector<std::vector<double>> photo;  // [light][(y*w + x)*3 + c], 0..255 units
  const MemoryImageStack stack = scene.photographs(lights, &photo);
  const std::size_t samples = lights.size() * scene.w * scene.h * 3;

  SECTION("RGB PTM") {
    fit::FitOptions o;
    o.basis = fit::Basis::PtmRgb;
    const fs::path file = temp.path() / "fit.ptm";
    formats::writePtm(file, fit::fitPtm(stack, lights, o));
    const indep::Ptm p = indep::readPtm(slurp(file));
    REQUIRE(!p.lrgb);
    std::vector<std::vector<double>> rows;
    for (const Light& l : lights) {
      const auto uv = ref::ptmArguments(l[0], l[1], l[2]);
      rows.push_back({});
      for (int k = 0; k < 6; ++k) rows.back().push_back(ref::ptmTerm(k, uv[0], uv[1]));
    }
    double errFile = 0, errLs = 0, worst = 0;
    for (int y = 0; y < scene.h; ++y)
      for (int x = 0; x < scene.w; ++x)
        for (int c = 0; c < 3; ++c) {
          std::vector<double> s;
          for (const auto& im : photo) s.push_back(im[(y * scene.w + x) * 3 + c]);
          const auto a = leastSquares(rows, s);
          for (std::size_t i = 0; i < lights.size(); ++i) {
            const Light& l = lights[i];
            const double file = std::clamp(indep::ptmValue(p, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
            double ls = 0;
            for (int k = 0; k < 6; ++k) ls += a[k] * rows[i][k];
            ls = std::clamp(ls, 0.0, 255.0);
            errFile += (file - s[i]) * (file - s[i]);
            errLs += (ls - s[i]) * (ls - s[i]);
            worst = std::max(worst, std::fabs(file - ls));
          }
        }
    const double bound = quantisationBound(rows, {p.scale.begin(), p.scale.end()});
    INFO("PSNR of the file " << psnr(errFile, samples) << " dB, unquantised fit "
                             << psnr(errLs, samples) << " dB, largest difference " << worst
                             << " (quantisation bound " << bound << ")");
    CHECK(psnr(errLs, samples) < 60);  // the scene is not a PTM: quantisation is not all
    CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
    CHECK(worst <= bound);
  }

  SECTION("LRGB PTM") {
    const fs::path file = temp.path() / "fit-lrgb.ptm";
    formats::writePtm(file, fit::fitPtm(stack, lights, fit::FitOptions{}));
    const indep::Ptm p = indep::readPtm(slurp(file));
    REQUIRE(p.lrgb);
    // relight's LRGB definition: colour = the mean colour weighted by
    // w_i = max(0, 0.25 - (asin(lz)/(pi/2) - 0.5)^2), stored as bytes (checked against the
    // file's to within 1, then the file's bytes are used); luminance
    // L_i = 255 (R_i + G_i + B_i) / (sum of the colour bytes), fitted by least squares.
    std::vector<std::vector<double>> rows;
    std::vector<double> weight;
    double total = 0;
    for (const Light& l : lights) {
      const auto uv = ref::ptmArguments(l[0], l[1], l[2]);
      rows.push_back({});
      for (int k = 0; k < 6; ++k) rows.back().push_back(ref::ptmTerm(k, uv[0], uv[1]));
      const double e = std::asin(l[2]) / (ref::kPi / 2) - 0.5;
      weight.push_back(std::max(0.0, 0.25 - e * e));
      total += weight.back();
    }
    double errFile = 0, errLs = 0, worst = 0;
    int colourOff = 0;
    for (int y = 0; y < scene.h; ++y)
      for (int x = 0; x < scene.w; ++x) {
        std::array<double, 3> colour{};
        double colourSum = 0;
        for (int c = 0; c < 3; ++c) {
          for (std::size_t i = 0; i < lights.size(); ++i)
            colour[c] += weight[i] * photo[i][(y * scene.w + x) * 3 + c] / total;
          if (std::fabs(colour[c] - p.colour[y][x][c]) > 1) ++colourOff;
          colour[c] = p.colour[y][x][c];
          colourSum += colour[c];
        }
        std::vector<double> lum;
        for (const auto& im : photo)
          lum.push_back(255.0 * (im[(y * scene.w + x) * 3] + im[(y * scene.w + x) * 3 + 1] +
                                 im[(y * scene.w + x) * 3 + 2]) / colourSum);
        const auto a = leastSquares(rows, lum);
        for (std::size_t i = 0; i < lights.size(); ++i) {
          const Light& l = lights[i];
          double lsL = 0;
          for (int k = 0; k < 6; ++k) lsL += a[k] * rows[i][k];
          for (int c = 0; c < 3; ++c) {
            const double s = photo[i][(y * scene.w + x) * 3 + c];
            const double file = std::clamp(indep::ptmValue(p, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
            const double ls = std::clamp(colour[c] * lsL / 255.0, 0.0, 255.0);
            errFile += (file - s) * (file - s);
            errLs += (ls - s) * (ls - s);
            worst = std::max(worst, std::fabs(file - ls));
          }
        }
      }
    // colour_c / 255 <= 1 multiplies the luminance's quantisation error.
    const double bound = quantisationBound(rows, {p.scale.begin(), p.scale.end()});
    INFO("PSNR of the file " << psnr(errFile, samples) << " dB, unquantised fit "
                             << psnr(errLs, samples) << " dB, largest difference " << worst
                             << " (quantisation bound " << bound << ")");
    CHECK(colourOff == 0);
    CHECK(psnr(errLs, samples) < 60);
    CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
    CHECK(worst <= bound);
  }

  SECTION("HSH orders 2 and 3") {
    for (fit::Basis b : {fit::Basis::Hsh2, fit::Basis::Hsh3}) {
      fit::FitOptions o;
      o.basis = b;
      const fs::path file = temp.path() / (std::string(fit::basisName(b)) + ".rti");
      formats::writeRti(file, fit::fitHsh(stack, lights, o));
      const indep::Rti r = indep::readRti(slurp(file));
      const int terms = b == fit::Basis::Hsh2 ? 4 : 9;
      REQUIRE(r.terms == terms);
      std::vector<std::vector<double>> rows;
      for (const Light& l : lights) {
        rows.push_back({});
        for (int k = 0; k < terms; ++k) rows.back().push_back(ref::hshTerm(k, l[0], l[1], l[2]));
      }
      double errFile = 0, errLs = 0, worst = 0;
      for (int y = 0; y < scene.h; ++y)
        for (int x = 0; x < scene.w; ++x)
          for (int c = 0; c < 3; ++c) {
            std::vector<double> s;
            for (const auto& im : photo) s.push_back(im[(y * scene.w + x) * 3 + c]);
            const auto a = leastSquares(rows, s);
            for (std::size_t i = 0; i < lights.size(); ++i) {
              const Light& l = lights[i];
              const double file = std::clamp(indep::rtiValue(r, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
              double ls = 0;
              for (int k = 0; k < terms; ++k) ls += a[k] * rows[i][k];
              ls = std::clamp(ls, 0.0, 255.0);
              errFile += (file - s[i]) * (file - s[i]);
              errLs += (ls - s[i]) * (ls - s[i]);
              worst = std::max(worst, std::fabs(file - ls));
            }
          }
      // A step of coefficient k is SCALE_k / 255 in 0..1 units, 255 times that rendered.
      std::vector<double> step;
      for (float sc : r.scale) step.push_back(static_cast<double>(sc));
      const double bound = quantisationBound(rows, step);
      INFO(terms << " terms: PSNR of the file " << psnr(errFile, samples)
                 << " dB, unquantised fit " << psnr(errLs, samples) << " dB, largest difference "
                 << worst << " (quantisation bound " << bound << ")");
      CHECK(psnr(errLs, samples) < 60);
      CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
      CHECK(worst <= bound);
    }
  }
}
