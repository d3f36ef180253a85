// Colour correction fitted to a chart. See correction_model.h.
//
// The fit, per output channel i (one row x_i of M):
//   minimise  sum over used patches k of (t(m_k) . x_i - r_k[i])^2
//   subject to  t(m_w) . x_i = r_w[i]
// where t is the model's terms, m_w the sum of the used neutral patches' measured values and
// r_w the sum of their references. For the matrix t is linear, so t(m_w) is also the sum of the
// neutrals' terms; for the root-polynomial the constraint is on the terms of the summed colour
// (not the sum of the terms): the white point as one colour maps exactly onto the summed
// reference. t is homogeneous of degree 1 in both models, so scaling all measured values by k
// scales the fitted M by 1/k and leaves the corrected values unchanged.
//
// Solved through the KKT (Lagrange) system
//   [ A^T A   c ] [x_i]   [A^T y_i]
//   [ c^T     0 ] [ l ] = [ r_w[i] ]      (A: used patches' terms, c = t(m_w))
// which has one solution exactly when [A; c^T] has full column rank and c is not zero.
#include "colour/correction_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace surrogate::colour {
namespace {

constexpr const char* kStep = "colour fit";
// Singular values below this fraction of the largest count as zero: the patches do not tell
// the model's terms apart (collinear colours, e.g. only greys).
constexpr double kRankTolerance = 1e-9;

int termCount(ColourModelKind kind) { return kind == ColourModelKind::Matrix ? 3 : 6; }

Eigen::VectorXd terms(ColourModelKind kind, const Rgb& rgb) {
  Eigen::VectorXd t(termCount(kind));
  t(0) = rgb[0];
  t(1) = rgb[1];
  t(2) = rgb[2];
  if (kind == ColourModelKind::RootPolynomial) {
    // Negatives (noise below black) clamp to 0 before the roots, which are undefined there.
    const double r = std::max(rgb[0], 0.0), g = std::max(rgb[1], 0.0), b = std::max(rgb[2], 0.0);
    t(3) = std::sqrt(r * g);
    t(4) = std::sqrt(g * b);
    t(5) = std::sqrt(r * b);
  }
  return t;
}

}  // namespace

std::string modelName(ColourModelKind kind) {
  return kind == ColourModelKind::Matrix ? "matrix" : "root-polynomial";
}

ColourModelKind parseModelName(const std::string& text, const std::string& origin) {
  if (text == "matrix") return ColourModelKind::Matrix;
  if (text == "root-polynomial") return ColourModelKind::RootPolynomial;
  throw Error(ErrorKind::Usage, origin, kStep,
              "unknown colour model '" + text + "'; use matrix or root-polynomial");
}

int ColourModel::terms() const { return termCount(kind); }

Rgb ColourModel::apply(const Rgb& linearRgb) const {
  const int n = terms();
  const Eigen::VectorXd t = colour::terms(kind, linearRgb);
  Rgb out{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < n; ++j) out[i] += coefficients[static_cast<size_t>(i * n + j)] * t(j);
  return out;
}

ColourModel fitColourModel(const std::vector<Rgb>& measured, const std::vector<Rgb>& reference,
                           ColourModelKind kind, const std::vector<int>& neutrals,
                           const std::vector<bool>& use) {
  const int count = static_cast<int>(measured.size());
  if (reference.size() != measured.size() || (!use.empty() && use.size() != measured.size()))
    throw Error(ErrorKind::Usage, "chart", kStep,
                "the measured, reference and use lists differ in length");
  if (neutrals.empty())
    throw Error(ErrorKind::Usage, "chart", kStep, "no neutral patch is given to fix the white");
  auto used = [&](int k) { return use.empty() || use[static_cast<size_t>(k)]; };

  const int p = termCount(kind);
  std::vector<int> rows;
  for (int k = 0; k < count; ++k)
    if (used(k)) rows.push_back(k);
  if (static_cast<int>(rows.size()) < p + 1)
    throw Error(ErrorKind::Input, "chart", kStep,
                "only " + std::to_string(rows.size()) + " usable patches for a " +
                    modelName(kind) + " of " + std::to_string(p) + " terms (at least " +
                    std::to_string(p + 1) + " needed); photograph the chart without clipping "
                    "or shadows, or use the matrix model");

  // The white point: the used neutrals, summed.
  Rgb mWhite{0, 0, 0}, rWhite{0, 0, 0};
  int whites = 0;
  for (int k : neutrals) {
    if (k < 0 || k >= count)
      throw Error(ErrorKind::Usage, "chart", kStep, "a neutral patch index is out of range");
    if (!used(k)) continue;
    ++whites;
    for (int i = 0; i < 3; ++i) {
      mWhite[i] += measured[static_cast<size_t>(k)][i];
      rWhite[i] += reference[static_cast<size_t>(k)][i];
    }
  }
  const Eigen::VectorXd c = terms(kind, mWhite);
  if (whites == 0 || c.norm() == 0)
    throw Error(ErrorKind::Input, "chart", kStep,
                "no usable neutral patch fixes the white point (all clipped, shadowed or "
                "black); photograph the chart with its grey row exposed");

  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd a(n, p);
  Eigen::MatrixXd y(n, 3);
  for (int r = 0; r < n; ++r) {
    const size_t k = static_cast<size_t>(rows[static_cast<size_t>(r)]);
    a.row(r) = terms(kind, measured[k]).transpose();
    for (int i = 0; i < 3; ++i) y(r, i) = reference[k][i];
  }

  Eigen::MatrixXd stacked(n + 1, p);
  stacked << a, c.transpose();
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(stacked).singularValues();
  if (sv(p - 1) <= kRankTolerance * sv(0))
    throw Error(ErrorKind::Input, "chart", kStep,
                "the usable patches do not determine a " + modelName(kind) +
                    " (their colours are too alike, e.g. only greys); use the whole chart");

  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(p + 1, p + 1);
  kkt.topLeftCorner(p, p) = a.transpose() * a;
  kkt.topRightCorner(p, 1) = c;
  kkt.bottomLeftCorner(1, p) = c.transpose();
  Eigen::MatrixXd rhs(p + 1, 3);
  rhs.topRows(p) = a.transpose() * y;
  for (int i = 0; i < 3; ++i) rhs(p, i) = rWhite[i];
  const Eigen::MatrixXd solution = kkt.fullPivLu().solve(rhs);

  ColourModel model;
  model.kind = kind;
  model.coefficients.resize(static_cast<size_t>(3 * p));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < p; ++j) model.coefficients[static_cast<size_t>(i * p + j)] = solution(j, i);
  return model;
}

std::vector<Rgb> leaveOneOut(const std::vector<Rgb>& measured, const std::vector<Rgb>& reference,
                             ColourModelKind kind, const std::vector<int>& neutrals) {
  std::vector<Rgb> out(measured.size());
  for (size_t k = 0; k < measured.size(); ++k) {
    // A neutral fixes the white point: leaving it out would change what the fit is held to,
    // so it is fitted with it kept (its figure is then an in-sample one).
    const bool neutral =
        std::find(neutrals.begin(), neutrals.end(), static_cast<int>(k)) != neutrals.end();
    std::vector<bool> use(measured.size(), true);
    if (!neutral) use[k] = false;
    out[k] = fitColourModel(measured, reference, kind, neutrals, use).apply(measured[k]);
  }
  return out;
}

}  // namespace surrogate::colour
