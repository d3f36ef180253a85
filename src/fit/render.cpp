#include "fit/render.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "fit/basis.h"
#include "fit/lambert.h"
#include "fit/normals.h"
#include "fit/quantise.h"
#include "fit/texel.h"

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

// ks * 255 * max(0, N . H)^e with H the half vector of the light and the view (0, 0, 1).
double specularTerm(const std::array<double, 3>& n, const Light& l, const RenderOptions& o) {
  double h[3] = {l.x, l.y, l.z + 1.0};
  const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  if (len == 0) return 0;
  const double nh = std::max(0.0, (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / len);
  return o.ks * 255.0 * std::pow(nh, o.specularExponent);
}

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
  const std::size_t plane = ptm.texels() * 6;  // bytes of one channel's coefficients
  forRows(ptm.height, options.threads, [&](int y) {
    for (int x = 0; x < ptm.width; ++x) {
      std::array<double, 3> n{0, 0, 1};
      if (gain || options.specular) n = ptmNormal(ptmLuminance(ptm, x, y));
      const double spec = options.specular ? specularTerm(n, l, options) : 0.0;
      double diffuse[3];
      const std::uint8_t* bytes = &ptm.coefficients[(static_cast<std::size_t>(y) * ptm.width + x) * 6];
      for (int c = 0; c < (lrgb ? 1 : 3); ++c) {
        if (gain) {
          diffuse[c] = evaluatePtm(applyDiffuseGain(ptmChannel(ptm, x, y, c), options.diffuseGain, n[0], n[1]), lu, lv);
        } else {
          diffuse[c] = terms.evaluate(bytes + c * plane);
        }
      }
      for (int c = 0; c < 3; ++c) {
        const double d =
            lrgb ? ptm.rgb[(static_cast<std::size_t>(y) * ptm.width + x) * 3 + c] * diffuse[0] / 255.0
                 : diffuse[c];
        out.at(x, y, c) = toSample(kd * d + spec);
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
        spec = specularTerm(n, l, options);
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
