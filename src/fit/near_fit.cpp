// The per-pixel inverses of a fit under lights at known positions (fit/near_fit.h).
#include "fit/near_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/basis.h"
#include "fit/pseudo_inverse.h"
#include "fit/row_kernels.h"
#include "fit/near_srgb_blocks.h"
#include "fit/srgb_falloff.h"

namespace surrogate::fit {

namespace {

// Pixels per block of the kernels: a block's fall-off-scaled samples (3 N doubles a pixel)
// stay in the first-level cache for 36 photographs.
constexpr int kBlock = 32;

#if defined(__x86_64__) && defined(__GNUC__)
#define SURROGATE_NEAR_AVX2 __attribute__((target("avx2")))
constexpr bool kAvx2Compiled = true;
#else
#define SURROGATE_NEAR_AVX2
constexpr bool kAvx2Compiled = false;
#endif
#define SURROGATE_INLINE __attribute__((always_inline)) inline

inline double clamp255(double v) {  // as row_kernels.cpp: std::clamp(v, 0, 255) on values
  const double low = v < 0.0 ? 0.0 : v;
  return 255.0 < low ? 255.0 : low;
}

using namespace falloff;

// One row's view of the model: the nodes interpolated to the row (R, cols x stride), their
// differences along x (D), the per-light parts of the squared distances, and block scratch.
struct Ctx {
  int n, terms, g, cols, w;
  bool srgb;  // samples sRGB-encoded: the fall-off applied in linear light (srgbScaled)
  const double* dec16;  // the sRGB tables (SrgbTables)
  const double* enc;
  const double* dec;
  std::size_t stride;
  const double* R;
  const double* D;
  const double* e;      // (Y_i + y)^2 + Z_i^2
  const double* x;      // X_i
  const double* inv;    // 1 / r_i^2
  const std::uint8_t* near;
  double* t;            // kBlock
  double* f;            // N x kBlock: f_i, or 1 / f_i for the errors
  double* fs;           // 3 N x kBlock
  double* pk;           // kBlock
  double* acc;          // 3 T x kBlock
  double* fp;           // N x kBlock, sRGB only: f_i^(1/2.4) (of what f holds)
  const double* pw;     // the table of rootWith (SrgbTables::root)
  bool avx2;            // the sRGB blocks' AVX2 variant (near_srgb_blocks.h)
  bool lanes;           // errors summed in eight lanes per block (ErrorMeasure::Lanes, fit.h)
};

// The block [x0, x1) of cell c: fills t and, for every light, f, or `over` / f when `over` is not
// 0 (the errors: one division per pixel and light, the rest multiplications).
SURROGATE_INLINE void blockFalloff(const Ctx& k, int c, int x0, int len, double over) {
  for (int b = 0; b < len; ++b) k.t[b] = static_cast<double>(x0 + b - c * k.g) / k.g;
  for (int i = 0; i < k.n; ++i) {
    double* __restrict fi = k.f + i * kBlock;
    if (!k.near[i]) {
      for (int b = 0; b < len; ++b) fi[b] = over != 0 ? over : 1.0;
      continue;
    }
    const double xi = k.x[i], ei = k.e[i], ri = k.inv[i];
    for (int b = 0; b < len; ++b) {
      const double dx = xi - static_cast<double>(x0 + b);
      fi[b] = (dx * dx + ei) * ri;
    }
    if (over != 0)
      for (int b = 0; b < len; ++b) fi[b] = over / fi[b];
  }
  // sRGB: the roots f^(1/2.4) are made light by light where they are used (scaleSrgbBlock, the
  // errors' loops), for the square roots to overlap the other work.
}

// The row's blocks, left to right, none across a node column: the one starting at x0 lies in
// cell *c and is *len pixels long. (A loop, not a function taking a lambda: a lambda's body would
// not be compiled for the AVX2 target of the function it is written in.)
SURROGATE_INLINE void nextBlock(const Ctx& k, int x0, int* c, int* len) {
  *c = std::min(x0 / k.g, k.cols - 2);
  const int cellEnd = *c == k.cols - 2 ? k.w : (*c + 1) * k.g;
  *len = std::min({k.w, cellEnd, x0 + kBlock}) - x0;
}
#define NEAR_FOR_BLOCKS(k) \
  for (int x0 = 0, c = 0, len = 0; x0 < (k).w && (nextBlock((k), x0, &c, &len), true); x0 += len)

// The errors' two shared pieces: the photograph's Rec. 709 luminance at pixel b of a row
// (0..255 units), and a block's squared errors added to a light's sum (as Ctx::lanes says).
template <typename Sample>
SURROGATE_INLINE double capturedLuminance(const Sample* s, int b) {
  return (kLumR * sampleValue(s[3 * b]) + kLumG * sampleValue(s[3 * b + 1]) + kLumB * sampleValue(s[3 * b + 2])) *
         (1.0 / 257.0);
}
SURROGATE_INLINE void addBlockErrors(const Ctx& k, const double* d2, int len, double* sum) {
  if (!k.lanes) {  // RtiFit version 7: one pixel after the other
    double err = *sum;
    for (int b = 0; b < len; ++b) err += d2[b];
    *sum = err;
    return;
  }
  // Version 8: pixel b of the block (below its last multiple of 8) into lane b mod 8, the lanes
  // combined pairwise, the rest in order, then the block's sum added to the light's. Both
  // variants compile this same code, so their sums stay the same bits.
  double part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int b = 0;
  for (; b + 8 <= len; b += 8)
    for (int j = 0; j < 8; ++j) part[j] += d2[b + j];
  double err = ((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7]));
  for (; b < len; ++b) err += d2[b];
  *sum += err;
}

// Fills f (and, for `samples`, fs: the fall-off-scaled samples in planes ch * n + i) for the
// block, zero beyond `len` up to whole lane groups.
template <typename Sample>
SURROGATE_INLINE int blockSamples(const Ctx& k, const Sample* const* images, int c, int x0, int len, double over,
                                  bool samples) {
  blockFalloff(k, c, x0, len, over);
  const int up = (len + kLanes - 1) / kLanes * kLanes;
  for (int b = len; b < up; ++b) k.t[b] = 0.0;
  for (int i = 0; i < k.n; ++i) {
    double* __restrict fi = k.f + i * kBlock;
    for (int b = len; b < up; ++b) fi[b] = 0.0;
    if (!samples) continue;
    const Sample* __restrict s = images[i] + 3 * static_cast<std::size_t>(x0);
    double* const out[3] = {k.fs + i * kBlock, k.fs + (k.n + i) * kBlock, k.fs + (2 * k.n + i) * kBlock};
    if (k.srgb) scaleSrgbBlock(k.avx2, k.dec16, k.enc, k.pw, s, fi, k.fp + i * kBlock, out, len);
    for (int ch = 0; ch < 3; ++ch) {
      double* __restrict o = out[ch];
      if (!k.srgb)
        for (int b = 0; b < len; ++b) o[b] = fi[b] * sampleValue(s[3 * b + ch]);
      for (int b = len; b < up; ++b) o[b] = 0.0;
    }
  }
  return up;
}

// Terms j .. j + kTerms - 1 (one or two) of a block's coefficients into acc (planes ch * T +
// term): for each term and channel, the sum over the photographs, in order, of the cell's
// pseudo-inverse row interpolated at t (R + t D) times the channel's fall-off-scaled samples
// (fs). The sums are named, not an array: as an array GCC kept them out of registers (the hsh2
// near fit 0.26 -> 0.32 s).
template <int kTerms>
SURROGATE_INLINE void termSums(const Ctx& k, const double* Rc, const double* Dc, int j, int up) {
  static_assert(kTerms == 1 || kTerms == 2, "one or two terms at a time");
  const int n = k.n, T = k.terms;
  const double* __restrict p0 = Rc + j * n;
  const double* __restrict d = Dc + j * n;
  const double* __restrict q0 = kTerms == 2 ? p0 + n : p0;  // the second term's (read for two)
  const double* __restrict e = kTerms == 2 ? d + n : d;
  for (int b = 0; b < up; b += kLanes) {
    V t, a0 = {}, a1 = {}, a2 = {}, b0 = {}, b1 = {}, b2 = {};
    NEAR_LOAD(t, k.t + b);
    for (int i = 0; i < n; ++i) {
      const V pk = p0[i] + t * d[i];
      V s0, s1, s2;
      NEAR_LOAD(s0, k.fs + i * kBlock + b);
      NEAR_LOAD(s1, k.fs + (n + i) * kBlock + b);
      NEAR_LOAD(s2, k.fs + (2 * n + i) * kBlock + b);
      a0 += pk * s0;
      a1 += pk * s1;
      a2 += pk * s2;
      if constexpr (kTerms == 2) {
        const V qk = q0[i] + t * e[i];
        b0 += qk * s0;
        b1 += qk * s1;
        b2 += qk * s2;
      }
    }
    NEAR_STORE(k.acc + (0 * T + j) * kBlock + b, a0);
    NEAR_STORE(k.acc + (1 * T + j) * kBlock + b, a1);
    NEAR_STORE(k.acc + (2 * T + j) * kBlock + b, a2);
    if constexpr (kTerms == 2) {
      NEAR_STORE(k.acc + (0 * T + j + 1) * kBlock + b, b0);
      NEAR_STORE(k.acc + (1 * T + j + 1) * kBlock + b, b1);
      NEAR_STORE(k.acc + (2 * T + j + 1) * kBlock + b, b2);
    }
  }
}

template <typename Sample>
SURROGATE_INLINE void fitChannelsBody(const Ctx& k, const Sample* const* images, double* out) {
  const std::size_t m = static_cast<std::size_t>(k.w) * 3;
  const int T = k.terms;
  NEAR_FOR_BLOCKS(k) {
    const int up = blockSamples(k, images, c, x0, len, 0.0, true);
    const double* Rc = k.R + c * k.stride;
    const double* Dc = k.D + c * k.stride;
    // Two terms at once: six sums in flight rather than three hide the additions' latency (each
    // sum still adds the photographs in order).
    int j = 0;
    for (; j + 1 < T; j += 2) termSums<2>(k, Rc, Dc, j, up);
    if (j < T) termSums<1>(k, Rc, Dc, j, up);  // an odd count's last term
    for (int j = 0; j < T; ++j)
      for (int ch = 0; ch < 3; ++ch) {
        const double* a = k.acc + (ch * T + j) * kBlock;
        double* o = out + j * m + 3 * static_cast<std::size_t>(x0) + ch;
        for (int b = 0; b < len; ++b) o[3 * b] = a[b];
      }
  }
}

// Light i's squared luminance errors over the block, added to sqErr[i]: r holds the three
// rendered channels (planes of kBlock) and is overwritten; d2 is kBlock of scratch.
template <typename Sample>
SURROGATE_INLINE void channelErrors(const Ctx& k, const Sample* const* images, int i, int x0, int len, double* r,
                                    double* __restrict d2, double* sqErr) {
  const Sample* __restrict s = images[i] + 3 * static_cast<std::size_t>(x0);
  const double* __restrict gi = k.f + i * kBlock;
  double* __restrict gp = k.fp + i * kBlock;  // sRGB: gi^(1/2.4)
  const double* planes[3] = {r, r + kBlock, r + 2 * kBlock};
  if (k.srgb && unscaledErrorsBlock(k.avx2, k.dec, k.enc, k.pw, planes, nullptr, gi, gp, s, d2, len))
    return addBlockErrors(k, d2, len, &sqErr[i]);
  if (k.srgb) {  // the fall-off undone on each channel (srgbUnscaled): then plain sums
    rootsBlock(k.avx2, k.pw, gi, gp, len);
    for (int ch = 0; ch < 3; ++ch) unscaleSrgbBlock(k.avx2, k.dec, k.enc, r + ch * kBlock, gi, gp, len);
  }
  for (int b = 0; b < len; ++b) {
    const double model =
        k.srgb ? kLumR * clamp255(r[b]) + kLumG * clamp255(r[kBlock + b]) + kLumB * clamp255(r[2 * kBlock + b])
               : kLumR * clamp255(r[b] * gi[b]) + kLumG * clamp255(r[kBlock + b] * gi[b]) +
                     kLumB * clamp255(r[2 * kBlock + b] * gi[b]);
    const double captured = capturedLuminance(s, b);
    d2[b] = (model - captured) * (model - captured);
  }
  addBlockErrors(k, d2, len, &sqErr[i]);
}

// Lights i .. i + kLights - 1 (one or two) rendered over a block: for each light and channel,
// the sum over the terms, in order, of the cell's basis at the light interpolated at t (R + t D)
// times the block's decoded coefficients (dec, planes ch * T + j), into r's three planes (the
// second light into q's). Named sums, as termSums says why.
template <int kLights>
SURROGATE_INLINE void lightRenders(const Ctx& k, const double* Rc, const double* Dc, const double* dec, int i,
                                   int up, double* __restrict r, double* __restrict q) {
  static_assert(kLights == 1 || kLights == 2, "one or two lights at a time");
  const int n = k.n, T = k.terms;
  for (int b = 0; b < up; b += kLanes) {
    V t, r0 = {}, r1 = {}, r2 = {}, q0 = {}, q1 = {}, q2 = {};
    NEAR_LOAD(t, k.t + b);
    for (int j = 0; j < T; ++j) {
      const V bk = Rc[j * n + i] + t * Dc[j * n + i];
      V d0, d1, d2;
      NEAR_LOAD(d0, dec + j * kBlock + b);
      NEAR_LOAD(d1, dec + (T + j) * kBlock + b);
      NEAR_LOAD(d2, dec + (2 * T + j) * kBlock + b);
      r0 += bk * d0;
      r1 += bk * d1;
      r2 += bk * d2;
      if constexpr (kLights == 2) {
        const V ck = Rc[j * n + i + 1] + t * Dc[j * n + i + 1];
        q0 += ck * d0;
        q1 += ck * d1;
        q2 += ck * d2;
      }
    }
    NEAR_STORE(r + b, r0);
    NEAR_STORE(r + kBlock + b, r1);
    NEAR_STORE(r + 2 * kBlock + b, r2);
    if constexpr (kLights == 2) {
      NEAR_STORE(q + b, q0);
      NEAR_STORE(q + kBlock + b, q1);
      NEAR_STORE(q + 2 * kBlock + b, q2);
    }
  }
}

template <typename Sample>
SURROGATE_INLINE void errorsChannelsBody(const Ctx& k, const Sample* const* images, const double* decoded,
                                         double* sqErr) {
  const std::size_t m = static_cast<std::size_t>(k.w) * 3;
  const int n = k.n, T = k.terms;
  const std::size_t basisAt = static_cast<std::size_t>(T) * n;
  NEAR_FOR_BLOCKS(k) {
    const int up = blockSamples(k, images, c, x0, len, 1.0, false);
    double* dec = k.acc;  // the block's decoded coefficients in planes ch * T + j
    for (int j = 0; j < T; ++j)
      for (int ch = 0; ch < 3; ++ch) {
        const double* src = decoded + j * m + 3 * static_cast<std::size_t>(x0) + ch;
        double* o = dec + (ch * T + j) * kBlock;
        for (int b = 0; b < len; ++b) o[b] = src[3 * b];
        for (int b = len; b < up; ++b) o[b] = 0.0;
      }
    const double* Rc = k.R + c * k.stride + basisAt;
    const double* Dc = k.D + c * k.stride + basisAt;
    // Two lights at once (six sums in flight, each adding the terms in order): light i rendered
    // in r's planes 0..2, light i + 1 in 3..5; the squared errors in pk.
    double* __restrict r = k.fs;
    double* __restrict q = r + 3 * kBlock;
    int i = 0;
    for (; i + 1 < n; i += 2) {
      lightRenders<2>(k, Rc, Dc, dec, i, up, r, q);
      channelErrors(k, images, i, x0, len, r, k.pk, sqErr);
      channelErrors(k, images, i + 1, x0, len, q, k.pk, sqErr);
    }
    if (i < n) {  // an odd count's last light
      lightRenders<1>(k, Rc, Dc, dec, i, up, r, q);
      channelErrors(k, images, i, x0, len, r, k.pk, sqErr);
    }
  }
}

template <typename Sample>
SURROGATE_INLINE void fitLrgbBody(const Ctx& k, const Sample* const* images, double* acc, double* mean) {
  const int n = k.n;
  const std::size_t weightsAt = 2 * static_cast<std::size_t>(6) * n;
  NEAR_FOR_BLOCKS(k) {
    const int up = blockSamples(k, images, c, x0, len, 0.0, true);
    const double* Rc = k.R + c * k.stride;
    const double* Dc = k.D + c * k.stride;
    double* sums = k.acc;  // 9 x kBlock: the six coefficients, then the mean colour's planes
    for (int b = 0; b < up; b += kLanes) {
      V t, a[6] = {}, m0 = {}, m1 = {}, m2 = {};
      NEAR_LOAD(t, k.t + b);
      for (int i = 0; i < n; ++i) {
        V s0, s1, s2;
        NEAR_LOAD(s0, k.fs + i * kBlock + b);
        NEAR_LOAD(s1, k.fs + (n + i) * kBlock + b);
        NEAR_LOAD(s2, k.fs + (2 * n + i) * kBlock + b);
        const V sum = s0 + s1 + s2;  // f (R + G + B)
        for (int j = 0; j < 6; ++j) a[j] += (Rc[j * n + i] + t * Dc[j * n + i]) * sum;
        const V wk = Rc[weightsAt + i] + t * Dc[weightsAt + i];
        m0 += wk * s0;
        m1 += wk * s1;
        m2 += wk * s2;
      }
      for (int j = 0; j < 6; ++j) NEAR_STORE(sums + j * kBlock + b, a[j]);
      NEAR_STORE(sums + 6 * kBlock + b, m0);
      NEAR_STORE(sums + 7 * kBlock + b, m1);
      NEAR_STORE(sums + 8 * kBlock + b, m2);
    }
    for (int j = 0; j < 6; ++j)
      for (int b = 0; b < len; ++b) acc[j * k.w + x0 + b] += sums[j * kBlock + b];
    for (int b = 0; b < len; ++b)
      for (int ch = 0; ch < 3; ++ch) mean[3 * static_cast<std::size_t>(x0 + b) + ch] += sums[(6 + ch) * kBlock + b];
  }
}

// The luminance of the block re-rendered at lights i .. i + L - 1 (lum, L planes of kBlock): L
// sums in flight hide the additions' latency; each adds the six terms in order.
template <int L>
SURROGATE_INLINE void lrgbLuminance(const Ctx& k, const double* Rc, const double* Dc, const double* dec, int i,
                                    int up, double* __restrict lum) {
  const int n = k.n;
  for (int b = 0; b < up; b += kLanes) {
    V t, l[L];
    NEAR_LOAD(t, k.t + b);
    for (int q = 0; q < L; ++q) l[q] = V{};
    for (int j = 0; j < 6; ++j) {
      V dj;
      NEAR_LOAD(dj, dec + j * kBlock + b);
      for (int q = 0; q < L; ++q) l[q] += (Rc[j * n + i + q] + t * Dc[j * n + i + q]) * dj;
    }
    for (int q = 0; q < L; ++q) NEAR_STORE(lum + q * kBlock + b, l[q]);
  }
}

// Light i's squared luminance errors over the block, added to sqErr[i]; d2 is 4 planes of
// kBlock of scratch.
template <typename Sample>
SURROGATE_INLINE void lrgbErrors(const Ctx& k, const Sample* const* images, const double* __restrict cr,
                                 const double* __restrict cg, const double* __restrict cb, int i, int x0, int len,
                                 const double* __restrict lum, double* __restrict d2, double* sqErr) {
  const Sample* __restrict s = images[i] + 3 * static_cast<std::size_t>(x0);
  const double* __restrict gi = k.f + i * kBlock;
  double* __restrict gp = k.fp + i * kBlock;  // sRGB: gi^(1/2.4)
  // sRGB: each channel's model value (its colour times L / 255), the fall-off undone, in
  // three planes of the scratch after d2.
  double* __restrict rgb = d2 + kBlock;
  const double* colour[3] = {cr + x0, cg + x0, cb + x0};
  if (k.srgb && unscaledErrorsBlock(k.avx2, k.dec, k.enc, k.pw, colour, lum, gi, gp, s, d2, len))
    return addBlockErrors(k, d2, len, &sqErr[i]);
  if (k.srgb) {
    rootsBlock(k.avx2, k.pw, gi, gp, len);
    for (int ch = 0; ch < 3; ++ch) {
      double* m = rgb + ch * kBlock;
      for (int b = 0; b < len; ++b) m[b] = colour[ch][b] * (lum[b] * (1.0 / 255.0));
      unscaleSrgbBlock(k.avx2, k.dec, k.enc, m, gi, gp, len);
    }
  }
  for (int b = 0; b < len; ++b) {
    double model;
    if (k.srgb) {
      model = kLumR * clamp255(rgb[b]) + kLumG * clamp255(rgb[kBlock + b]) + kLumB * clamp255(rgb[2 * kBlock + b]);
    } else {
      const double l = lum[b] * gi[b];  // gi = 1 / (255 f)
      model = kLumR * clamp255(cr[x0 + b] * l) + kLumG * clamp255(cg[x0 + b] * l) + kLumB * clamp255(cb[x0 + b] * l);
    }
    const double captured = capturedLuminance(s, b);
    d2[b] = (model - captured) * (model - captured);
  }
  addBlockErrors(k, d2, len, &sqErr[i]);
}

template <typename Sample>
SURROGATE_INLINE void errorsLrgbBody(const Ctx& k, const Sample* const* images, const double* __restrict cr,
                                     const double* __restrict cg, const double* __restrict cb, const double* decoded,
                                     double* sqErr) {
  const int n = k.n;
  const std::size_t basisAt = static_cast<std::size_t>(6) * n;
  constexpr int kLights = 4;  // lights rendered at once
  NEAR_FOR_BLOCKS(k) {
    // gi = 1 / (255 f); sRGB: 1 / f, the model's value made first (its colour times L / 255).
    const int up = blockSamples(k, images, c, x0, len, k.srgb ? 1.0 : 1.0 / 255.0, false);
    double* dec = k.acc;  // the block's six decoded planes
    for (int j = 0; j < 6; ++j) {
      for (int b = 0; b < len; ++b) dec[j * kBlock + b] = decoded[j * k.w + x0 + b];
      for (int b = len; b < up; ++b) dec[j * kBlock + b] = 0.0;
    }
    const double* Rc = k.R + c * k.stride + basisAt;
    const double* Dc = k.D + c * k.stride + basisAt;
    // The scratch of the errors: fs's planes 0..3 (3 N >= 18 planes for 6 terms), the
    // luminances after them.
    double* __restrict d2 = k.fs;
    double* __restrict lum = k.fs + 4 * kBlock;
    int i = 0;
    for (; i + kLights <= n; i += kLights) {
      lrgbLuminance<kLights>(k, Rc, Dc, dec, i, up, lum);
      for (int q = 0; q < kLights; ++q) lrgbErrors(k, images, cr, cg, cb, i + q, x0, len, lum + q * kBlock, d2, sqErr);
    }
    for (; i < n; ++i) {
      lrgbLuminance<1>(k, Rc, Dc, dec, i, up, lum);
      lrgbErrors(k, images, cr, cg, cb, i, x0, len, lum, d2, sqErr);
    }
  }
}

// Each body twice: the baseline, and for AVX2 without FMA (the same operations, row_kernels.h).
template <typename S>
void fitChannelsBase(const Ctx& k, const S* const* im, double* out) { fitChannelsBody(k, im, out); }
template <typename S>
SURROGATE_NEAR_AVX2 void fitChannelsAvx2(const Ctx& k, const S* const* im, double* out) {
  fitChannelsBody(k, im, out);
}
template <typename S>
void errorsChannelsBase(const Ctx& k, const S* const* im, const double* d, double* e) {
  errorsChannelsBody(k, im, d, e);
}
template <typename S>
SURROGATE_NEAR_AVX2 void errorsChannelsAvx2(const Ctx& k, const S* const* im, const double* d, double* e) {
  errorsChannelsBody(k, im, d, e);
}
template <typename S>
void fitLrgbBase(const Ctx& k, const S* const* im, double* a, double* m) { fitLrgbBody(k, im, a, m); }
template <typename S>
SURROGATE_NEAR_AVX2 void fitLrgbAvx2(const Ctx& k, const S* const* im, double* a, double* m) {
  fitLrgbBody(k, im, a, m);
}
template <typename S>
void errorsLrgbBase(const Ctx& k, const S* const* im, const double* cr, const double* cg, const double* cb,
                    const double* d, double* e) {
  errorsLrgbBody(k, im, cr, cg, cb, d, e);
}
template <typename S>
SURROGATE_NEAR_AVX2 void errorsLrgbAvx2(const Ctx& k, const S* const* im, const double* cr, const double* cg,
                                        const double* cb, const double* d, double* e) {
  errorsLrgbBody(k, im, cr, cg, cb, d, e);
}

bool useAvx2(KernelIsa isa) { return kAvx2Compiled && isa == KernelIsa::Avx2; }

}  // namespace

std::size_t NearModel::scratchDoubles(int) const {
  return 2 * static_cast<std::size_t>(cols_) * stride_ + n_ +
         static_cast<std::size_t>(kBlock) * (2 + n_ + 3 * n_ + 3 * terms_ + n_ + 4);
}

struct NearModel::Row {
  Ctx ctx;
};

// The row's nodes, only the part the caller reads: the inverse (and the chroma weights) to fit,
// the basis to re-render (`basis`). Pass 2 calls both, and the parts cost alike.
NearModel::Row NearModel::startRow(int y, double* scratch, bool basis) const {
  const int gy = std::min(y / g_, rows_ - 2);
  const double v = static_cast<double>(y - gy * g_) / g_;
  const std::size_t line = static_cast<std::size_t>(cols_) * stride_;
  double* R = scratch;
  double* D = R + line;
  double* e = D + line;
  const double* n0 = nodes_.data() + static_cast<std::size_t>(gy) * line;
  const double* n1 = n0 + line;
  const std::size_t tn = static_cast<std::size_t>(terms_) * n_;
  const std::size_t from = basis ? tn : 0, to = basis ? 2 * tn : tn;
  auto part = [&](std::size_t a, std::size_t b) {
    for (int c = 0; c < cols_; ++c) {
      const std::size_t o = static_cast<std::size_t>(c) * stride_;
      for (std::size_t q = o + a; q < o + b; ++q) R[q] = n0[q] + v * (n1[q] - n0[q]);
      if (c > 0)
        for (std::size_t q = o + a; q < o + b; ++q) D[q - stride_] = R[q] - R[q - stride_];
    }
  };
  part(from, to);
  if (!basis && lrgb_) part(2 * tn, stride_);
  for (int i = 0; i < n_; ++i) {
    const double dy = yz_[2 * i] + y, dz = yz_[2 * i + 1];
    e[i] = dy * dy + dz * dz;
  }
  double* block = e + n_;
  Row r;
  Ctx& k = r.ctx;
  k.n = n_;
  k.srgb = srgb_;
  const SrgbTables& tables = srgbTables();
  k.dec16 = tables.decode16.data();
  k.enc = tables.encode.data();
  k.dec = tables.decode.data();
  k.terms = terms_;
  k.g = g_;
  k.cols = cols_;
  k.w = 0;
  k.stride = stride_;
  k.R = R;
  k.D = D;
  k.e = e;
  k.x = x_.data();
  k.inv = inv_.data();
  k.near = near_.data();
  k.t = block;
  k.pk = k.t + kBlock;
  k.f = k.pk + kBlock;
  k.fs = k.f + static_cast<std::size_t>(n_) * kBlock;
  k.acc = k.fs + static_cast<std::size_t>(3) * n_ * kBlock;
  k.fp = k.acc + static_cast<std::size_t>(3) * terms_ * kBlock;
  k.pw = tables.root.data();
  k.avx2 = false;
  k.lanes = errors_ == ErrorMeasure::Lanes;
  return r;
}

std::vector<double> NearModel::pixelInverse(int x, int y) const {
  std::vector<double> scratch(scratchDoubles(x + 1));
  const Ctx k = startRow(y, scratch.data(), false).ctx;
  const int c = std::min(x / g_, cols_ - 2);
  const double t = static_cast<double>(x - c * g_) / g_;  // as blockFalloff
  std::vector<double> p(static_cast<std::size_t>(terms_) * n_);
  for (std::size_t q = 0; q < p.size(); ++q) p[q] = k.R[c * stride_ + q] + t * k.D[c * stride_ + q];
  return p;
}

void NearModel::fitChannels(const RowView& row, double* acc, double* scratch, KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, false).ctx;
  k.w = row.width;
  k.avx2 = useAvx2(isa);
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) fitChannelsAvx2(k, images, acc);
    else fitChannelsBase(k, images, acc);
  });
}

void NearModel::errorsChannels(const RowView& row, const double* decoded, double* scratch, double* sqErr,
                               KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, true).ctx;
  k.w = row.width;
  k.avx2 = useAvx2(isa);
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) errorsChannelsAvx2(k, images, decoded, sqErr);
    else errorsChannelsBase(k, images, decoded, sqErr);
  });
}

void NearModel::fitLrgb(const RowView& row, double* acc, double* mean, double* scratch, KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, false).ctx;
  k.w = row.width;
  k.avx2 = useAvx2(isa);
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) fitLrgbAvx2(k, images, acc, mean);
    else fitLrgbBase(k, images, acc, mean);
  });
}

void NearModel::errorsLrgb(const RowView& row, const double* cr, const double* cg, const double* cb,
                           const double* decoded, double* scratch, double* sqErr, KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, true).ctx;
  k.w = row.width;
  k.avx2 = useAvx2(isa);
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) errorsLrgbAvx2(k, images, cr, cg, cb, decoded, sqErr);
    else errorsLrgbBase(k, images, cr, cg, cb, decoded, sqErr);
  });
}

}  // namespace surrogate::fit
