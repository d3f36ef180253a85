#include "fit/render.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "fit/basis.h"
#include "fit/lambert.h"
#include "fit/normal_rows.h"
#include "fit/normals.h"
#include "fit/quantise.h"
#include "fit/row_kernels.h"
#include "fit/sample_lanes.h"
#include "fit/texel.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace surrogate::fit {

namespace {
const char* const kStep = "render";

struct Light {
  double x, y, z;
};

Light checkedLight(const std::array<double, 3>& l, const RenderOptions& o) {
  const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  if (!std::isfinite(n) || n < 1e-9)
    throw Error(ErrorKind::Usage, "--light", kStep, "the light must be a non-zero direction x,y,z");
  if (!(o.diffuseGain > 0) || !std::isfinite(o.diffuseGain))
    throw Error(ErrorKind::Usage, "--gain", kStep, "the diffuse gain must be a positive number");
  if (!(o.extrapolation > 0) || !std::isfinite(o.extrapolation))
    throw Error(ErrorKind::Usage, "--extrapolation", kStep, "must be a positive number");
  if (o.specular && (!(o.kd >= 0) || !(o.ks >= 0) || !(o.specularExponent > 0)))
    throw Error(ErrorKind::Usage, "--specular", kStep,
                "kd and ks must be >= 0 and the exponent > 0");
  return {l[0] / n, l[1] / n, l[2] / n};
}

// The half vector H of the light and the view (0, 0, 1), and its length, the same at every texel.
struct HalfVector {
  explicit HalfVector(const Light& l)
      : h{l.x, l.y, l.z + 1.0}, length(std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])) {}
  // max(0, N . H / |H|); -1 when H is 0 (a light from straight behind), which has no highlight.
  double cosine(const std::array<double, 3>& n) const {
    if (length == 0) return -1;
    return std::max(0.0, (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / length);
  }
  double h[3];
  double length;
};

// The specular term ks * 255 * nh^e (nh = max(0, N . H)), and the 8-bit samples kd * diffuse +
// that term gives, exactly as with std::pow, without a pow at most texels (libm's pow was 14 %
// of the instructions of a specular preview). For a whole exponent up to kMaxWholeExponent,
// nh^e is first taken by repeated squaring, within 2e roundings of nh^e (relative 2e 2^-53,
// under 1e-13), as pow is within one: the term is then known within kMargin * ks * 255, with
// room to spare. Rounding a sum and toByte are both monotonic, so where the sample is the same
// at both ends of that interval it is the sample pow gives; elsewhere (a sum within about 1e-9
// of a half) pow decides.
class Specular {
 public:
  explicit Specular(const RenderOptions& o)
      : exponent_(o.specularExponent),
        scale_(o.ks * 255.0),
        margin_(kMargin * scale_),
        whole_(std::isfinite(scale_) && exponent_ >= 1 && exponent_ <= kMaxWholeExponent &&
                       exponent_ == std::floor(exponent_)
                   ? static_cast<int>(exponent_)
                   : 0) {}

  // The whole exponent taken by squaring (0: pow at every texel), the scale ks * 255 and the margin.
  int whole() const { return whole_; }
  double scale() const { return scale_; }
  double margin() const { return margin_; }

  // The samples of one texel whose half-vector cosine is nh (HalfVector::cosine).
  class Texel {
   public:
    Texel(const Specular& s, double nh) : s_(s), nh_(nh), exact_(nh < 0 || s.whole_ == 0) {
      if (nh < 0)
        term_ = 0;
      else if (exact_)
        term_ = s.scale_ * std::pow(nh, s.exponent_);
      else
        term_ = s.scale_ * power(nh, s.whole_);
    }
    // toSample(kdDiffuse + the term).
    std::uint16_t sample(double kdDiffuse) {
      if (!exact_) {
        const std::uint8_t lo = detail::toByte(kdDiffuse + (term_ - s_.margin_));
        if (lo == detail::toByte(kdDiffuse + (term_ + s_.margin_))) return static_cast<std::uint16_t>(lo * 257);
        term_ = s_.scale_ * std::pow(nh_, s_.exponent_);
        exact_ = true;
      }
      return static_cast<std::uint16_t>(detail::toByte(kdDiffuse + term_) * 257);
    }

   private:
    const Specular& s_;
    double nh_, term_;
    bool exact_;
  };

 private:
  static constexpr int kMaxWholeExponent = 64;
  static constexpr double kMargin = 1e-9;
  static double power(double x, int e) {
    double result = 1, square = x;
    for (; e > 0; e >>= 1) {
      if (e & 1) result *= square;
      if (e > 1) square *= square;
    }
    return result;
  }
  double exponent_, scale_, margin_;
  int whole_;  // the exponent when whole and at most kMaxWholeExponent, else 0: pow at every texel
};

Image outputImage(int w, int h) {
  Image out(w, h, 3);
  out.bitsPerSample = 8;
  out.transfer = Transfer::Srgb;
  return out;
}

// The 8-bit value as a 16-bit sample: round(v) clamped to 0..255, times 257.
std::uint16_t toSample(double v) { return static_cast<std::uint16_t>(detail::toByte(v) * 257); }

// evaluatePtm(a, lu, lv) at one light as six terms, each a function of one coefficient's byte
// alone (a_k is (byte - bias_k) scale_k, and the channels share bias and scale): tabulated for
// the 256 byte values, a texel's value is six look-ups added in evaluatePtm's order, the same
// double as evaluatePtm gives for its decoded coefficients (-ffp-contract=off, CMakeLists.txt),
// without decoding six coefficients and multiplying them at every texel.
class PtmTerms {
 public:
  PtmTerms(const formats::PtmFile& ptm, double lu, double lv) {
    for (int b = 0; b < kByteValues; ++b) {
      double a[6];
      for (int k = 0; k < 6; ++k) a[k] = (b - ptm.bias[k]) * ptm.scale[k];  // PtmFile::coefficient
      term_[0][b] = a[0] * lu * lu;
      term_[1][b] = a[1] * lv * lv;
      term_[2][b] = a[2] * lu * lv;
      term_[3][b] = a[3] * lu;
      term_[4][b] = a[4] * lv;
      term_[5][b] = a[5];
    }
  }
  // The value at the texel whose six coefficient bytes start at `bytes`.
  double evaluate(const std::uint8_t* bytes) const {
    return term_[0][bytes[0]] + term_[1][bytes[1]] + term_[2][bytes[2]] + term_[3][bytes[3]] +
           term_[4][bytes[4]] + term_[5][bytes[5]];
  }

 private:
  static constexpr int kByteValues = 256;
  double term_[6][kByteValues];
};

// The plain LRGB samples of a row, toSample(rgb * diffuse / 255) with `diffuse` given per sample
// (each texel's value three times).
void plainBody(const std::uint8_t* rgb, const double* diffuse, int count, std::uint16_t* samples) {
  for (int i = 0; i < count; ++i) samples[i] = toSample(rgb[i] * diffuse[i] / 255.0);
}
#if defined(__x86_64__) && defined(__GNUC__)
// plainBody on four samples at a time, the same operations on each value (no fused multiply-add),
// rounded as detail::roundClamped (lanes::roundClampedFour).
__attribute__((target("avx2"))) void plainAvx2(const std::uint8_t* rgb, const double* diffuse, int count,
                                               std::uint16_t* samples) {
  const __m256d top = _mm256_set1_pd(255.0), widen = _mm256_set1_pd(257.0);
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    std::int32_t four;
    std::memcpy(&four, rgb + i, sizeof four);
    const __m256d c = _mm256_cvtepi32_pd(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(four)));
    const __m256d v = _mm256_div_pd(_mm256_mul_pd(c, _mm256_loadu_pd(diffuse + i)), top);
    const __m128i s = _mm256_cvttpd_epi32(_mm256_mul_pd(lanes::roundClampedFour(v, top), widen));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(samples + i), _mm_packus_epi32(s, s));
  }
  plainBody(rgb + i, diffuse + i, count - i, samples + i);
}
#endif
#if defined(__x86_64__) && defined(__GNUC__)
// The specular LRGB samples of four texels at a time where Specular::Texel needs no pow: per
// texel HalfVector::cosine, Specular's power by squaring and the two bytes of each sample, the
// same operations on each value in the same order. done[x] is 1 for the texels written; the
// others (a sample within the margin of a half, or the last texels) are left to Specular::Texel.
struct SpecularRow {
  const double* n[3];
  const double* diffuse;     // the luminance L(lu, lv) of each texel
  const std::uint8_t* rgb;   // the row's colours
  std::uint16_t* samples;    // the row's samples
  std::uint8_t* done;
  int width;
};
__attribute__((target("avx2"))) inline __m256d byteOf(__m256d v) {
  return lanes::roundClampedFour(v, _mm256_set1_pd(255.0));
}
__attribute__((target("avx2"))) void specularAvx2(const SpecularRow& r, const HalfVector& half, const Specular& spec,
                                                  double kd) {
  const __m256d h0 = _mm256_set1_pd(half.h[0]), h1 = _mm256_set1_pd(half.h[1]), h2 = _mm256_set1_pd(half.h[2]),
                length = _mm256_set1_pd(half.length), scale = _mm256_set1_pd(spec.scale()),
                margin = _mm256_set1_pd(spec.margin()), kdv = _mm256_set1_pd(kd), range = _mm256_set1_pd(255.0),
                widen = _mm256_set1_pd(257.0);
  int x = 0;
  for (; x + 4 <= r.width; x += 4) {
    const __m256d dot = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(r.n[0] + x), h0),
                                                    _mm256_mul_pd(_mm256_loadu_pd(r.n[1] + x), h1)),
                                      _mm256_mul_pd(_mm256_loadu_pd(r.n[2] + x), h2));
    const __m256d nh = _mm256_max_pd(_mm256_div_pd(dot, length), _mm256_setzero_pd());
    __m256d result = _mm256_set1_pd(1.0), square = nh;
    for (int e = spec.whole(); e > 0; e >>= 1) {
      if (e & 1) result = _mm256_mul_pd(result, square);
      if (e > 1) square = _mm256_mul_pd(square, square);
    }
    const __m256d term = _mm256_mul_pd(scale, result);
    const __m256d below = _mm256_sub_pd(term, margin), above = _mm256_add_pd(term, margin);
    const __m256d diffuse = _mm256_loadu_pd(r.diffuse + x);
    const std::uint8_t* rgb = r.rgb + 3 * x;
    __m256d same = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    __m128i out[3];
    for (int c = 0; c < 3; ++c) {
      const __m256d colour = _mm256_set_pd(rgb[9 + c], rgb[6 + c], rgb[3 + c], rgb[c]);
      const __m256d kdd = _mm256_mul_pd(kdv, _mm256_div_pd(_mm256_mul_pd(colour, diffuse), range));
      const __m256d lo = byteOf(_mm256_add_pd(kdd, below)), hi = byteOf(_mm256_add_pd(kdd, above));
      same = _mm256_and_pd(same, _mm256_cmp_pd(lo, hi, _CMP_EQ_OQ));
      out[c] = _mm256_cvttpd_epi32(_mm256_mul_pd(lo, widen));
    }
    const int sameBits = _mm256_movemask_pd(same);
    alignas(16) std::int32_t v[3][4];
    for (int c = 0; c < 3; ++c) _mm_store_si128(reinterpret_cast<__m128i*>(v[c]), out[c]);
    for (int i = 0; i < 4; ++i) {
      r.done[x + i] = (sameBits >> i) & 1;
      if (!r.done[x + i]) continue;
      for (int c = 0; c < 3; ++c) r.samples[(x + i) * 3 + c] = static_cast<std::uint16_t>(v[c][i]);
    }
  }
  for (; x < r.width; ++x) r.done[x] = 0;
}

#endif

void plainSamples(const std::uint8_t* rgb, const double* diffuse, int count, std::uint16_t* samples) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (activeKernelIsa() == KernelIsa::Avx2) return plainAvx2(rgb, diffuse, count, samples);
#endif
  plainBody(rgb, diffuse, count, samples);
}

void forRows(int height, int threads, const std::function<void(int)>& fn) {
  parallelFor(static_cast<std::size_t>(height), 8, effectiveThreads(threads),
              [&](std::size_t b, std::size_t e) {
                for (std::size_t y = b; y < e; ++y) fn(static_cast<int>(y));
              });
}
}  // namespace

Image render(const formats::PtmFile& ptm, const std::array<double, 3>& light,
             const RenderOptions& options) {
  const Light l = checkedLight(light, options);
  const double lu = options.extrapolation * l.x, lv = options.extrapolation * l.y;
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  const bool gain = options.diffuseGain != 1.0;
  const double kd = options.specular ? options.kd : 1.0;
  Image out = outputImage(ptm.width, ptm.height);
  const PtmTerms terms(ptm, lu, lv);  // without a gain the coefficients are the file's
  const HalfVector half(l);
  const Specular specular(options);
  const std::size_t plane = ptm.texels() * 6;  // bytes of one channel's coefficients
  const PtmDecoded decoded(ptm);
  const bool plain = lrgb && !gain && !options.specular;
  // The specular LRGB picture four texels at a time (DerivedMaps' third preview) where its
  // highlight is taken by squaring; the texels it leaves by the loop below.
  bool vectorSpecular = false;
#if defined(__x86_64__) && defined(__GNUC__)
  vectorSpecular = lrgb && !gain && options.specular && specular.whole() != 0 && half.length != 0 &&
                   activeKernelIsa() == KernelIsa::Avx2;
#endif
  parallelFor(static_cast<std::size_t>(ptm.height), 8, effectiveThreads(options.threads), [&](std::size_t b, std::size_t e) {
    if (plain) {
      // The plain LRGB picture, alone in a loop of its own (two of DerivedMaps' three previews):
      // kd is 1 and there is no specular term, so the sample is toSample(d), as 1 * d + 0.0 is d.
      std::vector<double> diffuse(static_cast<std::size_t>(ptm.width) * 3);
      for (std::size_t y = b; y < e; ++y) {
        const std::size_t row = y * ptm.width;
        for (int x = 0; x < ptm.width; ++x)
          diffuse[x * 3] = diffuse[x * 3 + 1] = diffuse[x * 3 + 2] = terms.evaluate(&ptm.coefficients[(row + x) * 6]);
        plainSamples(&ptm.rgb[row * 3], diffuse.data(), ptm.width * 3, &out.pixels[row * 3]);
      }
      return;
    }
    // The normals of a row at once where the gain or the highlight needs them (fit/normal_rows.h).
    PtmNormalRow normalRow(gain || options.specular ? ptm.width : 0);
    std::vector<double> diffuseRow;
    std::vector<std::uint8_t> done(ptm.width, 0);
    for (std::size_t yy = b; yy < e; ++yy) {
      const int y = static_cast<int>(yy);
      if (gain || options.specular) normalRow.fill(ptm, decoded, plane, y);
      if (vectorSpecular) {
        const std::size_t row = yy * ptm.width;
        diffuseRow.resize(ptm.width);
        for (int x = 0; x < ptm.width; ++x) diffuseRow[x] = terms.evaluate(&ptm.coefficients[(row + x) * 6]);
        const SpecularRow r{{normalRow.n[0].data(), normalRow.n[1].data(), normalRow.n[2].data()},
                            diffuseRow.data(), &ptm.rgb[row * 3], &out.pixels[row * 3], done.data(), ptm.width};
#if defined(__x86_64__) && defined(__GNUC__)
        specularAvx2(r, half, specular, kd);
#endif
      }
      for (int x = 0; x < ptm.width; ++x) {
        if (done[x]) continue;
        std::array<double, 3> n{0, 0, 1};
        const std::uint8_t* bytes = &ptm.coefficients[(static_cast<std::size_t>(y) * ptm.width + x) * 6];
        if (gain || options.specular) n = {normalRow.n[0][x], normalRow.n[1][x], normalRow.n[2][x]};
        double diffuse[3];
        for (int c = 0; c < (lrgb ? 1 : 3); ++c) {
          if (gain) {
            diffuse[c] = evaluatePtm(applyDiffuseGain(ptmChannel(ptm, x, y, c), options.diffuseGain, n[0], n[1]), lu, lv);
          } else {
            diffuse[c] = terms.evaluate(bytes + c * plane);
          }
        }
        // Without the specular term, the sum is kd * d + 0.0, the same byte as kd * d.
        Specular::Texel spec(specular, options.specular ? half.cosine(n) : -1);
        for (int c = 0; c < 3; ++c) {
          const double d =
              lrgb ? ptm.rgb[(static_cast<std::size_t>(y) * ptm.width + x) * 3 + c] * diffuse[0] / 255.0
                   : diffuse[c];
          out.at(x, y, c) = options.specular ? spec.sample(kd * d) : toSample(kd * d);
        }
      }
    }
  });
  return out;
}

Image render(const formats::HshFile& hsh, const std::array<double, 3>& light,
             const RenderOptions& options) {
  const Light l = checkedLight(light, options);
  if (options.diffuseGain != 1.0) {
    throw Error(ErrorKind::Usage, "--gain", kStep,
                "diffuse gain is defined for PTM files only; render the .ptm instead");
  }
  double h[16];
  hshBasis(l.x, l.y, l.z, hsh.terms, h);
  const double kd = options.specular ? options.kd : 1.0;
  Image out = outputImage(hsh.width, hsh.height);
  forRows(hsh.height, options.threads, [&](int y) {
    for (int x = 0; x < hsh.width; ++x) {
      double spec = 0;
      if (options.specular) {
        std::array<double, 3> b[3], sum{}, n;
        hshLambert(hsh, x, y, b);
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r) sum[r] += b[c][r] / 3.0;
        normalFromLambert(sum, &n);
        const double nh = HalfVector(l).cosine(n);
        spec = nh < 0 ? 0 : options.ks * 255.0 * std::pow(nh, options.specularExponent);
      }
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        for (int k = 0; k < hsh.terms; ++k) v += hsh.coefficient(x, y, c, k) * h[k];
        out.at(x, y, c) = toSample(kd * 255.0 * v + spec);
      }
    }
  });
  return out;
}

namespace {
class PtmModel : public Relightable {
 public:
  explicit PtmModel(formats::PtmFile ptm) : ptm_(std::move(ptm)) {}
  int width() const override { return ptm_.width; }
  int height() const override { return ptm_.height; }
  std::string basis() const override {
    return ptm_.format == formats::PtmFile::Format::Lrgb ? "ptm-lrgb" : "ptm-rgb";
  }
  Image render(const std::array<double, 3>& light, const RenderOptions& o) const override {
    return fit::render(ptm_, light, o);
  }
  Image normalMap(int* fallbackCount, int threads) const override {
    return fit::normalMap(ptm_, fallbackCount, threads);
  }
  Image albedoMap(int threads) const override { return fit::albedoMap(ptm_, threads); }
  void normalAndAlbedoMaps(Image* normals, Image* albedo, int* fallbackCount, int threads) const override {
    fit::normalAndAlbedoMaps(ptm_, normals, albedo, fallbackCount, threads);
  }

 private:
  formats::PtmFile ptm_;
};

class HshModel : public Relightable {
 public:
  explicit HshModel(formats::HshFile hsh) : hsh_(std::move(hsh)) {}
  int width() const override { return hsh_.width; }
  int height() const override { return hsh_.height; }
  std::string basis() const override {
    return hsh_.terms == 4 ? "hsh2" : hsh_.terms == 9 ? "hsh3" : "hsh4";
  }
  Image render(const std::array<double, 3>& light, const RenderOptions& o) const override {
    return fit::render(hsh_, light, o);
  }
  Image normalMap(int* fallbackCount, int threads) const override {
    return fit::normalMap(hsh_, fallbackCount, threads);
  }
  Image albedoMap(int threads) const override { return fit::albedoMap(hsh_, threads); }

 private:
  formats::HshFile hsh_;
};
}  // namespace

std::unique_ptr<Relightable> makeRelightable(formats::PtmFile ptm) {
  return std::make_unique<PtmModel>(std::move(ptm));
}

std::unique_ptr<Relightable> makeRelightable(formats::HshFile hsh) {
  return std::make_unique<HshModel>(std::move(hsh));
}

std::unique_ptr<Relightable> openRelightable(const std::filesystem::path& path, const formats::ModelBudget& budget) {
  const std::string bytes = readFile(path, kStep);
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  if (bytes.compare(0, 4, "PTM_") == 0)
    return makeRelightable(formats::parsePtm(data, bytes.size(), path.string(), nullptr, budget));
  if (!bytes.empty() && bytes[0] == '#')
    return makeRelightable(formats::parseRti(data, bytes.size(), path.string(), nullptr, budget));
  throwInputError(path.string(), kStep,
                  "is neither a PTM (.ptm) nor an HSH RTI (.rti) file; nothing to relight");
}

}  // namespace surrogate::fit
