#include "fit/row_kernels.h"

#include "core/cpu_features.h"
#include "fit/stream_fit.h"

// This file is compiled with -fno-trapping-math (src/fit/CMakeLists.txt): it lets the
// compiler turn the clamps into vector selects. It changes no value, only what may happen to
// floating-point exception flags, which nothing reads.

namespace surrogate::fit {

namespace {

// clamp(v, 0, 255) as std::clamp computes it (NaN passes through), written on values so that
// it vectorises.
inline double clamp255(double v) {
  const double low = v < 0.0 ? 0.0 : v;
  return 255.0 < low ? 255.0 : low;
}

// The operations and their order per value are the whole contract (see the header).
__attribute__((always_inline)) inline void lrgbBody(const double* __restrict cr, const double* __restrict cg,
                                                    const double* __restrict cb, const double* __restrict decoded,
                                                    std::size_t stride, const double* basis,
                                                    const std::uint16_t* __restrict s, std::size_t pixels,
                                                    double* __restrict d2) {
  const double b0 = basis[0], b1 = basis[1], b2 = basis[2], b3 = basis[3], b4 = basis[4], b5 = basis[5];
  for (std::size_t x = 0; x < pixels; ++x) {
    double l = 0;
    l += b0 * decoded[x];
    l += b1 * decoded[stride + x];
    l += b2 * decoded[2 * stride + x];
    l += b3 * decoded[3 * stride + x];
    l += b4 * decoded[4 * stride + x];
    l += b5 * decoded[5 * stride + x];
    double model = 0;
    model += kLumR * clamp255(cr[x] * l / 255.0);
    model += kLumG * clamp255(cg[x] * l / 255.0);
    model += kLumB * clamp255(cb[x] * l / 255.0);
    const double captured = (kLumR * s[3 * x] + kLumG * s[3 * x + 1] + kLumB * s[3 * x + 2]) / 257.0;
    d2[x] = (model - captured) * (model - captured);
  }
}

__attribute__((always_inline)) inline void rgbBody(const double* __restrict p, const std::uint16_t* __restrict s,
                                                   std::size_t pixels, double* __restrict d2) {
  for (std::size_t x = 0; x < pixels; ++x) {
    const double r = clamp255(p[3 * x]);
    const double g = clamp255(p[3 * x + 1]);
    const double b = clamp255(p[3 * x + 2]);
    const double model = kLumR * r + kLumG * g + kLumB * b;
    const double captured = (kLumR * s[3 * x] + kLumG * s[3 * x + 1] + kLumB * s[3 * x + 2]) / 257.0;
    d2[x] = (model - captured) * (model - captured);
  }
}

__attribute__((always_inline)) inline void accumulateBody(const std::uint16_t* const* images, int n,
                                                          std::size_t w, std::size_t x0, std::size_t x1,
                                                          const double* p, const double* weight,
                                                          double* __restrict acc, double* __restrict mean,
                                                          double* __restrict sum) {
  for (int i = 0; i < n; ++i) {
    const std::uint16_t* __restrict s = images[i];
    for (std::size_t x = x0; x < x1; ++x) sum[x] = static_cast<double>(s[3 * x] + s[3 * x + 1] + s[3 * x + 2]);
    for (int k = 0; k < 6; ++k) {
      const double pk = p[static_cast<std::size_t>(k) * n + i];
      double* __restrict a = acc + k * w;
      for (std::size_t x = x0; x < x1; ++x) a[x] += pk * sum[x];
    }
    const double wi = weight[i];
    if (wi != 0)
      for (std::size_t j = 3 * x0; j < 3 * x1; ++j) mean[j] += wi * s[j];
  }
}

// The quantisers themselves (fit/quantise.h: PtmQuantisation, HshQuantisation), a row at a time.
template <typename Quantisation>
__attribute__((always_inline)) inline void quantiseBody(const double* __restrict a, std::size_t count,
                                                        const Quantisation q, std::uint8_t* __restrict bytes,
                                                        double* __restrict decoded) {
  for (std::size_t j = 0; j < count; ++j) {
    const std::uint8_t b = q.quantise(a[j]);
    bytes[j] = b;
    decoded[j] = q.decode(b);
  }
}

// The bodies compiled for AVX2 where the compiler can target it. "avx2" alone: the compiler may
// not fuse a multiply and an add (that needs "fma"), so every operation rounds as in the
// baseline variant, which is the same body inlined into the public functions below. Elsewhere
// these are plain copies that activeKernelIsa never picks.
#if defined(__x86_64__) && defined(__GNUC__)
#define SURROGATE_AVX2_TARGET __attribute__((target("avx2")))
constexpr bool kAvx2Compiled = true;
#else
#define SURROGATE_AVX2_TARGET
constexpr bool kAvx2Compiled = false;
#endif

SURROGATE_AVX2_TARGET void accumulateAvx2(const std::uint16_t* const* images, int n, std::size_t w, std::size_t x0,
                                          std::size_t x1, const double* p, const double* weight, double* acc,
                                          double* mean, double* sum) {
  accumulateBody(images, n, w, x0, x1, p, weight, acc, mean, sum);
}
SURROGATE_AVX2_TARGET void lrgbAvx2(const double* cr, const double* cg, const double* cb, const double* decoded,
                                    std::size_t stride, const double* basis, const std::uint16_t* s,
                                    std::size_t pixels, double* d2) {
  lrgbBody(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
}
SURROGATE_AVX2_TARGET void rgbAvx2(const double* p, const std::uint16_t* s, std::size_t pixels, double* d2) {
  rgbBody(p, s, pixels, d2);
}
SURROGATE_AVX2_TARGET void ptmAvx2(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes,
                                   double* decoded) {
  quantiseBody(a, count, q, bytes, decoded);
}
SURROGATE_AVX2_TARGET void hshAvx2(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes,
                                   double* decoded) {
  quantiseBody(a, count, q, bytes, decoded);
}

}  // namespace

KernelIsa activeKernelIsa() { return kAvx2Compiled && cpuHasAvx2() ? KernelIsa::Avx2 : KernelIsa::Baseline; }

void accumulateLrgb(const std::uint16_t* const* images, int n, std::size_t w, std::size_t x0, std::size_t x1,
                    const double* p, const double* weight, double* acc, double* mean, double* sum, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return accumulateAvx2(images, n, w, x0, x1, p, weight, acc, mean, sum);
  accumulateBody(images, n, w, x0, x1, p, weight, acc, mean, sum);
}

void squaredErrorsLrgb(const double* cr, const double* cg, const double* cb, const double* decoded,
                       std::size_t stride, const double* basis, const std::uint16_t* s, std::size_t pixels,
                       double* d2, KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return lrgbAvx2(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
  lrgbBody(cr, cg, cb, decoded, stride, basis, s, pixels, d2);
}

void squaredErrorsRgb(const double* rendered, const std::uint16_t* s, std::size_t pixels, double* d2,
                      KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return rgbAvx2(rendered, s, pixels, d2);
  rgbBody(rendered, s, pixels, d2);
}

void quantisePtm(const double* a, std::size_t count, const PtmQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return ptmAvx2(a, count, q, bytes, decoded);
  quantiseBody(a, count, q, bytes, decoded);
}

void quantiseHsh(const double* a, std::size_t count, const HshQuantisation& q, std::uint8_t* bytes, double* decoded,
                 KernelIsa isa) {
  if (isa == KernelIsa::Avx2) return hshAvx2(a, count, q, bytes, decoded);
  quantiseBody(a, count, q, bytes, decoded);
}

}  // namespace surrogate::fit
