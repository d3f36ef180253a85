#include "report/colour_section.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "colour/colour_space.h"
#include "core/text.h"
#include "report/html.h"

namespace surrogate::report {

namespace {

// The mean CIEDE2000 after correction above which the colour step warns (its kWarnMeanDeltaE):
// said on the page too, beside the figures.
constexpr double kFarMeanDeltaE = 4;
constexpr int kChartColumns = 6, kChartPatches = 24;

std::string figure(const std::optional<double>& v, int digits = 2) {
  return v ? fixedDecimals(*v, digits) : std::string("-");
}

std::string labText(const carrier::LabValues& lab) {
  return "L* " + fixedDecimals(lab[0], 2) + ", a* " + fixedDecimals(lab[1], 2) + ", b* " + fixedDecimals(lab[2], 2);
}

std::string modelWords(const std::string& model) {
  if (model == "matrix") return "a 3\u00d73 matrix on linear RGB";
  if (model == "root-polynomial") return "a root-polynomial of degree 2 on linear RGB (3\u00d76)";
  return model;
}

// One swatch: its colour, and the words a screen reader and a hover give for it.
std::string swatch(const char* cls, const std::string& what, const carrier::LabValues& lab) {
  bool clipped = false;
  const std::string hex = srgbHex(lab, &clipped);
  const std::string words = what + ": " + labText(lab) + " (sRGB " + hex + (clipped ? ", outside sRGB: shown clipped" : "") + ")";
  return "<span class=\"" + std::string(cls) + "\" style=\"background:" + hex + "\" role=\"img\" title=\"" +
         escapeHtml(words) + "\" aria-label=\"" + escapeHtml(words) + "\"></span>";
}

std::string patchCell(const carrier::ColourPatch& p) {
  std::ostringstream s;
  s << "<li class=\"patch\" data-patch=\"" << p.index << "\"><span class=\"patch-swatches\">";
  if (p.reference) s << swatch("reference", "reference", *p.reference);
  if (p.corrected) s << swatch("corrected", "corrected", *p.corrected);
  else s << "<span class=\"unmeasured\">not measured</span>";
  if (p.before) s << swatch("as-shot", "as photographed", *p.before);
  s << "</span><span class=\"patch-name\">" << p.index + 1 << " " << escapeHtml(p.name) << "</span>";
  if (p.deltaE2000)
    s << "<span class=\"patch-de\">\u0394E<sub>00</sub> " << fixedDecimals(*p.deltaE2000, 1)
      << (p.deltaE2000Before ? " (was " + fixedDecimals(*p.deltaE2000Before, 1) + ")" : std::string()) << "</span>";
  else
    s << "<span class=\"patch-de\">clipped or shadowed in every frame</span>";
  s << "</li>";
  return s.str();
}

std::string figuresTable(const carrier::ColourSummary& k) {
  std::ostringstream s;
  s << "<table class=\"colour-figures\"><tr><th>CIEDE2000 over the patches</th><th>mean</th><th>max</th></tr>"
    << "<tr><td>as photographed (exposure set by the neutral patches)</td><td class=\"num\">" << figure(k.meanBefore)
    << "</td><td class=\"num\">" << figure(k.maxBefore) << "</td></tr><tr><td>corrected</td><td class=\"num\">"
    << figure(k.meanAfter) << "</td><td class=\"num\">" << figure(k.maxAfter) << "</td></tr>"
    << "<tr><td>each patch corrected by a fit without it (held out)</td><td class=\"num\">" << figure(k.meanHeldOut)
    << "</td><td class=\"num\">" << figure(k.maxHeldOut) << "</td></tr></table>";
  return s.str();
}

std::string correctedBody(const carrier::ColourSummary& k) {
  std::ostringstream s;
  const std::string title = k.referenceTitle.empty() ? k.reference : k.referenceTitle;
  s << "<p>The colours the fits read were corrected from a chart: <strong>" << escapeHtml(title) << "</strong>, "
    << (k.method == "given" ? "its corners given by hand" : "found") << " in <code>" << escapeHtml(k.image) << "</code>";
  if (k.framesMeasured)
    s << ", measured in " << *k.framesMeasured << (*k.framesMeasured == 1 ? " frame" : " frames");
  s << "; the correction is " << escapeHtml(modelWords(k.model))
    << ", fitted to the chart's reference values. The photographs themselves are unchanged.</p>";
  s << figuresTable(k);
  s << "<p class=\"note\">CIEDE2000 (\u0394E<sub>00</sub>) is the difference people see between two colours: "
       "about 1 is just noticeable side by side. The held-out figures are the fairer guide to colours that are "
       "not on the chart.</p>";
  if (k.meanAfter && *k.meanAfter > kFarMeanDeltaE)
    s << "<p class=\"warning\">The chart's colours stay far from its reference after correction: check the "
         "chart's edition (--chart-reference), its lighting, or try --colour-model root-polynomial.</p>";
  if (!k.qualityLevels.empty()) {
    s << "<p>Levels met by the corrected chart:</p><ul class=\"quality-levels\">";
    for (const std::string& level : k.qualityLevels)
      s << "<li" << (level.find("below every level") != std::string::npos ? " class=\"warning\"" : "") << ">"
        << escapeHtml(level) << "</li>";
    s << "</ul>";
  }
  s << "<h3>The chart, patch by patch</h3><p class=\"note\">In each patch: left, the chart's reference colour; "
       "middle, the colour measured and corrected; right (narrow), as photographed. Under each, its "
       "\u0394E<sub>00</sub> after correction (and before). Colours are shown in sRGB: approximate on an "
       "uncalibrated screen.</p><ol class=\"colour-chart\" aria-label=\"" << escapeHtml(title)
    << ", 24 patches in 4 rows of " << kChartColumns << "\">";
  for (const carrier::ColourPatch& p : k.patches) s << patchCell(p);
  s << "</ol>";
  if (static_cast<int>(k.patches.size()) != kChartPatches)
    s << "<p class=\"warning\">The carrier records " << k.patches.size() << " of the chart's " << kChartPatches
      << " patches.</p>";
  return s.str();
}

}  // namespace

std::string srgbHex(const carrier::LabValues& lab, bool* clipped) {
  const colour::Rgb linear = colour::linearSrgbFromLabD50({lab[0], lab[1], lab[2]});
  constexpr double kTolerance = 1e-3;  // rounding in the recorded two decimals is not "outside"
  bool outside = false;
  char hex[8];
  int channels[3];
  for (int i = 0; i < 3; ++i) {
    if (!(linear[i] >= -kTolerance && linear[i] <= 1 + kTolerance)) outside = true;
    const double v = std::isfinite(linear[i]) ? std::clamp(linear[i], 0.0, 1.0) : 0.0;
    channels[i] = static_cast<int>(std::lround(colour::srgbEncode(v) * 255));
  }
  std::snprintf(hex, sizeof hex, "#%02x%02x%02x", channels[0], channels[1], channels[2]);
  if (clipped) *clipped = outside;
  return hex;
}

std::string colourSection(const carrier::Carrier& c) {
  const std::optional<carrier::ColourSummary> k = carrier::describeColour(c);
  if (!k) return "";
  std::ostringstream s;
  s << "<section id=\"colour\"><h2>Colour</h2>";
  if (k->corrected) {
    s << correctedBody(*k);
  } else if (k->chart == "none") {
    s << "<p>No colour chart was used (--colour-chart none): the colours are as photographed.</p>";
  } else {
    // The step's own sentence ("no ColorChecker found in IMG.jpg: the images keep their colours").
    std::string said = k->outcome.empty() ? std::string("no colour correction was recorded") : k->outcome;
    said[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(said[0])));
    said += said.find("keep their colours") == std::string::npos ? ": the colours are as photographed" : ", as photographed";
    s << "<p>" << escapeHtml(said) << ".</p>";
  }
  s << "</section>";
  return s.str();
}

}  // namespace surrogate::report
