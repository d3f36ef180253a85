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
  if (k.srgb)
    for (int i = 0; i < k.n; ++i) {
      const double* __restrict fi = k.f + i * kBlock;
      double* __restrict pi = k.fp + i * kBlock;
      for (int b = 0; b < len; ++b) pi[b] = rootWith(k.pw, fi[b]);
    }
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

// Four pixels at once: GCC's vector extension, each lane rounded as a double (no fused
// multiply-add: -ffp-contract=off and no "fma" target), so a lane's value does not depend on
// its neighbours or on the instruction set. The accumulators of a pixel group stay in registers
// while every photograph is added, in photograph order.
typedef double V __attribute__((vector_size(32), aligned(8)));
constexpr int kLanes = 4;
#define NEAR_LOAD(v, p) __builtin_memcpy(&(v), (p), sizeof(V))
#define NEAR_STORE(p, v) __builtin_memcpy((p), &(v), sizeof(V))

// The errors' two shared pieces: the photograph's Rec. 709 luminance at pixel b of a row
// (0..255 units), and a row's squared errors added to a light's sum in pixel order.
template <typename Sample>
SURROGATE_INLINE double capturedLuminance(const Sample* s, int b) {
  return (kLumR * sampleValue(s[3 * b]) + kLumG * sampleValue(s[3 * b + 1]) + kLumB * sampleValue(s[3 * b + 2])) *
         (1.0 / 257.0);
}
SURROGATE_INLINE void addInOrder(const double* d2, int len, double* sum) {
  double err = *sum;
  for (int b = 0; b < len; ++b) err += d2[b];
  *sum = err;
}

// o[b] = scaledWith(sample b, fi[b], pi[b]) for the samples s[3 b] (one channel of a row),
// four at a time above the toe (the same operations lane by lane as scaledWith's, so the same
// bits), one at a time where a lane is in the toe.
template <typename Sample>
SURROGATE_INLINE void scaleSrgb(const Ctx& k, const Sample* s, const double* fi, const double* pi, double* o,
                                int len) {
  int b = 0;
  for (; b + kLanes <= len; b += kLanes) {
    const V v = V{static_cast<double>(sampleValue(s[3 * b])), static_cast<double>(sampleValue(s[3 * b + 3])),
                  static_cast<double>(sampleValue(s[3 * b + 6])), static_cast<double>(sampleValue(s[3 * b + 9]))} *
                (1.0 / 65535.0);
    V p;
    NEAR_LOAD(p, pi + b);
    const V y = (v + 0.055) * p - 0.055;
    const auto above = (v > kToe) & (y > kToe);
    if (above[0] & above[1] & above[2] & above[3]) {
      const V r = y * 65535.0;
      NEAR_STORE(o + b, r);
    } else {
      for (int j = b; j < b + kLanes; ++j) o[j] = scaledWith(k.dec16, k.enc, sampleValue(s[3 * j]), fi[j], pi[j]);
    }
  }
  for (; b < len; ++b) o[b] = scaledWith(k.dec16, k.enc, sampleValue(s[3 * b]), fi[b], pi[b]);
}

// m[b] = unscaledWith(m[b], gi[b], gp[b]) in place, four at a time above the toe (the same
// operations lane by lane), one at a time where a lane is in the toe.
SURROGATE_INLINE void unscaleSrgb(const Ctx& k, double* m, const double* gi, const double* gp, int len) {
  int b = 0;
  for (; b + kLanes <= len; b += kLanes) {
    V v, p;
    NEAR_LOAD(v, m + b);
    NEAR_LOAD(p, gp + b);
    v = v * (1.0 / 255.0);
    const V y = (v + 0.055) * p - 0.055;
    const auto above = (v > kToe) & (y > kToe);
    if (above[0] & above[1] & above[2] & above[3]) {
      const V r = 255.0 * y;
      NEAR_STORE(m + b, r);
    } else {
      for (int j = b; j < b + kLanes; ++j) m[j] = unscaledWith(k.dec, k.enc, m[j], gi[j], gp[j]);
    }
  }
  for (; b < len; ++b) m[b] = unscaledWith(k.dec, k.enc, m[b], gi[b], gp[b]);
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
    for (int ch = 0; ch < 3; ++ch) {
      double* __restrict o = k.fs + (ch * k.n + i) * kBlock;
      const double* __restrict pi = k.fp + i * kBlock;
      if (k.srgb)
        scaleSrgb(k, s + ch, fi, pi, o, len);
      else
        for (int b = 0; b < len; ++b) o[b] = fi[b] * sampleValue(s[3 * b + ch]);
      for (int b = len; b < up; ++b) o[b] = 0.0;
    }
  }
  return up;
}

template <typename Sample>
SURROGATE_INLINE void fitChannelsBody(const Ctx& k, const Sample* const* images, double* out) {
  const std::size_t m = static_cast<std::size_t>(k.w) * 3;
  const int n = k.n, T = k.terms;
  NEAR_FOR_BLOCKS(k) {
    const int up = blockSamples(k, images, c, x0, len, 0.0, true);
    const double* Rc = k.R + c * k.stride;
    const double* Dc = k.D + c * k.stride;
    for (int j = 0; j < T; ++j) {
      const double* __restrict p0 = Rc + j * n;
      const double* __restrict d = Dc + j * n;
      for (int b = 0; b < up; b += kLanes) {
        V t, a0 = {}, a1 = {}, a2 = {};
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
        }
        NEAR_STORE(k.acc + (0 * T + j) * kBlock + b, a0);
        NEAR_STORE(k.acc + (1 * T + j) * kBlock + b, a1);
        NEAR_STORE(k.acc + (2 * T + j) * kBlock + b, a2);
      }
    }
    for (int j = 0; j < T; ++j)
      for (int ch = 0; ch < 3; ++ch) {
        const double* a = k.acc + (ch * T + j) * kBlock;
        double* o = out + j * m + 3 * static_cast<std::size_t>(x0) + ch;
        for (int b = 0; b < len; ++b) o[3 * b] = a[b];
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
    double* __restrict r = k.fs;  // 3 x kBlock rendered, then kBlock squared errors
    for (int i = 0; i < n; ++i) {
      for (int b = 0; b < up; b += kLanes) {
        V t, r0 = {}, r1 = {}, r2 = {};
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
        }
        NEAR_STORE(r + b, r0);
        NEAR_STORE(r + kBlock + b, r1);
        NEAR_STORE(r + 2 * kBlock + b, r2);
      }
      const Sample* __restrict s = images[i] + 3 * static_cast<std::size_t>(x0);
      const double* __restrict gi = k.f + i * kBlock;
      const double* __restrict gp = k.fp + i * kBlock;  // sRGB: gi^(1/2.4)
      double* __restrict d2 = r + 3 * kBlock;
      if (k.srgb)  // the fall-off undone on each channel (srgbUnscaled): then plain sums
        for (int ch = 0; ch < 3; ++ch) unscaleSrgb(k, r + ch * kBlock, gi, gp, len);
      for (int b = 0; b < len; ++b) {
        const double model =
            k.srgb ? kLumR * clamp255(r[b]) + kLumG * clamp255(r[kBlock + b]) + kLumB * clamp255(r[2 * kBlock + b])
                   : kLumR * clamp255(r[b] * gi[b]) + kLumG * clamp255(r[kBlock + b] * gi[b]) +
                         kLumB * clamp255(r[2 * kBlock + b] * gi[b]);
        const double captured = capturedLuminance(s, b);
        d2[b] = (model - captured) * (model - captured);
      }
      addInOrder(d2, len, &sqErr[i]);
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

template <typename Sample>
SURROGATE_INLINE void errorsLrgbBody(const Ctx& k, const Sample* const* images, const double* __restrict cr,
                                     const double* __restrict cg, const double* __restrict cb, const double* decoded,
                                     double* sqErr) {
  const int n = k.n;
  const std::size_t basisAt = static_cast<std::size_t>(6) * n;
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
    double* __restrict lum = k.pk;
    double* __restrict d2 = k.fs;
    for (int i = 0; i < n; ++i) {
      for (int b = 0; b < up; b += kLanes) {
        V t, l = {};
        NEAR_LOAD(t, k.t + b);
        for (int j = 0; j < 6; ++j) {
          V dj;
          NEAR_LOAD(dj, dec + j * kBlock + b);
          l += (Rc[j * n + i] + t * Dc[j * n + i]) * dj;
        }
        NEAR_STORE(lum + b, l);
      }
      const Sample* __restrict s = images[i] + 3 * static_cast<std::size_t>(x0);
      const double* __restrict gi = k.f + i * kBlock;
      const double* __restrict gp = k.fp + i * kBlock;  // sRGB: gi^(1/2.4)
      // sRGB: each channel's model value (its colour times L / 255), the fall-off undone, in
      // three planes of the scratch after d2.
      double* __restrict rgb = d2 + kBlock;
      if (k.srgb) {
        const double* colour[3] = {cr + x0, cg + x0, cb + x0};
        for (int ch = 0; ch < 3; ++ch) {
          double* m = rgb + ch * kBlock;
          for (int b = 0; b < len; ++b) m[b] = colour[ch][b] * (lum[b] * (1.0 / 255.0));
          unscaleSrgb(k, m, gi, gp, len);
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
      addInOrder(d2, len, &sqErr[i]);
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
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) fitChannelsAvx2(k, images, acc);
    else fitChannelsBase(k, images, acc);
  });
}

void NearModel::errorsChannels(const RowView& row, const double* decoded, double* scratch, double* sqErr,
                               KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, true).ctx;
  k.w = row.width;
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) errorsChannelsAvx2(k, images, decoded, sqErr);
    else errorsChannelsBase(k, images, decoded, sqErr);
  });
}

void NearModel::fitLrgb(const RowView& row, double* acc, double* mean, double* scratch, KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, false).ctx;
  k.w = row.width;
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) fitLrgbAvx2(k, images, acc, mean);
    else fitLrgbBase(k, images, acc, mean);
  });
}

void NearModel::errorsLrgb(const RowView& row, const double* cr, const double* cg, const double* cb,
                           const double* decoded, double* scratch, double* sqErr, KernelIsa isa) const {
  Ctx k = startRow(row.y, scratch, true).ctx;
  k.w = row.width;
  withSamples(row, [&](auto images) {
    if (useAvx2(isa)) errorsLrgbAvx2(k, images, cr, cg, cb, decoded, sqErr);
    else errorsLrgbBase(k, images, cr, cg, cb, decoded, sqErr);
  });
}

}  // namespace surrogate::fit
