// The light directions of a capture on a hemisphere plot, and the gaps in their coverage.
//
// The plot is the hemisphere seen from the camera: the centre is a light on the optical axis
// (elevation 90 degrees), the rim is grazing light (elevation 0); azimuth 0 is to the right of
// the image, 90 at the top (x right, y up, as in the carrier):
//
//     radius = R * (90 - elevation) / 90        point = centre + radius * (cos az, -sin az)
//
// Coverage rules (what a photographer would redo the capture for):
//   - no light below kRakingElevationDeg: raking light, which shows relief best, is missing;
//   - an azimuth sector wider than kMaxAzimuthGapDeg without any light: relief facing that way
//     is only lit from one side;
//   - no light above kHighElevationDeg: the fit has nothing near the axis.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace surrogate::report {

inline constexpr double kRakingElevationDeg = 20;
inline constexpr double kMaxAzimuthGapDeg = 90;
inline constexpr double kHighElevationDeg = 60;

struct LightPoint {
  std::string image;           // the image's path in the capture
  double elevationDeg = 0;     // 0 grazing .. 90 on the axis
  double azimuthDeg = 0;       // -180..180, 0 right, 90 up
  std::optional<double> rmse;  // the fit's residual on this image (8-bit levels), if fitted
  // How far the highlight(s) the light was measured from can be trusted, 0..1: the lowest
  // confidence of the highlights used (carrier highlight/@confidence); absent for lights from
  // an .lp file or carriers that do not record it.
  std::optional<double> highlightConfidence;
  // A highlight the light was measured from was given by hand (flag "manual"): it has no
  // confidence of its own (the carrier records 1), so it does not count in highlightConfidence.
  bool highlightByHand = false;
  // The 95 % bound in degrees on the light's angle from the true direction (carrier
  // light/@uncertaintyDegrees, hrti/light_uncertainty.h); absent for lights from an .lp file.
  std::optional<double> uncertaintyDeg;
};

// The highlight confidence as the page shows it: "0.93", "by hand", "0.93, and one by hand",
// or "-" when neither is known.
std::string highlightConfidenceText(const LightPoint& light);

// Below this highlight confidence a light is marked as doubtful on the plot (a red ring).
inline constexpr double kDoubtfulConfidence = 0.5;

struct AzimuthGap {
  double fromDeg = 0, toDeg = 0;  // counter-clockwise from `fromDeg` to `toDeg`, 0..360
  double widthDeg() const;
};

struct Coverage {
  std::vector<AzimuthGap> azimuthGaps;
  bool missingRaking = false;  // no light below kRakingElevationDeg
  bool missingHigh = false;    // no light above kHighElevationDeg
  double lowestElevationDeg = 0, highestElevationDeg = 0;
  // One sentence per finding, for the page and --json.
  std::vector<std::string> sentences() const;
};

// Empty `lights` gives an empty Coverage.
Coverage analyseCoverage(const std::vector<LightPoint>& lights);

// The plot as an inline <svg id="hemisphere"> with one <circle class="light"> per light,
// coloured from low (dark blue) to high residual (yellow), a red ring round the lights whose
// highlight confidence is below kDoubtfulConfidence, gaps shaded, and a colour legend.
std::string hemisphereSvg(const std::vector<LightPoint>& lights, const Coverage& coverage);

// A light of a prior light file (the Audit step, audit/recorded.h), drawn beside Surrogate's
// light of the same image: a cross joined to it by a line, red when the two differ by more than
// the audit's threshold.
struct PriorLightPoint {
  std::string image;  // the image's path in the capture (LightPoint::image)
  std::string file;   // the prior light file
  double elevationDeg = 0, azimuthDeg = 0;
  double angleDeg = 0;  // to Surrogate's light
  bool aboveThreshold = false;
};

// The plot with the prior lights drawn too (<path class="prior-light">, one per prior light).
std::string hemisphereSvg(const std::vector<LightPoint>& lights, const Coverage& coverage,
                          const std::vector<PriorLightPoint>& priorLights);

// A photograph's light on the plot of a prior model's error (the Audit result, audit/recorded.h):
// the prior light it was rendered at, and the prior's error against it there.
struct ErrorPoint {
  std::string image;  // the photograph's file name
  double elevationDeg = 0, azimuthDeg = 0;
  double psnr = 0, rmse = 0;  // dB; 8-bit levels of luminance
  bool pictured = false;      // a difference image was made at it
};

// The prior's error per photograph on the hemisphere (the projection above): an inline
// <svg class="error-plot" id=`id`> with one <circle class="error-light"> per photograph,
// coloured by PSNR on the viridis-like scale, yellow at the lowest PSNR (the largest error) and
// dark at the highest, those with a difference image ringed, and a legend. Empty without points.
std::string errorHemisphereSvg(const std::vector<ErrorPoint>& points, const std::string& id);

// "#rrggbb" for t in 0..1 on a viridis-like scale.
std::string residualColour(double t);

}  // namespace surrogate::report
