// NearModel's nodes and the checks of near lights (fit/near_fit.h): the exact conditioned
// inverse at every node of the grid, from the node's own light directions.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "fit/basis.h"
#include "fit/near_fit.h"
#include "fit/pseudo_inverse.h"
#include "fit/srgb_falloff.h"

namespace surrogate::fit {

namespace {

const char* const kStep = "fit";

std::vector<double> designRow(Basis basis, const std::array<double, 3>& l) {
  const int terms = basisTerms(basis);
  std::vector<double> w(terms);
  if (isPtm(basis)) {
    const auto p = ptmBasis(l[0], l[1]);
    std::copy(p.begin(), p.end(), w.begin());
  } else {
    hshBasis(l[0], l[1], l[2], terms, w.data());
  }
  return w;
}


}  // namespace

double srgbScaled(unsigned v16, double f) {
  const falloff::SrgbTables& t = falloff::srgbTables();
  return falloff::scaledWith(t.decode16.data(), t.encode.data(), v16, f, falloff::rootWith(t.root.data(), f));
}

double srgbUnscaled(double m255, double g) {
  const falloff::SrgbTables& t = falloff::srgbTables();
  return falloff::unscaledWith(t.decode.data(), t.encode.data(), m255, g, falloff::rootWith(t.root.data(), g));
}

bool hasNearLights(const std::vector<std::array<double, 3>>& lights, const FitOptions& options) {
  const auto& near = options.nearLights;
  if (near.empty()) return false;
  if (near.size() != lights.size()) {
    throw Error(ErrorKind::Input, "", kStep,
                "there are " + std::to_string(lights.size()) + " lights but " + std::to_string(near.size()) +
                    " light positions; give one position (or none) per light");
  }
  bool any = false;
  for (std::size_t i = 0; i < near.size(); ++i) {
    if (!near[i].near) continue;
    any = true;
    const auto& p = near[i].position;
    const double r = near[i].referenceDistance;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) || !(p[2] > 0) ||
        !std::isfinite(r) || !(r > 0)) {
      throw Error(ErrorKind::Input, "", kStep,
                  "light " + std::to_string(i + 1) +
                      "'s position must be finite and above the surface (z > 0), with a positive reference "
                      "distance; give its direction alone if its position is not known");
    }
  }
  return any;
}

int nearNodeSpacing(int width, int height, const std::vector<NearLight>& near) {
  double closest = std::numeric_limits<double>::infinity();
  for (const NearLight& l : near) {
    if (!l.near) continue;
    const double dx = std::max({0.0, -l.position[0], l.position[0] - (width - 1)});
    const double dy = std::max({0.0, l.position[1], -l.position[1] - (height - 1)});
    closest = std::min(closest, std::sqrt(dx * dx + dy * dy + l.position[2] * l.position[2]));
  }
  if (!std::isfinite(closest)) return 64;
  return static_cast<int>(std::clamp(std::floor(closest / 48.0), 2.0, 64.0));
}

NearModel::NearModel(int width, int height, const std::vector<std::array<double, 3>>& lights,
                     const std::vector<NearLight>& near, Basis basis, double scale, int spacing, int threads,
                     Transfer transfer)
    : n_(static_cast<int>(lights.size())), terms_(basisTerms(basis)), g_(std::max(1, spacing)),
      lrgb_(basis == Basis::PtmLrgb), srgb_(transfer == Transfer::Srgb) {
  cols_ = std::max(2, (width - 1 + g_ - 1) / g_ + 1);
  rows_ = std::max(2, (height - 1 + g_ - 1) / g_ + 1);
  const std::size_t tn = static_cast<std::size_t>(terms_) * n_;
  stride_ = 2 * tn + (lrgb_ ? n_ : 0);
  for (int i = 0; i < n_; ++i) {
    const bool isNear = near[i].near;
    near_.push_back(isNear ? 1 : 0);
    x_.push_back(isNear ? near[i].position[0] : 0.0);
    yz_.push_back(isNear ? near[i].position[1] : 0.0);
    yz_.push_back(isNear ? near[i].position[2] : 0.0);
    inv_.push_back(isNear ? 1.0 / (near[i].referenceDistance * near[i].referenceDistance) : 0.0);
  }
  const std::size_t count = static_cast<std::size_t>(rows_) * cols_;
  // The design at a node: each light's direction from the node's surface point (gx G, -gy G, 0).
  auto design = [&](std::size_t node, std::vector<std::array<double, 3>>* dirs) {
    const double px = static_cast<double>(node % cols_) * g_, py = -static_cast<double>(node / cols_) * g_;
    std::vector<double> a;
    dirs->clear();
    for (int i = 0; i < n_; ++i) {
      std::array<double, 3> l = lights[i];
      if (near_[i]) {
        const double dx = x_[i] - px, dy = yz_[2 * i] - py, dz = yz_[2 * i + 1];
        const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
        l = {dx / len, dy / len, dz / len};
      }
      dirs->push_back(l);
      const auto w = designRow(basis, l);
      a.insert(a.end(), w.begin(), w.end());
    }
    return a;
  };
  // Each node's own conditioning (the far fit's rule), then one weight for the whole frame.
  std::vector<Conditioning> at(count);
  parallelFor(count, 8, threads, [&](std::size_t b, std::size_t e) {
    std::vector<std::array<double, 3>> dirs;
    for (std::size_t j = b; j < e; ++j) at[j] = conditionedInverse(design(j, &dirs), n_, basis);
  });
  double mu = 0;
  for (const Conditioning& c : at) mu = std::max(mu, c.weight);
  nodes_.assign(count * stride_, 0.0);
  parallelFor(count, 8, threads, [&](std::size_t b, std::size_t e) {
    std::vector<std::array<double, 3>> dirs;
    for (std::size_t j = b; j < e; ++j) {
      const std::vector<double> a = design(j, &dirs);
      if (mu > 0 && at[j].weight != mu) {
        const int rank = at[j].inverse.rank;
        at[j].inverse = dampedPseudoInverse(a, n_, terms_, higherTerms(basis), mu);
        at[j].inverse.rank = rank;
        at[j].noiseGain = noiseGain(a, n_, terms_, at[j].inverse.matrix);
      }
      double* node = nodes_.data() + j * stride_;
      for (std::size_t q = 0; q < tn; ++q) node[q] = at[j].inverse.matrix[q] * scale;
      for (int i = 0; i < n_; ++i)
        for (int k = 0; k < terms_; ++k) node[tn + k * n_ + i] = a[static_cast<std::size_t>(i) * terms_ + k];
      if (lrgb_) {  // the chroma weights of LrgbFitter (ptm_fit.cpp), at the node's directions
        double* w = node + 2 * tn;
        double total = 0;
        for (int i = 0; i < n_; ++i) {
          const double el = std::asin(std::clamp(dirs[i][2], -1.0, 1.0)) / (M_PI / 2) - 0.5;
          w[i] = std::max(0.0, 0.25 - el * el);
          total += w[i];
        }
        if (!(total > 0)) {
          std::fill(w, w + n_, 1.0);
          total = n_;
        }
        for (int i = 0; i < n_; ++i) w[i] /= total * 257.0;
      }
    }
  });
  summary_ = at[0];
  summary_.weight = mu;
  summary_.damped = mu > 0 ? higherTerms(basis) : std::vector<int>{};
  for (const Conditioning& c : at) {
    summary_.conditionNumber = std::max(summary_.conditionNumber, c.conditionNumber);
    summary_.noiseGain = std::max(summary_.noiseGain, c.noiseGain);
    summary_.plainNoiseGain = std::max(summary_.plainNoiseGain, c.plainNoiseGain);
    summary_.inverse.rank = std::min(summary_.inverse.rank, c.inverse.rank);
  }
}

}  // namespace surrogate::fit
