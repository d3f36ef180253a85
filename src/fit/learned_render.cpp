// The viewer's side of a learned model: the interpolation weights at a light and the relit image,
// computed as OpenLIME's RTI shader computes them (fit/learned.h), so that what Surrogate reports
// of a model (its PSNR at unseen lights, `surrogate render`) is what a reader sees on screen.
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/learned.h"
#include "fit/learned_nodes.h"

namespace surrogate::fit {

namespace {

// A basis byte as the viewer decodes it (fit/learned.h).
float basisValue(const LearnedModel& model, int plane, int node, int channel) {
  const int byte = model.basis[(static_cast<std::size_t>(plane) * model.nodes() + node) * 3 + channel];
  if (plane == 0) return static_cast<float>(byte) / 255.0f;
  return (static_cast<float>(byte) - 127.0f) / model.range[plane - 1];
}

void checkModel(const LearnedModel& model) {
  const std::size_t nodes = static_cast<std::size_t>(model.nodes());
  const std::size_t P = static_cast<std::size_t>(model.planes);
  if (model.planes <= 0 || nodes == 0 || model.basis.size() != (P + 1) * nodes * 3 || model.range.size() != P ||
      model.scale.size() != P || model.bias.size() != P ||
      model.coefficients.size() != static_cast<std::size_t>(model.width) * model.height * P)
    throw Error(ErrorKind::Internal, "learned model", "render",
                "the model's parts do not agree in size (planes, nodes, basis, coefficients)");
}

}  // namespace

std::vector<float> learnedLightWeights(const LearnedModel& model, const std::array<double, 3>& light) {
  checkModel(model);
  const double n = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
  if (!(n > 0) || !std::isfinite(n))
    throw Error(ErrorKind::Usage, "--light", "command line", "give a light direction x,y,z that is not zero");
  const std::array<double, 3> l = {light[0] / n, light[1] / n, light[2] / n};
  const std::vector<NodeWeight> nodes = model.kind == LearnedKind::Rbf ? rbfNodeWeights(model.lights, l)
                                                                       : bilinearNodeWeights(model.resolution, l);
  const int P = model.planes;
  std::vector<float> weights(static_cast<std::size_t>(P + 1) * 3, 0.0f);
  for (int p = 0; p <= P; ++p)
    for (int k = 0; k < 3; ++k) {
      // Summed in float in the node order, as the viewer's Float32Array accumulates them.
      float sum = 0.0f;
      for (const NodeWeight& w : nodes) sum += static_cast<float>(w.weight) * basisValue(model, p, w.node, k);
      weights[static_cast<std::size_t>(p) * 3 + k] = sum;
    }
  return weights;
}

Image renderLearned(const LearnedModel& model, const std::array<double, 3>& light, int threads) {
  const std::vector<float> W = learnedLightWeights(model, light);
  const int P = model.planes;
  // out_k = W_0k + sum_p W_(p+1)k (byte_p / 255 - bias_p) scale_p, regrouped as
  // base_k + sum_p a_pk byte_p: the same sum, fewer operations a texel.
  std::vector<float> a(static_cast<std::size_t>(P) * 3);
  float base[3];
  for (int k = 0; k < 3; ++k) {
    base[k] = W[k];
    for (int p = 0; p < P; ++p) {
      const float w = W[static_cast<std::size_t>(p + 1) * 3 + k];
      a[static_cast<std::size_t>(p) * 3 + k] = w * model.scale[p] / 255.0f;
      base[k] -= w * model.bias[p] * model.scale[p];
    }
  }
  Image out(model.width, model.height, 3);
  out.bitsPerSample = 8;
  out.transfer = Transfer::Srgb;
  const std::size_t texels = static_cast<std::size_t>(model.width) * model.height;
  parallelFor(texels, 4096, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const std::uint8_t* c = model.coefficients.data() + t * P;
      for (int k = 0; k < 3; ++k) {
        float v = base[k];
        for (int p = 0; p < P; ++p) v += a[static_cast<std::size_t>(p) * 3 + k] * static_cast<float>(c[p]);
        const float clamped = std::min(1.0f, std::max(0.0f, v));
        out.pixels[t * 3 + k] = static_cast<std::uint16_t>(std::lround(clamped * 255.0f) * 257);
      }
    }
  });
  return out;
}

}  // namespace surrogate::fit
