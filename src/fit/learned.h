// Learned bases: relight's RBF and bilinear (BLN) models, a principal-component basis of the
// capture's own light responses, interpolated over the light direction by the viewer
// (docs/hrti-math.md, "Learned bases"; docs/formats.md, "The web layout", for the files).
//
// What a viewer (OpenLIME, relight's viewer) computes at a light l, per texel and channel k:
//
//     out_k = W_0k(l) + sum_p W_(p+1)k(l) * c_p          c_p = (byte_p / 255 - bias_p) * scale_p
//
// W(l) interpolates the basis stored at nodes: for "rbf" one node per captured light, weights
// exp(-eps r^2) normalised, eps = 8 / (the distances' exp(-2 d)-weighted mean) (OpenLIME's
// adaptive RBF); for "bilinear" an R x R grid over the octahedral map of the hemisphere,
// bilinear weights of the four nodes around the light. Basis bytes: node value of plane 0 (the
// mean) = byte / 255, of plane p >= 1 = (byte - 127) / range_(p-1). Everything in 0..1 units of
// the stored (sRGB-encoded) values; the output is clamped to 0..1.
//
// How Surrogate chooses what it stores (the part a writer is free in):
//   1. each texel's response f(l) is estimated from its N photographs by kernel ridge
//      regression on the light directions, f(l) = k(l)^T (K + lambda I)^-1 s, with a Gaussian
//      kernel whose width and lambda are chosen by leaving each photograph out in turn, on a
//      sample of texels (closed form); unseen lights are what the model is for;
//   2. the node values are those whose viewer interpolation W(l) best reproduces f over a dense
//      set of directions (least squares), so the viewer's own interpolation is part of the fit;
//   3. the principal components of those node values (all three channels together, "mrgb")
//      give the basis; the coefficients are the least-squares fit of each texel's node values
//      to the basis AS QUANTISED (the bytes the viewer reads), not to the exact one.
// All three are linear in the samples, so one matrix (planes x 3N) maps a texel's photographs
// to its coefficients; the texel's own light directions (near lights) are not used: the lights
// are at infinity, as in relight.
//
//   LearnedOptions options;  options.kind = LearnedKind::Bilinear;  options.planes = 27;
//   LearnedModel model = fitLearned(stack, lights, options, &stats);
//   Image relit = renderLearned(model, {0.3, 0.2, 0.93});
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack.h"

namespace surrogate::fit {

enum class LearnedKind { Rbf, Bilinear };

// "rbf", "bln" (the command line's and the carrier's names; info.json says "rbf"/"bilinear").
const char* learnedKindName(LearnedKind kind);
// Throws Error(Usage) naming "--basis" for anything else.
LearnedKind parseLearnedKind(const std::string& name);
// Whether `name` is a learned basis's name ("rbf" or "bln").
bool isLearnedBasisName(const std::string& name);

struct LearnedOptions {
  // Recorded (they change the result):
  LearnedKind kind = LearnedKind::Bilinear;
  int planes = 45;        // coefficients per texel, a multiple of 3 (a JPEG holds three), 3..120
  int resolution = 8;     // bilinear: the grid's side R, 4..32 (the basis holds (planes+1) R^2 3 bytes)
  // 0 = chosen by leave-one-out (step 1); else the kernel's width in radians and its ridge.
  double kernelWidth = 0;
  double ridge = 0;

  // Not recorded (bit-identical results at any value):
  int threads = 0;
  std::function<void(double fraction)> progress;

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  // Missing names keep their defaults; Error(Input) for unknown names or values.
  static LearnedOptions fromParameters(const std::vector<std::pair<std::string, std::string>>& parameters);
};

// A learned model as the web layout stores it (before the planes' JPEG compression when fitted,
// after it when read back from a layout).
struct LearnedModel {
  LearnedKind kind = LearnedKind::Bilinear;
  int width = 0, height = 0;
  int planes = 0;                // P, a multiple of 3
  int resolution = 0;            // bilinear: R; rbf: 0
  // rbf: the lights as info.json gives them (3 decimals), the interpolation's nodes; bilinear:
  // the lights fitted, for the record only.
  std::vector<std::array<double, 3>> lights;
  // (P + 1) x nodes x 3 bytes, node-major within a plane: byte (p * nodes + n) * 3 + k;
  // nodes = lights.size() (rbf) or R * R (bilinear, node (x, y) = x + y R).
  std::vector<std::uint8_t> basis;
  std::vector<float> range;      // P: plane p >= 1 decodes as (byte - 127) / range[p - 1]
  std::vector<float> scale, bias;// P each: c_p = (byte / 255 - bias[p]) * scale[p]
  // The coefficient bytes, texel-interleaved: coefficients[(y * width + x) * P + p], rows top-first.
  std::vector<std::uint8_t> coefficients;
  // Chosen by step 1 (recorded in the carrier as results, written in info.json as comments are
  // not: info.json has no member for them).
  double kernelWidth = 0, ridge = 0;

  int nodes() const { return kind == LearnedKind::Rbf ? static_cast<int>(lights.size()) : resolution * resolution; }
};

struct LearnedStatistics {
  double psnr = 0;               // at the captured lights, of the unquantised-planes model (dB)
  double leaveOneOutPsnr = 0;    // step 1's leave-one-out figure on its texel sample (dB)
  double explainedVariance = 0;  // fraction of the node values' variance the P planes keep
  int sampledTexels = 0;
};

// The planes fitted for `requested` on `photographs` photographs: at most 3 N - 3 (their three
// channels give 3 N values a texel, one of which the mean takes), so that a default of 45 planes
// fits 12 photographs with 33, and a fit that leaves photographs out with what remains.
int learnedPlanesFor(int requested, int photographs);

// Error(Usage) naming the option for planes or resolution out of range: what fitLearned checks
// first, for callers that check before decoding the photographs.
void checkLearnedOptions(const LearnedOptions& options);

// Fits learnedPlanesFor(options.planes, N) planes (model.planes says how many). Throws
// Error(Input) when the light count differs from the stack's, a light is not a direction or is
// below the horizon, or there are fewer than 4 photographs; Error(Usage) naming the option for
// planes/resolution out of range.
LearnedModel fitLearned(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                        const LearnedOptions& options, LearnedStatistics* stats = nullptr);

// The viewer's weights at light l (normalised here): (P + 1) x 3 floats, W[(p * 3) + k].
std::vector<float> learnedLightWeights(const LearnedModel& model, const std::array<double, 3>& light);

// The model relit at `light` as OpenLIME draws it: 8-bit values widened * 257, RGB, rows
// top-first, transfer sRGB. Error(Usage) naming "--light" for a zero or non-finite light.
Image renderLearned(const LearnedModel& model, const std::array<double, 3>& light, int threads = 0);

}  // namespace surrogate::fit
