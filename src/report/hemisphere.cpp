#include "report/hemisphere.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "report/html.h"

namespace surrogate::report {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCentre = 180, kRadius = 150;
constexpr double kLightDot = 6;  // a light's dot, radius in the plot's units

double wrap360(double deg) {
  double d = std::fmod(deg, 360.0);
  return d < 0 ? d + 360 : d;
}

// Plot coordinates of (elevation, azimuth).
void project(double elevationDeg, double azimuthDeg, double& x, double& y) {
  const double r = kRadius * (90 - std::clamp(elevationDeg, 0.0, 90.0)) / 90;
  x = kCentre + r * std::cos(azimuthDeg * kPi / 180);
  y = kCentre - r * std::sin(azimuthDeg * kPi / 180);
}

std::string num(double v) { return displayNumber(v, 2); }

// An SVG path for the ring sector between two elevations and two azimuths (ccw from a0 to a1).
std::string sectorPath(double e0, double e1, double a0, double a1) {
  std::ostringstream p;
  double x, y;
  const int segments = std::max(2, static_cast<int>(std::ceil((a1 - a0) / 5)));
  for (int i = 0; i <= segments; ++i) {
    project(e0, a0 + (a1 - a0) * i / segments, x, y);
    p << (i == 0 ? "M" : "L") << num(x) << "," << num(y);
  }
  for (int i = segments; i >= 0; --i) {
    project(e1, a0 + (a1 - a0) * i / segments, x, y);
    p << "L" << num(x) << "," << num(y);
  }
  p << "Z";
  return p.str();
}

// A mark of the plot a label must not cover: a light's dot, a cross, a ring, a spoke's label.
struct Mark {
  double x, y, radius;
};

// Whether the box of an elevation label centred at (x, y) (11 px text, "el 60°": some 36 x 12
// units, with a margin) touches a mark.
bool covers(double x, double y, const Mark& m) {
  const double halfWidth = 21, halfHeight = 8;
  const double dx = std::max(0.0, std::abs(m.x - x) - halfWidth), dy = std::max(0.0, std::abs(m.y - y) - halfHeight);
  return dx * dx + dy * dy < m.radius * m.radius;
}

// Elevation rings and azimuth spokes, with their labels. An elevation label goes just inside its
// ring, between the 90 and 135 degree spokes when nothing is there, else at the nearest azimuth
// where it covers none of `marks` (a light drawn over "el 60" hid the label).
void drawGrid(std::ostringstream& s, std::vector<Mark> marks = {}) {
  for (int a = -135; a <= 180; a += 45) {  // the spokes' labels, drawn below
    double tx, ty;
    project(-9, a, tx, ty);
    marks.push_back({tx, ty, 12});
  }
  for (double e : {0.0, 30.0, 60.0}) {
    const double ring = kRadius * (90 - e) / 90;
    double x = 0, y = 0;
    std::size_t fewest = marks.size() + 1;
    for (int k = 0; k <= 48 && fewest > 0; ++k) {  // 112.5, 120, 105, 127.5, 97.5... degrees
      const double az = 112.5 + (k % 2 ? 1 : -1) * 7.5 * ((k + 1) / 2);
      double lx, ly;
      project(e, az, lx, ly);
      lx -= 9 * (lx - kCentre) / ring;
      ly -= 9 * (ly - kCentre) / ring;
      const std::size_t n = static_cast<std::size_t>(
          std::count_if(marks.begin(), marks.end(), [&](const Mark& m) { return covers(lx, ly, m); }));
      if (n < fewest) fewest = n, x = lx, y = ly;
    }
    s << "<circle class=\"grid\" cx=\"" << kCentre << "\" cy=\"" << kCentre << "\" r=\"" << num(ring) << "\"/>";
    s << "<text class=\"axis elevation\" text-anchor=\"middle\" x=\"" << num(x) << "\" y=\"" << num(y + 4)
      << "\">el " << e << "\u00b0</text>\n";
  }
  s << "<circle class=\"grid raking\" cx=\"" << kCentre << "\" cy=\"" << kCentre << "\" r=\""
    << num(kRadius * (90 - kRakingElevationDeg) / 90) << "\"/>\n";
  // Azimuth labels in the lights' own range, -180..180 (the table and the tooltips use it too).
  for (int a = -135; a <= 180; a += 45) {
    double x, y, tx, ty;
    project(0, a, x, y);
    project(-9, a, tx, ty);
    s << "<line class=\"grid\" x1=\"" << kCentre << "\" y1=\"" << kCentre << "\" x2=\"" << num(x)
      << "\" y2=\"" << num(y) << "\"/><text class=\"axis\" text-anchor=\"middle\" x=\"" << num(tx)
      << "\" y=\"" << num(ty + 4) << "\">" << (a < 0 ? "\u2212" : "") << std::abs(a) << "\u00b0</text>\n";
  }
}

// The vertical colour bar of the legend, `gradient` from t = 0 at the bottom to 1 at the top.
void drawScale(std::ostringstream& s, const std::string& gradient) {
  s << "<defs><linearGradient id=\"" << gradient << "\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">";
  for (int i = 0; i <= 4; ++i)
    s << "<stop offset=\"" << i * 25 << "%\" stop-color=\"" << residualColour(i / 4.0) << "\"/>";
  s << "</linearGradient></defs>\n";
}

}  // namespace

double AzimuthGap::widthDeg() const { return wrap360(toDeg - fromDeg); }

Coverage analyseCoverage(const std::vector<LightPoint>& lights) {
  Coverage c;
  if (lights.empty()) return c;
  c.lowestElevationDeg = c.highestElevationDeg = lights.front().elevationDeg;
  std::vector<double> az;
  for (const LightPoint& l : lights) {
    c.lowestElevationDeg = std::min(c.lowestElevationDeg, l.elevationDeg);
    c.highestElevationDeg = std::max(c.highestElevationDeg, l.elevationDeg);
    az.push_back(wrap360(l.azimuthDeg));
  }
  c.missingRaking = c.lowestElevationDeg >= kRakingElevationDeg;
  c.missingHigh = c.highestElevationDeg <= kHighElevationDeg;
  std::sort(az.begin(), az.end());
  for (std::size_t i = 0; i < az.size(); ++i) {
    const double from = az[i];
    const double to = i + 1 < az.size() ? az[i + 1] : az.front() + 360;
    if (to - from > kMaxAzimuthGapDeg) c.azimuthGaps.push_back({from, wrap360(to)});
  }
  return c;
}

std::vector<std::string> Coverage::sentences() const {
  std::vector<std::string> out;
  if (missingRaking)
    out.push_back("No light below " + displayNumber(kRakingElevationDeg, 0) +
                  "\u00b0 elevation (the lowest is " + displayNumber(lowestElevationDeg, 1) +
                  "\u00b0): raking light, which shows relief best, is missing.");
  for (const AzimuthGap& g : azimuthGaps) {
    const double width = g.widthDeg() == 0 ? 360 : g.widthDeg();
    out.push_back("No light between azimuth " + displayNumber(g.fromDeg, 0) + "\u00b0 and " +
                  displayNumber(g.toDeg, 0) + "\u00b0 (a sector of " + displayNumber(width, 0) +
                  "\u00b0): relief facing that way is lit from one side only.");
  }
  if (missingHigh)
    out.push_back("No light above " + displayNumber(kHighElevationDeg, 0) +
                  "\u00b0 elevation (the highest is " + displayNumber(highestElevationDeg, 1) +
                  "\u00b0): the fit has nothing near the camera's axis.");
  return out;
}

std::string residualColour(double t) {
  // Viridis, five stops.
  static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98},
                                     {253, 231, 37}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double f = t - i;
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x",
                static_cast<int>(std::lround(stops[i][0] + f * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + f * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + f * (stops[i + 1][2] - stops[i][2]))));
  return buf;
}

std::string hemisphereSvg(const std::vector<LightPoint>& lights, const Coverage& coverage) {
  return hemisphereSvg(lights, coverage, {});
}

namespace {
// Each prior light as a cross, joined by a line to Surrogate's light of the same image.
void drawPriorLights(std::ostringstream& s, const std::vector<LightPoint>& lights,
                     const std::vector<PriorLightPoint>& priorLights) {
  for (const PriorLightPoint& p : priorLights) {
    double x, y;
    project(p.elevationDeg, p.azimuthDeg, x, y);
    const std::string colour = p.aboveThreshold ? "#d62728" : "#555555";
    for (const LightPoint& l : lights) {
      if (l.image != p.image) continue;
      double lx, ly;
      project(l.elevationDeg, l.azimuthDeg, lx, ly);
      s << "<line class=\"prior-offset\" x1=\"" << num(lx) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(x)
        << "\" y2=\"" << num(y) << "\" stroke=\"" << colour << "\"/>";
    }
    s << "<path class=\"prior-light" << (p.aboveThreshold ? " off" : "") << "\" d=\"M" << num(x - 4) << ","
      << num(y - 4) << "L" << num(x + 4) << "," << num(y + 4) << "M" << num(x - 4) << "," << num(y + 4) << "L"
      << num(x + 4) << "," << num(y - 4) << "\" stroke=\"" << colour << "\" stroke-width=\"2\" data-image=\""
      << escapeHtml(p.image) << "\"><title>" << escapeHtml(p.image) << " in " << escapeHtml(p.file)
      << ": elevation " << displayNumber(p.elevationDeg, 1) << "\u00b0, azimuth " << displayNumber(p.azimuthDeg, 1)
      << "\u00b0, " << displayNumber(p.angleDeg, 1) << "\u00b0 from Surrogate's light</title></path>\n";
  }
}
}  // namespace

std::string hemisphereSvg(const std::vector<LightPoint>& lights, const Coverage& coverage,
                          const std::vector<PriorLightPoint>& priorLights) {
  double lo = 0, hi = 0;
  bool any = false;
  for (const LightPoint& l : lights) {
    if (!l.rmse) continue;
    lo = any ? std::min(lo, *l.rmse) : *l.rmse;
    hi = any ? std::max(hi, *l.rmse) : *l.rmse;
    any = true;
  }
  std::ostringstream s;
  s << "<svg id=\"hemisphere\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 460 360\" "
       "width=\"460\" height=\"360\" role=\"img\" aria-label=\"Light directions on the hemisphere\">\n";
  // Gaps first, beneath everything.
  if (coverage.missingRaking)
    s << "<path class=\"gap\" d=\"" << sectorPath(0, kRakingElevationDeg, 0, 360) << "\"/>\n";
  for (const AzimuthGap& g : coverage.azimuthGaps) {
    const double width = g.widthDeg() == 0 ? 360 : g.widthDeg();
    s << "<path class=\"gap\" d=\"" << sectorPath(0, 90, g.fromDeg, g.fromDeg + width) << "\"/>\n";
  }
  std::vector<Mark> marks;
  for (const LightPoint& l : lights) {
    double x, y;
    project(l.elevationDeg, l.azimuthDeg, x, y);
    marks.push_back({x, y, kLightDot + 1.5});
  }
  for (const PriorLightPoint& p : priorLights) {
    double x, y;
    project(p.elevationDeg, p.azimuthDeg, x, y);
    marks.push_back({x, y, 6.5});
  }
  drawGrid(s, marks);
  // Each light's uncertainty, beneath the lights: a ring of its 95 % bound (the plot's radius is
  // 90 degrees of elevation, so the ring is exact along the elevation and close across it),
  // where it reaches beyond the light's dot (radius 6, 3.6 degrees).
  for (const LightPoint& l : lights) {
    const double ring = l.uncertaintyDeg ? std::min(*l.uncertaintyDeg, 90.0) / 90 * kRadius : 0;
    if (!(ring > kLightDot)) continue;
    double x, y;
    project(l.elevationDeg, l.azimuthDeg, x, y);
    s << "<circle class=\"light-bound\" cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"" << num(ring)
      << "\" fill=\"none\" stroke=\"#555555\" stroke-dasharray=\"2,2\"/>\n";
  }
  // The lights.
  for (const LightPoint& l : lights) {
    double x, y;
    project(l.elevationDeg, l.azimuthDeg, x, y);
    const std::string colour =
        l.rmse ? residualColour(hi > lo ? (*l.rmse - lo) / (hi - lo) : 0.5) : std::string("#999999");
    const bool doubtful = l.highlightConfidence && *l.highlightConfidence < kDoubtfulConfidence;
    s << "<circle class=\"light" << (doubtful ? " doubtful" : "") << "\" cx=\"" << num(x) << "\" cy=\""
      << num(y) << "\" r=\"6\" fill=\"" << colour << "\""
      << (doubtful ? " stroke=\"#d62728\" stroke-width=\"2.5\"" : "") << " data-image=\""
      << escapeHtml(l.image) << "\"><title>" << escapeHtml(l.image)
      << ": elevation " << displayNumber(l.elevationDeg, 1) << "\u00b0, azimuth "
      << displayNumber(l.azimuthDeg, 1) << "\u00b0"
      << (l.uncertaintyDeg ? ", within " + displayNumber(*l.uncertaintyDeg, 1) + "\u00b0 (95 %)" : std::string())
      << (l.rmse ? ", residual " + displayNumber(*l.rmse, 2) + " levels" : std::string())
      << (l.highlightConfidence || l.highlightByHand ? ", highlight confidence " + highlightConfidenceText(l)
                                                     : std::string())
      << "</title></circle>\n";
  }
  drawPriorLights(s, lights, priorLights);
  // Legend: the residual scale.
  drawScale(s, "residual-scale");
  if (any) {
    s << "<rect x=\"400\" y=\"60\" width=\"16\" height=\"200\" fill=\"url(#residual-scale)\"/>"
      << "<text class=\"axis\" x=\"420\" y=\"66\">" << displayNumber(hi, 1) << "</text>"
      << "<text class=\"axis\" x=\"420\" y=\"262\">" << displayNumber(lo, 1) << "</text>"
      << "<text class=\"axis\" x=\"392\" y=\"50\">residual</text>"
      << "<text class=\"axis\" x=\"392\" y=\"280\">(8-bit levels)</text>\n";
  } else {
    s << "<text class=\"axis\" x=\"380\" y=\"60\">no fit: grey</text>\n";
  }
  s << "</svg>";
  return s.str();
}

}  // namespace surrogate::report

namespace surrogate::report {

std::string errorHemisphereSvg(const std::vector<ErrorPoint>& points, const std::string& id) {
  if (points.empty()) return "";
  double lo = points.front().psnr, hi = lo;
  for (const ErrorPoint& p : points) lo = std::min(lo, p.psnr), hi = std::max(hi, p.psnr);
  std::ostringstream s;
  s << "<svg class=\"error-plot\" id=\"" << escapeHtml(id) << "\" xmlns=\"http://www.w3.org/2000/svg\" "
       "viewBox=\"0 0 460 360\" width=\"460\" height=\"360\" role=\"img\" aria-label=\"The prior model's "
       "error at each photograph's light\">\n";
  std::vector<Mark> marks;
  for (const ErrorPoint& p : points) {
    double x, y;
    project(p.elevationDeg, p.azimuthDeg, x, y);
    marks.push_back({x, y, p.pictured ? 11.5 : 7.5});
  }
  drawGrid(s, marks);
  // The worst last, so that it is drawn over its neighbours.
  std::vector<const ErrorPoint*> order;
  for (const ErrorPoint& p : points) order.push_back(&p);
  std::stable_sort(order.begin(), order.end(), [](const ErrorPoint* a, const ErrorPoint* b) { return a->psnr > b->psnr; });
  for (const ErrorPoint* p : order) {
    double x, y;
    project(p->elevationDeg, p->azimuthDeg, x, y);
    // Yellow at the lowest PSNR: the colours of the light plot, where yellow is the largest residual.
    const std::string colour = residualColour(hi > lo ? (hi - p->psnr) / (hi - lo) : 0.5);
    if (p->pictured)
      s << "<circle class=\"pictured\" cx=\"" << num(x) << "\" cy=\"" << num(y)
        << "\" r=\"10\" fill=\"none\" stroke=\"#222\" stroke-width=\"2\"/>";
    s << "<circle class=\"error-light\" cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"6\" fill=\"" << colour
      << "\" data-image=\"" << escapeHtml(p->image) << "\" data-psnr=\"" << displayNumber(p->psnr, 2) << "\"><title>"
      << escapeHtml(p->image) << ": elevation " << displayNumber(p->elevationDeg, 1) << "\u00b0, azimuth "
      << displayNumber(p->azimuthDeg, 1) << "\u00b0; prior PSNR " << displayNumber(p->psnr, 2) << " dB, RMSE "
      << displayNumber(p->rmse, 2) << " levels" << (p->pictured ? "; difference image below" : "")
      << "</title></circle>\n";
  }
  const std::string gradient = id + "-scale";
  drawScale(s, gradient);
  s << "<rect x=\"400\" y=\"60\" width=\"16\" height=\"200\" fill=\"url(#" << escapeHtml(gradient) << ")\"/>"
    << "<text class=\"axis\" x=\"420\" y=\"66\">" << displayNumber(lo, 1) << "</text>"
    << "<text class=\"axis\" x=\"420\" y=\"262\">" << displayNumber(hi, 1) << "</text>"
    << "<text class=\"axis\" x=\"392\" y=\"36\">prior</text>"
    << "<text class=\"axis\" x=\"392\" y=\"50\">PSNR (dB)</text>"
    << "<circle cx=\"392\" cy=\"296\" r=\"10\" fill=\"none\" stroke=\"#222\" stroke-width=\"2\"/>"
    << "<text class=\"axis\" x=\"406\" y=\"300\">difference</text>"
    << "<text class=\"axis\" x=\"406\" y=\"314\">image</text>\n";
  s << "</svg>";
  return s.str();
}

std::string highlightConfidenceText(const LightPoint& light) {
  if (!light.highlightConfidence) return light.highlightByHand ? "by hand" : "-";
  return displayNumber(*light.highlightConfidence, 2) + (light.highlightByHand ? ", and one by hand" : "");
}

}  // namespace surrogate::report
