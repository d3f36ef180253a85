// fitLearned: the three steps of fit/learned.h. All three are linear in a texel's samples, so they
// are composed once into one matrix (planes x 3N) and the image is read once to apply it; the
// statistics they need come from a deterministic lattice of at most kSampleTexels texels.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/learned.h"
#include "fit/learned_interpolant.h"
#include "fit/learned_nodes.h"

namespace surrogate::fit {

namespace {

using Direction = std::array<double, 3>;

// Enough texels for a stable covariance of a few hundred values; more only costs time.
constexpr int kSampleTexels = 65536;
constexpr double kSampleValues = 16.0 * 1024 * 1024;
// Coefficients beyond these quantiles of the sampled texels are clamped: a few outliers (specks
// of dust, clipped highlights) would otherwise spend most of a plane's 256 levels.
constexpr double kRangeQuantile = 0.0005;

Direction normalised(const Direction& l) {
  const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  return {l[0] / n, l[1] / n, l[2] / n};
}

double angle(const Direction& a, const Direction& b) {
  return std::acos(std::max(-1.0, std::min(1.0, a[0] * b[0] + a[1] * b[1] + a[2] * b[2])));
}

// Directions over the hemisphere (a Fibonacci spiral, z from 1 down to 0.02) where the viewer's
// interpolation is made to follow the response, and their weights: 1 within reach of the captured
// lights (1.5 times their median spacing), 0.05 beyond, where the response is an extrapolation
// that only needs to stay tame.
void denseDirections(const std::vector<Direction>& lights, std::vector<Direction>* dirs, std::vector<double>* weights) {
  const int count = 2000;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (i + 0.5) / count * 0.98;
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    dirs->push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
  }
  for (const Direction& l : lights) dirs->push_back(l);
  std::vector<double> spacing;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    double nearest = M_PI;
    for (std::size_t j = 0; j < lights.size(); ++j)
      if (j != i) nearest = std::min(nearest, angle(lights[i], lights[j]));
    spacing.push_back(nearest);
  }
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  const double reach = 1.5 * spacing[spacing.size() / 2];
  for (const Direction& d : *dirs) {
    double nearest = M_PI;
    for (const Direction& l : lights) nearest = std::min(nearest, angle(d, l));
    weights->push_back(nearest <= reach ? 1.0 : 0.05);
  }
}

// The viewer's weights at each direction, |dirs| x nodes.
Eigen::MatrixXd viewerWeights(LearnedKind kind, int resolution, const std::vector<Direction>& nodeLights,
                              const std::vector<Direction>& dirs) {
  const int nodes = kind == LearnedKind::Rbf ? static_cast<int>(nodeLights.size()) : resolution * resolution;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(dirs.size(), nodes);
  for (std::size_t d = 0; d < dirs.size(); ++d)
    for (const NodeWeight& w : kind == LearnedKind::Rbf ? rbfNodeWeights(nodeLights, dirs[d])
                                                        : bilinearNodeWeights(resolution, dirs[d]))
      W(d, w.node) += w.weight;
  return W;
}

// kron(A, I3) for the layout [node or light][channel].
Eigen::MatrixXd perChannel(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(A.rows() * 3, A.cols() * 3);
  for (Eigen::Index r = 0; r < A.rows(); ++r)
    for (Eigen::Index c = 0; c < A.cols(); ++c)
      for (int k = 0; k < 3; ++k) K(r * 3 + k, c * 3 + k) = A(r, c);
  return K;
}

// The sampled texels' values in 0..1, one column of 3N per texel ([light][channel]), as floats:
// at most kSampleValues values (64 MB), fewer texels when there are many photographs. A row of
// every photograph is read, then each texel's column written whole.
Eigen::MatrixXf sampleTexels(const ImageStack& stack, int* strideOut) {
  const int W = stack.width(), H = stack.height(), N = stack.size();
  const double texels = std::min<double>(kSampleTexels, kSampleValues / (3.0 * N));
  const int stride = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(W) * H / texels))));
  *strideOut = stride;
  const int cols = (W + stride - 1) / stride, rows = (H + stride - 1) / stride;
  Eigen::MatrixXf S(3 * N, static_cast<Eigen::Index>(cols) * rows);
  const std::size_t rowSize = static_cast<std::size_t>(W) * 3;
  std::vector<std::uint16_t> row(rowSize * N);
  for (int r = 0; r < rows; ++r) {
    for (int i = 0; i < N; ++i) stack.readRows(i, r * stride, r * stride + 1, row.data() + i * rowSize);
    for (int c = 0; c < cols; ++c) {
      float* column = S.col(static_cast<Eigen::Index>(r) * cols + c).data();
      const std::size_t at = static_cast<std::size_t>(c) * stride * 3;
      for (int i = 0; i < N; ++i)
        for (int k = 0; k < 3; ++k) column[i * 3 + k] = row[i * rowSize + at + k] / 65535.0f;
    }
  }
  return S;
}

}  // namespace

int learnedPlanesFor(int requested, int photographs) { return std::max(3, std::min(requested, 3 * photographs - 3)); }

void checkLearnedOptions(const LearnedOptions& o) {
  if (o.planes < 3 || o.planes > 120 || o.planes % 3 != 0)
    throw Error(ErrorKind::Usage, "--planes " + std::to_string(o.planes), "command line",
                "give a multiple of 3 from 3 to 120 (each web-layout JPEG holds three planes)");
  if (o.kind == LearnedKind::Bilinear && (o.resolution < 4 || o.resolution > 32))
    throw Error(ErrorKind::Usage, "--resolution " + std::to_string(o.resolution), "command line",
                "give the bilinear grid's side, 4 to 32");
}

namespace {

void checkInputs(const ImageStack& stack, const std::vector<Direction>& lights, const LearnedOptions& o) {
  checkLearnedOptions(o);
  if (stack.channels() != 3) throw Error(ErrorKind::Internal, "stack", "fit", "a learned fit reads RGB photographs");
  const int N = stack.size();
  if (static_cast<int>(lights.size()) != N)
    throw Error(ErrorKind::Input, "lights", "fit",
                std::to_string(lights.size()) + " light directions for " + std::to_string(N) + " photographs");
  if (N < 4) throw Error(ErrorKind::Input, "lights", "fit", "a learned basis needs at least 4 photographs");
  for (const Direction& l : lights) {
    const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    if (!(n > 0) || !std::isfinite(n) || !(l[2] / n > 0))
      throw Error(ErrorKind::Input, "lights", "fit", "a light direction is zero or at or below the horizon");
  }
}

}  // namespace

LearnedModel fitLearned(const ImageStack& stack, const std::vector<Direction>& rawLights, const LearnedOptions& o,
                        LearnedStatistics* stats) {
  checkInputs(stack, rawLights, o);
  const int N = stack.size(), W = stack.width(), H = stack.height(), P = learnedPlanesFor(o.planes, N);
  const auto progress = [&](double f) { if (o.progress) o.progress(f); };
  std::vector<Direction> lights;
  for (const Direction& l : rawLights) lights.push_back(normalised(l));

  LearnedModel model;
  model.kind = o.kind;
  model.width = W;
  model.height = H;
  model.planes = P;
  model.resolution = o.kind == LearnedKind::Bilinear ? o.resolution : 0;
  // The viewer reads the lights with three decimals: the RBF's nodes are those.
  for (const Direction& l : lights)
    model.lights.push_back({std::round(l[0] * 1000) / 1000, std::round(l[1] * 1000) / 1000, std::round(l[2] * 1000) / 1000});

  // Step 1: the response's smoothness, by leave-one-out on the sampled texels.
  int stride = 1;
  const Eigen::MatrixXf S = sampleTexels(stack, &stride);
  progress(0.1);
  // One second-moment matrix of the samples (3N x 3N, its lower half by a symmetric rank update)
  // gives both the leave-one-out's Gram matrix (the channels' diagonal blocks summed) and the
  // covariance of step 3.
  Eigen::MatrixXd moment = Eigen::MatrixXd::Zero(3 * N, 3 * N);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(3 * N);
  for (Eigen::Index t0 = 0; t0 < S.cols(); t0 += 4096) {  // in double, a block at a time
    const Eigen::MatrixXd block = S.middleCols(t0, std::min<Eigen::Index>(4096, S.cols() - t0)).cast<double>();
    moment.selfadjointView<Eigen::Lower>().rankUpdate(block);
    sum += block.rowwise().sum();
  }
  moment = moment.selfadjointView<Eigen::Lower>();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < 3; ++k) gram(i, j) += moment(i * 3 + k, j * 3 + k);
  const Interpolant f = chooseInterpolant(lights, gram, double(S.cols()) * 3, o.kernelWidth, o.ridge);
  model.kernelWidth = f.width;
  model.ridge = f.ridge;
  progress(0.2);

  // Step 2: node values whose viewer interpolation follows the response over the hemisphere.
  std::vector<Direction> dirs;
  std::vector<double> omega;
  denseDirections(lights, &dirs, &omega);
  const Eigen::MatrixXd V = viewerWeights(o.kind, o.resolution, model.lights, dirs);
  const Eigen::MatrixXd T = f.weightsAt(dirs);
  const Eigen::MatrixXd VtO = V.transpose() * Eigen::Map<const Eigen::VectorXd>(omega.data(), omega.size()).asDiagonal();
  Eigen::MatrixXd Q = VtO * V / Eigen::Map<const Eigen::VectorXd>(omega.data(), omega.size()).sum();
  const int D = static_cast<int>(Q.rows());
  Q += 1e-6 * Q.trace() / D * Eigen::MatrixXd::Identity(D, D);  // nodes no direction reaches stay near 0
  const Eigen::MatrixXd M = (VtO * V + 1e-6 * (VtO * V).trace() / D * Eigen::MatrixXd::Identity(D, D)).ldlt().solve(VtO * T);

  // Step 3: principal components of the node values in the metric of the rendered image (Q),
  // so that the planes kept are those that matter most on screen.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> qe(Q);
  const Eigen::VectorXd qs = qe.eigenvalues().cwiseMax(0).cwiseSqrt();
  const Eigen::MatrixXd Lroot = qe.eigenvectors() * qs.asDiagonal() * qe.eigenvectors().transpose();
  const Eigen::MatrixXd LrootInv = qe.eigenvectors() * qs.cwiseInverse().asDiagonal() * qe.eigenvectors().transpose();
  const Eigen::MatrixXd Mk = perChannel(M);
  const Eigen::VectorXd mean = sum / double(S.cols());
  const Eigen::MatrixXd covS = moment / double(S.cols()) - mean * mean.transpose();
  const Eigen::MatrixXd B = perChannel(Lroot) * Mk;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> pe(B * covS * B.transpose());
  const Eigen::Index dims = pe.eigenvalues().size();
  Eigen::MatrixXd E(3 * D, P);  // node-space basis, columns in order of decreasing variance
  for (int p = 0; p < P; ++p) {
    Eigen::VectorXd u = pe.eigenvectors().col(dims - 1 - p);
    // A sign for every plane so that the same capture gives the same bytes on any machine.
    Eigen::Index big = 0;
    u.cwiseAbs().maxCoeff(&big);
    if (u(big) < 0) u = -u;
    E.col(p) = perChannel(LrootInv) * u;
  }
  const double total = pe.eigenvalues().cwiseMax(0).sum();
  const double kept = pe.eigenvalues().tail(P).cwiseMax(0).sum();
  progress(0.3);

  // The basis as bytes, and as the viewer decodes them.
  const Eigen::VectorXd nodeMean = Mk * mean;
  model.basis.assign(static_cast<std::size_t>(P + 1) * D * 3, 0);
  Eigen::VectorXd meanQ(3 * D);
  Eigen::MatrixXd EQ(3 * D, P);
  for (int j = 0; j < 3 * D; ++j) {
    const int byte = static_cast<int>(std::lround(std::min(1.0, std::max(0.0, nodeMean(j))) * 255));
    model.basis[j] = static_cast<std::uint8_t>(byte);
    meanQ(j) = byte / 255.0f;
  }
  for (int p = 0; p < P; ++p) {
    const float range = static_cast<float>(127.0 / std::max(1e-12, E.col(p).cwiseAbs().maxCoeff()));
    model.range.push_back(range);
    for (int j = 0; j < 3 * D; ++j) {
      const int byte = std::min(255, std::max(0, static_cast<int>(std::lround(127 + range * E(j, p)))));
      model.basis[static_cast<std::size_t>(p + 1) * D * 3 + j] = static_cast<std::uint8_t>(byte);
      EQ(j, p) = (static_cast<float>(byte) - 127.0f) / range;
    }
  }
  // Coefficients: least squares against the quantised basis in the same metric.
  const Eigen::MatrixXd Qk = perChannel(Q);
  const Eigen::MatrixXd Hm = (EQ.transpose() * Qk * EQ).ldlt().solve(EQ.transpose() * Qk);
  const Eigen::MatrixXf C = (Hm * Mk).cast<float>();              // P x 3N
  const Eigen::VectorXf c0 = (-(Hm * meanQ)).cast<float>();        // P

  // Each plane's range from the sampled texels (quantiles), then scale and bias as info.json
  // stores them: c = (byte / 255 - bias) * scale.
  const Eigen::MatrixXf sampleCoefficients = (C * S).colwise() + c0;
  for (int p = 0; p < P; ++p) {
    std::vector<float> w(sampleCoefficients.cols());
    for (Eigen::Index t = 0; t < sampleCoefficients.cols(); ++t) w[t] = sampleCoefficients(p, t);
    const std::size_t lo = static_cast<std::size_t>(kRangeQuantile * (w.size() - 1));
    const std::size_t hi = w.size() - 1 - lo;
    std::nth_element(w.begin(), w.begin() + lo, w.end());
    const float mn = w[lo];
    std::nth_element(w.begin(), w.begin() + hi, w.end());
    const float mx = w[hi];
    const float scale = std::max(1e-6f, mx - mn);
    model.scale.push_back(scale);
    model.bias.push_back(-mn / scale);
  }
  progress(0.35);

  // The coefficient bytes of every texel, a band of rows at a time.
  model.coefficients.assign(static_cast<std::size_t>(W) * H * P, 0);
  const int band = std::max(1, std::min(H, static_cast<int>((48u << 20) / (std::size_t(N) * W * 6))));
  std::vector<std::uint16_t> buffer(static_cast<std::size_t>(N) * band * W * 3);
  std::vector<float> invScale(P), bias(P);
  for (int p = 0; p < P; ++p) {
    invScale[p] = 1.0f / model.scale[p];
    bias[p] = model.bias[p];
  }
  for (int y0 = 0; y0 < H; y0 += band) {
    const int y1 = std::min(H, y0 + band);
    const std::size_t plane = static_cast<std::size_t>(y1 - y0) * W * 3;
    for (int i = 0; i < N; ++i) stack.readRows(i, y0, y1, buffer.data() + i * plane);
    parallelFor(static_cast<std::size_t>(y1 - y0), 1, o.threads, [&](std::size_t r0, std::size_t r1) {
      Eigen::MatrixXf samples(3 * N, W);
      for (std::size_t r = r0; r < r1; ++r) {
        for (int i = 0; i < N; ++i) {
          const std::uint16_t* src = buffer.data() + i * plane + r * W * 3;
          for (int x = 0; x < W; ++x)
            for (int k = 0; k < 3; ++k) samples(i * 3 + k, x) = src[x * 3 + k] / 65535.0f;
        }
        const Eigen::MatrixXf c = (C * samples).colwise() + c0;  // P x W
        std::uint8_t* out = model.coefficients.data() + (static_cast<std::size_t>(y0 + r) * W) * P;
        for (int x = 0; x < W; ++x)
          for (int p = 0; p < P; ++p) {
            const float q = (c(p, x) * invScale[p] + bias[p]) * 255.0f;
            out[static_cast<std::size_t>(x) * P + p] = static_cast<std::uint8_t>(std::lround(std::min(255.0f, std::max(0.0f, q))));
          }
      }
    });
    progress(0.35 + 0.65 * y1 / H);
  }

  if (stats) {
    stats->leaveOneOutPsnr = f.leaveOneOutMse > 0 ? -10 * std::log10(f.leaveOneOutMse) : 100;
    stats->explainedVariance = total > 0 ? kept / total : 1;
    stats->sampledTexels = static_cast<int>(S.cols());
    // At the captured lights, the quantised model on the sampled texels, in 8-bit units.
    const Eigen::MatrixXd Vl = perChannel(viewerWeights(o.kind, o.resolution, model.lights, lights));
    const Eigen::MatrixXd VlE = Vl * EQ;
    const Eigen::VectorXd VlMean = Vl * meanQ;
    // In blocks of texels, so that the relit values (3N a texel) stay a few megabytes.
    double se = 0;
    const Eigen::Index block = 2048;
    for (Eigen::Index t0 = 0; t0 < S.cols(); t0 += block) {
      const Eigen::Index n = std::min(block, S.cols() - t0);
      Eigen::MatrixXd c(P, n);
      for (Eigen::Index t = 0; t < n; ++t)
        for (int p = 0; p < P; ++p) {
          const float q = std::lround(std::min(255.0f, std::max(0.0f, (sampleCoefficients(p, t0 + t) * invScale[p] + bias[p]) * 255.0f)));
          c(p, t) = (q / 255.0f - bias[p]) * model.scale[p];
        }
      const Eigen::MatrixXd relit = ((VlE * c).colwise() + VlMean).cwiseMax(0).cwiseMin(1);
      se += (relit - S.middleCols(t0, n).cast<double>()).squaredNorm();
    }
    const double mse = se / (double(S.cols()) * 3 * N);
    stats->psnr = mse > 0 ? std::min(100.0, -10 * std::log10(mse)) : 100;
  }
  return model;
}

}  // namespace surrogate::fit
