#include "fit/learned_relightable.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/lambert.h"
#include "fit/learned_nodes.h"
#include "fit/quantise.h"

namespace surrogate::fit {

namespace {
const char* const kStep = "render";

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
    const std::size_t P = static_cast<std::size_t>(m_.planes), stride = (P + 1) * 3;
    // rbf: the weights at a normal from a table over the octahedral map (bilinear between its
    // entries): every texel's own would cost an exponential per photograph. bln: exact.
    std::vector<float> table;
    const int side = 65;
    if (m_.kind == LearnedKind::Rbf) {
      table.resize(static_cast<std::size_t>(side) * side * stride);
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
          const std::vector<float> w = learnedLightWeights(m_, bilinearNodeDirection(side, x, y));
          std::copy(w.begin(), w.end(), table.begin() + (static_cast<std::size_t>(y) * side + x) * stride);
        }
    }
    std::vector<double> a(P), o(P);  // a byte's coefficient: byte * a_p + o_p
    for (std::size_t p = 0; p < P; ++p) {
      a[p] = m_.scale[p] / 255.0;
      o[p] = -static_cast<double>(m_.bias[p]) * m_.scale[p];
    }
    std::vector<float> decoded;  // bln: the basis as the viewer decodes it, node-major
    if (m_.kind == LearnedKind::Bilinear)
      for (int node = 0; node < m_.nodes(); ++node)
        for (std::size_t p = 0; p <= P; ++p)
          for (int k = 0; k < 3; ++k) decoded.push_back(basisValue(p, node, k));
    eachTexel(threads, [&](int x, int y, const std::array<double, 3>& n, bool) {
      float w[3 * 121] = {};
      if (m_.kind == LearnedKind::Rbf) {
        for (const NodeWeight& nw : bilinearNodeWeights(side, n))
          for (std::size_t i = 0; i < stride; ++i) w[i] += static_cast<float>(nw.weight) * table[nw.node * stride + i];
      } else {
        for (const NodeWeight& nw : bilinearNodeWeights(m_.resolution, n))
          for (std::size_t i = 0; i < stride; ++i) w[i] += static_cast<float>(nw.weight) * decoded[nw.node * stride + i];
      }
      const std::size_t t = static_cast<std::size_t>(y) * static_cast<std::size_t>(m_.width) + static_cast<std::size_t>(x);
      for (int c = 0; c < 3; ++c) {
        double v = w[c];
        for (std::size_t p = 0; p < P; ++p) v += w[(p + 1) * 3 + c] * (m_.coefficients[t * P + p] * a[p] + o[p]);
        out.at(x, y, c) = static_cast<std::uint16_t>(detail::toByte(255 * std::clamp(v, 0.0, 1.0)) * 257);
      }
      return 0;
    });
    return out;
  }

 private:
  float basisValue(std::size_t p, int node, int k) const {
    const int byte = m_.basis[(p * static_cast<std::size_t>(m_.nodes()) + node) * 3 + k];
    return p == 0 ? byte / 255.0f : (byte - 127.0f) / m_.range[p - 1];
  }

  // fn(x, y, normal, found) for every texel, rows over threads; the sum of fn's results. The
  // Lambertian vector is linear in the texel's coefficient bytes (the viewer's sums, unclamped),
  // so Q (base_d + A_d byte) is folded into b0 + G byte once: 3 x P numbers a texel rather than
  // 61 relightings.
  int eachTexel(int threads, const std::function<int(int, int, const std::array<double, 3>&, bool)>& fn) const {
    // Per channel, the table of the viewer's value at each direction of fit/lambert.h as an
    // affine function of the bytes (column 0 the constant, column p + 1 byte p's factor),
    // folded by lambertOfBasis; the mean of the three channels' b.
    const LambertDirections& lambert = lambertDirections();
    const std::size_t k = lambert.directions.size(), P = static_cast<std::size_t>(m_.planes), terms = P + 1;
    std::vector<std::vector<float>> weights;
    for (const auto& d : lambert.directions) weights.push_back(learnedLightWeights(m_, d));
    std::array<double, 3> b0{};
    std::vector<double> G(3 * P, 0.0);
    for (int c = 0; c < 3; ++c) {
      std::vector<double> table(k * terms);
      for (std::size_t d = 0; d < k; ++d) {
        const std::vector<float>& w = weights[d];
        double base = w[static_cast<std::size_t>(c)];
        for (std::size_t p = 0; p < P; ++p) {
          base -= w[(p + 1) * 3 + c] * m_.bias[p] * m_.scale[p];
          table[d * terms + 1 + p] = w[(p + 1) * 3 + c] * m_.scale[p] / 255.0;
        }
        table[d * terms] = base;
      }
      const std::vector<double> qb = lambertOfBasis(table, static_cast<int>(terms));
      for (std::size_t r = 0; r < 3; ++r) {
        b0[r] += qb[r * terms] / 3.0;
        for (std::size_t p = 0; p < P; ++p) G[r * P + p] += qb[r * terms + 1 + p] / 3.0;
      }
    }
    std::vector<int> rows(static_cast<std::size_t>(m_.height), 0);
    parallelFor(static_cast<std::size_t>(m_.height), 8, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      for (std::size_t y = b; y < e; ++y)
        for (int x = 0; x < m_.width; ++x) {
          const std::uint8_t* bytes = m_.coefficients.data() + (y * static_cast<std::size_t>(m_.width) + x) * P;
          std::array<double, 3> sum = b0, n{};
          for (std::size_t r = 0; r < 3; ++r)
            for (std::size_t p = 0; p < P; ++p) sum[r] += G[r * P + p] * bytes[p];
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
