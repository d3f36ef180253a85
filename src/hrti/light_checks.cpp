#include "hrti/light_checks.h"

#include <algorithm>
#include <cmath>

#include "core/text.h"

namespace surrogate::hrti {

namespace {

double elevationDeg(const std::array<double, 3>& l) { return std::asin(std::clamp(l[2], -1.0, 1.0)) * 180 / M_PI; }

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + (v.size() - 1) / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

LightCheck belowHorizon(const LightCheckInput& in) {
  LightCheck c{kCheckBelowHorizon, false, "", {}};
  std::vector<std::string> named;
  // Behind the horizon when even the light's 95 % bound does not reach it: the margin is its
  // uncertainty when measured (at most kMaxHorizonMarginDeg), else kHorizonMarginDeg.
  const bool bounds = in.uncertaintyDeg.size() == in.lights.size();
  for (std::size_t i = 0; i < in.lights.size(); ++i) {
    const double e = elevationDeg(in.lights[i]);
    const double u = bounds && std::isfinite(in.uncertaintyDeg[i]) && in.uncertaintyDeg[i] >= 0
                         ? std::min(in.uncertaintyDeg[i], LightCheckLimits::kMaxHorizonMarginDeg)
                         : LightCheckLimits::kHorizonMarginDeg;
    if (e >= -u) continue;
    c.images.push_back(static_cast<int>(i));
    named.push_back(in.names[i] + " (" + fixedDecimals(e, 0) + " deg)");
  }
  c.failed = !c.images.empty();
  c.detail = c.failed ? std::to_string(c.images.size()) + " of " + std::to_string(in.lights.size()) +
                            " lights come from behind the object (elevation below 0): " + listedInFull(named) +
                            ". Their highlights lie near the sphere's rim, where no light in front of the object "
                            "puts one: the circle is probably not the sphere, or not where it is"
                      : "every light is in front of the object";
  return c;
}

LightCheck spheresOverlap(const LightCheckInput& in) {
  LightCheck c{kCheckSpheresOverlap, false, "", {}};
  std::string pairs;
  for (std::size_t a = 0; a < in.spheres.size(); ++a)
    for (std::size_t b = a + 1; b < in.spheres.size(); ++b) {
      const DetectedSphere &p = in.spheres[a], &q = in.spheres[b];
      if (std::hypot(p.cx - q.cx, p.cy - q.cy) >= p.r + q.r) continue;
      pairs += (pairs.empty() ? "" : ", ") + std::string("spheres ") + std::to_string(a) + " and " + std::to_string(b);
    }
  c.failed = !pairs.empty();
  c.detail = c.failed ? "the circles of " + pairs + " overlap: two spheres cannot, so one is a reflection in the "
                            "other or the same sphere twice"
                      : in.spheres.size() > 1 ? "the spheres' circles are apart" : "one sphere";
  return c;
}

LightCheck spheresDisagree(const LightCheckInput& in) {
  LightCheck c{kCheckSpheresDisagree, false, "", {}};
  std::vector<double> angles;
  for (std::size_t i = 0; i < in.perSphere.size(); ++i) {
    const auto& row = in.perSphere[i];
    double worst = -1;
    for (std::size_t a = 0; a < row.size(); ++a)
      for (std::size_t b = a + 1; b < row.size(); ++b)
        if (row[a] && row[b]) worst = std::max(worst, angleDeg(*row[a], *row[b]));
    if (worst >= 0) angles.push_back(worst);
  }
  if (angles.empty()) {
    c.detail = "no image has highlights on two spheres";
    return c;
  }
  const double m = median(angles);
  c.failed = m > LightCheckLimits::kMaxDisagreementDeg;
  c.detail = "the spheres' directions for the same image differ by " + fixedDecimals(m, 1) + " deg (median over " +
             std::to_string(angles.size()) + " images; a near light makes them differ, but not by more than " +
             fixedDecimals(LightCheckLimits::kMaxDisagreementDeg, 0) + " deg)" +
             (c.failed ? ": one of the circles is probably not a sphere, or the light was so near that the "
                         "spheres see it from directions this far apart (then say how far with --light-distance, "
                         "or leave it auto for the spheres to place it)"
                       : "");
  return c;
}

LightCheck lightsClustered(const LightCheckInput& in) {
  LightCheck c{kCheckLightsClustered, false, "", {}};
  std::vector<double> angles;
  for (std::size_t a = 0; a < in.lights.size(); ++a)
    for (std::size_t b = a + 1; b < in.lights.size(); ++b) angles.push_back(angleDeg(in.lights[a], in.lights[b]));
  if (angles.empty()) {
    c.detail = "fewer than two lights";
    return c;
  }
  const double m = median(angles);
  c.failed = in.lights.size() >= 3 && m < LightCheckLimits::kMinSpreadDeg;
  c.detail = "two lights are " + fixedDecimals(m, 1) + " deg apart (median)" +
             (c.failed ? ": the light was not moved between the shots, or the highlights found are not of the light"
                       : "");
  return c;
}

LightCheck exposureOutlier(const LightCheckInput& in) {
  LightCheck c{kCheckExposureOutlier, false, "", {}};
  const std::size_t n = in.lights.size();
  std::vector<std::string> named;
  // The highlight's peak: the same lamp at about the same distance gives about the same peak
  // (usually clipped) in every photograph, whatever the object does; a misfired flash or a
  // short exposure lowers it.
  double typicalPeak = 0;
  if (in.highlightPeaks.size() == n) {
    std::vector<double> peaks;
    for (double p : in.highlightPeaks)
      if (p > 0) peaks.push_back(p);
    typicalPeak = median(peaks);
  }
  // The clipped area around the highlight: the lamp's halo reaches full scale farther out in a
  // frame exposed too long, whatever the light's direction (the peak itself is clipped and
  // cannot tell).
  double typicalClipped = 0;
  if (in.clippedAreas.size() == n) {
    std::vector<double> areas;
    for (double a : in.clippedAreas)
      if (a > 0) areas.push_back(a);
    if (areas.size() * 2 > n) typicalClipped = median(areas);
  }
  // The mean brightness against the photographs lit from the nearest directions: catches a
  // frame far too bright, or dark where the highlight is not measured.
  const bool means = in.imageMeans.size() == n && n >= static_cast<std::size_t>(LightCheckLimits::kNeighbours) + 2;
  for (std::size_t i = 0; i < n; ++i) {
    std::string why;
    if (typicalPeak > 0 && in.highlightPeaks[i] > 0 &&
        in.highlightPeaks[i] < LightCheckLimits::kPeakRatio * typicalPeak) {
      why = "its highlight peaks at " + fixedDecimals(100 * in.highlightPeaks[i] / typicalPeak, 0) +
            " % of the others': too dark";
    } else if (typicalClipped >= LightCheckLimits::kMinClippedPx &&
               in.clippedAreas[i] > LightCheckLimits::kClippedRatio * typicalClipped) {
      why = "its highlight's halo is clipped at full scale over " +
            fixedDecimals(in.clippedAreas[i] / typicalClipped, 1) + " times the others' area: too bright";
    } else if (means) {
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) near.push_back({angleDeg(in.lights[i], in.lights[j]), j});
      std::sort(near.begin(), near.end());
      std::vector<double> around;
      for (int k = 0; k < LightCheckLimits::kNeighbours; ++k) around.push_back(in.imageMeans[near[k].second]);
      const double expected = median(around);
      const double ratio = expected > 1e-4 ? in.imageMeans[i] / expected : 1;
      if (ratio < LightCheckLimits::kDarkRatio || ratio > LightCheckLimits::kBrightRatio)
        why = fixedDecimals(ratio * 100, 0) + " % of the brightness of the images lit from beside it: " +
              (ratio < 1 ? "too dark" : "too bright");
    }
    if (why.empty()) continue;
    c.images.push_back(static_cast<int>(i));
    named.push_back(in.names[i] + " (" + why + ")");
  }
  c.failed = !c.images.empty();
  c.detail = c.failed ? "an exposure unlike the others': " + listedInFull(named) +
                            ". A misfired flash or a wrong exposure gives a wrong sample to every pixel of the fit"
                      : "every image is exposed like the others";
  return c;
}

}  // namespace

const std::vector<std::string>& lightCheckNames() {
  static const std::vector<std::string> names = {kCheckFrameMoved,       kCheckBelowHorizon,     kCheckSpheresOverlap,
                                                 kCheckSpheresDisagree,  kCheckLightsClustered,
                                                 kCheckExposureOutlier, kCheckResidualOutlier};
  return names;
}

double angleDeg(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (!(na > 0) || !(nb > 0)) return 180;
  const double d = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (na * nb);
  return std::acos(std::clamp(d, -1.0, 1.0)) * 180 / M_PI;
}

std::vector<int> residualOutliers(const std::vector<double>& rmse) {
  std::vector<int> out;
  if (rmse.size() < 5) return out;
  const double m = median(rmse);
  std::vector<double> deviations;
  for (double v : rmse) deviations.push_back(std::abs(v - m));
  const double sigma = 1.4826 * median(deviations);
  for (std::size_t i = 0; i < rmse.size(); ++i)
    if (rmse[i] > LightCheckLimits::kResidualRatio * m && rmse[i] > m + LightCheckLimits::kResidualDeviations * sigma)
      out.push_back(static_cast<int>(i));
  return out;
}

LightCheck residualCheck(const std::vector<double>& rmse, const std::vector<std::string>& names) {
  LightCheck c{kCheckResidualOutlier, false, "", residualOutliers(rmse)};
  const std::string typical = "median RMSE " + fixedDecimals(median(rmse), 1) + " levels";
  std::vector<std::string> named;
  for (int i : c.images)
    named.push_back(names[static_cast<std::size_t>(i)] + " (RMSE " + fixedDecimals(rmse[static_cast<std::size_t>(i)], 1) +
                    " levels)");
  c.failed = !c.images.empty();
  c.detail = c.failed ? "the model misses " + listedInFull(named) + " far more than the other images (" + typical +
                            "): a misfired flash, a moved object or a wrong light direction, which pulls every "
                            "pixel's fit toward it"
                      : "no image stands out of the others' fit error (" + typical + ")";
  return c;
}

LightCheck frameMovedCheck(const std::vector<double>& movedPx, double limitPx, const std::vector<std::string>& names) {
  LightCheck c{kCheckFrameMoved, false, "", {}};
  std::vector<std::string> named;
  for (std::size_t i = 0; i < movedPx.size() && i < names.size(); ++i) {
    if (!(movedPx[i] > limitPx)) continue;
    c.images.push_back(static_cast<int>(i));
    named.push_back(names[i] + " (" + fixedDecimals(movedPx[i], 0) + " px)");
  }
  c.failed = !c.images.empty();
  c.detail = c.failed ? "the picture moved against the other images by more than " + fixedDecimals(limitPx, 0) +
                            " pixels: " + listedInFull(named) +
                            ". The camera was knocked or turned, or the sphere or the object was bumped, between the "
                            "shots: every pixel of the fit would mix different points, and the light would be "
                            "measured on a circle that is not where the sphere is"
                      : "no image moved against the others by more than " + fixedDecimals(limitPx, 0) + " pixels";
  return c;
}

std::vector<LightCheck> checkLights(const LightCheckInput& in) {
  return {belowHorizon(in), spheresOverlap(in), spheresDisagree(in), lightsClustered(in), exposureOutlier(in)};
}

}  // namespace surrogate::hrti
