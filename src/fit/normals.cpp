#include "fit/normals.h"

#include "fit/basis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/parallel.h"
#include "fit/lambert.h"
#include "fit/quantise.h"
#include "fit/texel.h"

namespace surrogate::fit {

namespace {

// A normal's component -1..1 as 0..65535, rounded half away from zero (roundClamped clamps:
// (v + 1) / 2 outside 0..1 scales to outside 0..65535).
std::uint16_t encodeUnit(double v) {
  return static_cast<std::uint16_t>(detail::roundClamped((v + 1.0) / 2.0 * 65535.0, 65535.0));
}

// An 8-bit value as a 16-bit sample: round(v) clamped to 0..255, times 257.
std::uint16_t encodeByte(double v) { return static_cast<std::uint16_t>(detail::toByte(v) * 257); }

// Runs fn(x, y) over every texel, rows split over threads; returns the sum of fn's results
// (per-row counts added in row order).
int forEachTexel(int width, int height, int threads, const std::function<int(int, int)>& fn) {
  std::vector<int> rowCounts(height, 0);
  parallelFor(static_cast<std::size_t>(height), 8, effectiveThreads(threads),
              [&](std::size_t b, std::size_t e) {
                for (std::size_t y = b; y < e; ++y)
                  for (int x = 0; x < width; ++x) rowCounts[y] += fn(x, static_cast<int>(y));
              });
  int total = 0;
  for (int c : rowCounts) total += c;
  return total;
}

Image normalImage(int w, int h) {
  Image out(w, h, 3);
  out.bitsPerSample = 16;
  out.transfer = Transfer::Linear;
  return out;
}

Image albedoImage(int w, int h) {
  Image out(w, h, 3);
  out.bitsPerSample = 8;
  out.transfer = Transfer::Srgb;
  return out;
}

}  // namespace

std::array<double, 3> ptmNormal(const PtmCoefficients& a, bool* usedFallback) {
  double lu0 = 0, lv0 = 0;
  if (ptmMaximum(a, &lu0, &lv0)) {
    const double r2 = lu0 * lu0 + lv0 * lv0;
    if (r2 > 1) {
      const double r = std::sqrt(r2);
      lu0 /= r;
      lv0 /= r;
    }
    if (usedFallback) *usedFallback = false;
    return {lu0, lv0, std::sqrt(std::max(0.0, 1 - lu0 * lu0 - lv0 * lv0))};
  }
  std::array<double, 3> n;
  normalFromLambert(ptmLambert(a), &n);
  if (usedFallback) *usedFallback = true;
  return n;
}

namespace {
// The normal map and the albedo of a PTM, either of them (nullptr: not made), in one pass: the
// albedo is the model at the normal, so making both together finds each texel's normal once.
// Rows are looped over here rather than through forEachTexel, and the coefficients decoded by
// table: the same values as ptmLuminance and ptmChannel give, in less time (about 12 ms of
// CPU of 1200x800, a std::function call and six conversions a texel).
int ptmMaps(const formats::PtmFile& ptm, Image* normals, Image* albedo, int threads) {
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  const PtmDecoded decoded(ptm);
  const std::size_t plane = ptm.texels() * 6;  // bytes of one channel's coefficients
  std::vector<int> rowCounts(ptm.height, 0);
  parallelFor(static_cast<std::size_t>(ptm.height), 8, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t y = b; y < e; ++y) {
      const std::size_t row = y * ptm.width;
      for (int x = 0; x < ptm.width; ++x) {
        const std::size_t texel = row + x;
        const std::uint8_t* bytes = &ptm.coefficients[texel * 6];
        const PtmCoefficients lum = ptmLuminance(ptm, decoded, bytes, plane);
        bool fallback = false;
        const auto n = ptmNormal(lum, &fallback);
        rowCounts[y] += fallback ? 1 : 0;
        if (normals)
          for (int c = 0; c < 3; ++c) normals->pixels[texel * 3 + c] = encodeUnit(n[c]);
        if (albedo && lrgb) {
          const double l = evaluatePtm(lum, n[0], n[1]);
          for (int c = 0; c < 3; ++c) albedo->pixels[texel * 3 + c] = encodeByte(ptm.rgb[texel * 3 + c] * l / 255.0);
        } else if (albedo) {
          for (int c = 0; c < 3; ++c)
            albedo->pixels[texel * 3 + c] = encodeByte(evaluatePtm(decoded(bytes + c * plane), n[0], n[1]));
        }
      }
    }
  });
  int total = 0;
  for (int c : rowCounts) total += c;
  return total;
}
}  // namespace

Image normalMap(const formats::PtmFile& ptm, int* fallbackCount, int threads) {
  Image out = normalImage(ptm.width, ptm.height);
  const int fallbacks = ptmMaps(ptm, &out, nullptr, threads);
  if (fallbackCount) *fallbackCount = fallbacks;
  return out;
}

void normalAndAlbedoMaps(const formats::PtmFile& ptm, Image* normals, Image* albedo, int* fallbackCount,
                         int threads) {
  *normals = normalImage(ptm.width, ptm.height);
  *albedo = albedoImage(ptm.width, ptm.height);
  const int fallbacks = ptmMaps(ptm, normals, albedo, threads);
  if (fallbackCount) *fallbackCount = fallbacks;
}

Image normalMap(const formats::HshFile& hsh, int* fallbackCount, int threads) {
  Image out = normalImage(hsh.width, hsh.height);
  const int fallbacks = forEachTexel(hsh.width, hsh.height, threads, [&](int x, int y) {
    std::array<double, 3> b[3];
    hshLambert(hsh, x, y, b);
    std::array<double, 3> sum{}, n;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) sum[r] += b[c][r] / 3.0;
    const bool ok = normalFromLambert(sum, &n);
    for (int c = 0; c < 3; ++c) out.at(x, y, c) = encodeUnit(n[c]);
    return ok ? 0 : 1;
  });
  if (fallbackCount) *fallbackCount = fallbacks;
  return out;
}

Image albedoMap(const formats::PtmFile& ptm, int threads) {
  Image out = albedoImage(ptm.width, ptm.height);
  ptmMaps(ptm, nullptr, &out, threads);
  return out;
}

Image albedoMap(const formats::HshFile& hsh, int threads) {
  Image out = albedoImage(hsh.width, hsh.height);
  forEachTexel(hsh.width, hsh.height, threads, [&](int x, int y) {
    std::array<double, 3> b[3];
    hshLambert(hsh, x, y, b);
    std::array<double, 3> sum{}, n;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) sum[r] += b[c][r] / 3.0;
    normalFromLambert(sum, &n);  // (0, 0, 1) where there is no normal, as normalMap gives
    double w[16];
    hshBasis(n[0], n[1], n[2], hsh.terms, w);
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      for (int t = 0; t < hsh.terms; ++t) v += w[t] * hsh.coefficient(x, y, c, t);
      out.at(x, y, c) = encodeByte(255 * v);  // 0..255 units, as the PTM's
    }
    return 0;
  });
  return out;
}

}  // namespace surrogate::fit
