#include "fit/learned_relightable.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/lambert.h"
#include "fit/quantise.h"

namespace surrogate::fit {

namespace {
const char* const kStep = "render";
constexpr double kPi = 3.14159265358979323846;

std::vector<std::array<double, 3>> lambertLights() {
  std::vector<std::array<double, 3>> d;
  for (double elevation : {30.0, 50.0, 70.0})
    for (int a = 0; a < 8; ++a) {
      const double e = elevation * kPi / 180, phi = a * kPi / 4;
      d.push_back({std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e)});
    }
  d.push_back({0, 0, 1});
  return d;
}

// Q = (D^T D)^-1 D^T, 3 x K row-major, for the K directions D.
std::vector<double> lambertSolve(const std::vector<std::array<double, 3>>& d) {
  double m[3][3] = {};
  for (const auto& v : d)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] += v[r] * v[c];
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  double inv[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      // cofactor of (c, r), transposed: the adjugate
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      inv[r][c] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / det;
    }
  std::vector<double> q(3 * d.size());
  for (int r = 0; r < 3; ++r)
    for (std::size_t k = 0; k < d.size(); ++k)
      q[static_cast<std::size_t>(r) * d.size() + k] = inv[r][0] * d[k][0] + inv[r][1] * d[k][1] + inv[r][2] * d[k][2];
  return q;
}

// The viewer's value of channel k at texel t, weights W of one light (learnedLightWeights).
double viewerValue(const LearnedModel& m, const std::vector<float>& w, std::size_t t, int k) {
  const auto planes = static_cast<std::size_t>(m.planes);
  double v = w[static_cast<std::size_t>(k)];
  for (std::size_t p = 0; p < planes; ++p) {
    const double c = (m.coefficients[t * planes + p] / 255.0 - m.bias[p]) * m.scale[p];
    v += w[(p + 1) * 3 + static_cast<std::size_t>(k)] * c;
  }
  return std::clamp(v, 0.0, 1.0);
}

Image picture(int w, int h, int bits, Transfer transfer) {
  Image out(w, h, 3);
  out.bitsPerSample = bits;
  out.transfer = transfer;
  return out;
}

class LearnedRelightable : public Relightable {
 public:
  explicit LearnedRelightable(LearnedModel m) : m_(std::move(m)) {}
  int width() const override { return m_.width; }
  int height() const override { return m_.height; }
  std::string basis() const override { return learnedKindName(m_.kind); }

  Image render(const std::array<double, 3>& light, const RenderOptions& o) const override {
    if (o.diffuseGain != 1.0)
      throw Error(ErrorKind::Usage, "--gain", kStep,
                  "diffuse gain is not defined for a learned basis (rbf, bln): it has no closed-form normal "
                  "or polynomial to enhance around; render a PTM for it");
    if (o.specular)
      throw Error(ErrorKind::Usage, "--specular", kStep,
                  "specular enhancement is not defined for a learned basis (rbf, bln): it has no closed-form "
                  "normal to enhance around; render a PTM or HSH model for it");
    return renderLearned(m_, light, o.threads);
  }

  Image normalMap(int* fallbackCount, int threads) const override {
    Image out = picture(m_.width, m_.height, 16, Transfer::Linear);
    const int fallbacks = eachTexel(threads, [&](int x, int y, const std::array<double, 3>& n, bool ok) {
      for (int c = 0; c < 3; ++c)
        out.at(x, y, c) = static_cast<std::uint16_t>(detail::roundClamped((n[static_cast<std::size_t>(c)] + 1) / 2 * 65535.0, 65535.0));
      return ok ? 0 : 1;
    });
    if (fallbackCount) *fallbackCount = fallbacks;
    return out;
  }

  Image albedoMap(int threads) const override {
    Image out = picture(m_.width, m_.height, 8, Transfer::Srgb);
    eachTexel(threads, [&](int x, int y, const std::array<double, 3>& n, bool) {
      const std::vector<float> w = learnedLightWeights(m_, n);
      const std::size_t t = static_cast<std::size_t>(y) * static_cast<std::size_t>(m_.width) + static_cast<std::size_t>(x);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<std::uint16_t>(detail::toByte(255 * viewerValue(m_, w, t, c)) * 257);
      return 0;
    });
    return out;
  }

 private:
  // fn(x, y, normal, found) for every texel, rows over threads; the sum of fn's results.
  int eachTexel(int threads, const std::function<int(int, int, const std::array<double, 3>&, bool)>& fn) const {
    static const std::vector<std::array<double, 3>> lights = lambertLights();
    static const std::vector<double> q = lambertSolve(lights);
    std::vector<std::vector<float>> weights;
    for (const auto& l : lights) weights.push_back(learnedLightWeights(m_, l));
    const std::size_t k = lights.size();
    std::vector<int> rows(static_cast<std::size_t>(m_.height), 0);
    parallelFor(static_cast<std::size_t>(m_.height), 8, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      for (std::size_t y = b; y < e; ++y)
        for (int x = 0; x < m_.width; ++x) {
          const std::size_t t = y * static_cast<std::size_t>(m_.width) + static_cast<std::size_t>(x);
          std::array<double, 3> sum{}, n{};
          for (int c = 0; c < 3; ++c)
            for (std::size_t d = 0; d < k; ++d) {
              const double v = viewerValue(m_, weights[d], t, c) / 3.0;
              for (std::size_t r = 0; r < 3; ++r) sum[r] += q[r * k + d] * v;
            }
          const bool ok = normalFromLambert(sum, &n);
          rows[y] += fn(x, static_cast<int>(y), n, ok);
        }
    });
    int total = 0;
    for (int r : rows) total += r;
    return total;
  }

  LearnedModel m_;
};
}  // namespace

std::unique_ptr<Relightable> makeRelightable(LearnedModel model) {
  return std::make_unique<LearnedRelightable>(std::move(model));
}

}  // namespace surrogate::fit
