// The report's colour section on carriers made by hand (colour_carrier.h): the chart's edition,
// where it was found, the figures, the levels and the 24 patches as swatches; one sentence when
// the colours were kept; nothing for a carrier without a colour step.
#include <catch2/catch.hpp>

#include <string>

#include "colour_carrier.h"
#include "report/colour_section.h"
#include "report/report.h"

using namespace surrogate;
using namespace surrogate::report;
using Catch::Contains;

namespace {

class CarrierOnly : public ReportSource {
 public:
  explicit CarrierOnly(carrier::Carrier c) : carrier_(std::move(c)) {}
  const carrier::Carrier& carrier() const override { return carrier_; }
  std::optional<std::string> read(const std::string&) const override { return std::nullopt; }
  std::string describe() const override { return "test source"; }
  bool isPackage() const override { return false; }

 private:
  carrier::Carrier carrier_;
};

std::string page(carrier::Carrier c) {
  CarrierOnly source(std::move(c));
  return buildReport(source.carrier(), source, ReportOptions()).html;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

}  // namespace

TEST_CASE("a Lab D50 colour is shown as the sRGB of its closed form") {
  // D50 white adapts to D65 white; L* 50 is Y = (66/116)^3 = 0.18419, encoded 0.4663 = 118.9.
  CHECK(srgbHex({100, 0, 0}) == "#ffffff");
  CHECK(srgbHex({50, 0, 0}) == "#777777");
  CHECK(srgbHex({0, 0, 0}) == "#000000");
  // The 2014 chart's cyan lies outside sRGB (its red below 0: colour/chart_reference.cpp), its
  // dark skin inside.
  bool clipped = false;
  CHECK(srgbHex({49.57, -29.71, -28.32}, &clipped).substr(0, 3) == "#00");
  CHECK(clipped);
  srgbHex({37.54, 14.37, 14.92}, &clipped);
  CHECK_FALSE(clipped);
}

TEST_CASE("a corrected carrier shows the chart edition and figures and levels and 24 patch swatches") {
  const std::string html = page(colour_test::correctedCarrier());
  REQUIRE_THAT(html, Contains("<section id=\"colour\"><h2>Colour</h2>"));
  CHECK_THAT(html, Contains("<strong>ColorChecker Classic (charts made after November 2014)</strong>, found in "
                            "<code>jpeg-exports/IMG_0003.jpg</code>, measured in 24 frames; the correction is a "
                            "3\u00d73 matrix on linear RGB"));
  CHECK_THAT(html, Contains("<td class=\"num\">6.10</td><td class=\"num\">14.60</td>"));
  CHECK_THAT(html, Contains("<tr><td>corrected</td><td class=\"num\">1.65</td><td class=\"num\">2.80</td></tr>"));
  CHECK_THAT(html, Contains("(held out)</td><td class=\"num\">2.10</td><td class=\"num\">4.30</td>"));
  CHECK_THAT(html, Contains("<li>FADGI 2023: 3 star</li>"));
  CHECK_THAT(html, Contains("<li class=\"warning\">Metamorfoze 2019: below every level</li>"));
  // The mean after correction is within the step's warning limit (4): no warning.
  CHECK_THAT(html, !Contains("stay far from its reference"));

  // The chart: 24 cells, each with its reference; 23 measured, corrected and as photographed.
  CHECK(count(html, "<li class=\"patch\"") == 24);
  CHECK(count(html, "<span class=\"reference\"") == 24);
  CHECK(count(html, "<span class=\"corrected\"") == 23);
  CHECK(count(html, "<span class=\"as-shot\"") == 23);
  CHECK(count(html, "<span class=\"unmeasured\">not measured</span>") == 1);
  CHECK(count(html, "role=\"img\"") == 24 + 23 + 23);
  // In chart order, named, each swatch saying what it is in words.
  CHECK(html.find("data-patch=\"0\"") < html.find("data-patch=\"23\""));
  CHECK_THAT(html, Contains("<span class=\"patch-name\">1 dark skin</span>"));
  CHECK_THAT(html, Contains("aria-label=\"reference: L* 37.54, a* 14.37, b* 14.92 (sRGB #"));
  CHECK_THAT(html, Contains("<span class=\"patch-name\">24 black 2 (1.5 D)</span><span class=\"patch-de\">"
                            "\u0394E<sub>00</sub> 2.8 (was 14.5)</span>"));
  CHECK_THAT(html, Contains("<span class=\"patch-name\">11 yellow green</span><span class=\"patch-de\">clipped or "
                            "shadowed in every frame</span>"));
  // L* 50 a* 0 b* 0 recorded as corrected for neutral 5: #777777 (closed form, above).
  CHECK_THAT(html, Contains("<span class=\"corrected\" style=\"background:#777777\" role=\"img\" title=\"corrected: "
                            "L* 50.00, a* 0.00, b* 0.00 (sRGB #777777)\""));
  // The cyan reference is outside sRGB: said.
  CHECK_THAT(html, Contains("L* 49.57, a* -29.71, b* -28.32 (sRGB #00"));
  CHECK_THAT(html, Contains(", outside sRGB: shown clipped)"));
  // Between the detection and the fits' results.
  CHECK(html.find("<section id=\"detection\"") < html.find("<section id=\"colour\""));
  CHECK(html.find("<section id=\"colour\"") < html.find("<section id=\"results\""));
}

TEST_CASE("the colour section escapes the text the carrier gives") {
  const std::string hostile = "<img src=x onerror=alert(1)>";
  const std::string html = colourSection(colour_test::correctedCarrier(hostile));
  CHECK_THAT(html, !Contains(hostile));
  CHECK_THAT(html, Contains("&lt;img src=x onerror=alert(1)&gt;"));
}

TEST_CASE("colours kept say so in one sentence: no chart found, and no chart used") {
  const std::string notFound = colourSection(colour_test::notFoundCarrier());
  CHECK(notFound == "<section id=\"colour\"><h2>Colour</h2><p>No ColorChecker found in jpeg-exports/IMG_0003.jpg: "
                    "the images keep their colours, as photographed.</p></section>");
  const std::string none = colourSection(colour_test::noChartCarrier());
  CHECK(none == "<section id=\"colour\"><h2>Colour</h2><p>No colour chart was used (--colour-chart none): the "
                "colours are as photographed.</p></section>");
  CHECK_THAT(page(colour_test::notFoundCarrier()), Contains("<section id=\"colour\">"));
}

TEST_CASE("a carrier without a colour step has no colour section") {
  carrier::Carrier c = carrier::newCarrier("Older carrier", {});
  c.addStep("CaptureIngest", "1");
  CHECK(colourSection(c).empty());
  CHECK_THAT(page(c), !Contains("id=\"colour\""));
}
