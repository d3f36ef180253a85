// The report's light plot in headless chromium: no elevation ring's label ("el 60°") lies under a
// light's dot, even when a light sits where the label used to go (between the 90 and 135 degree
// spokes, just inside the ring); and at 1400x1000 and 800x1000 the page is no wider than the
// window. The boxes are measured by a probe script when the page is ready (probedCopy).
#include <catch2/catch.hpp>

#include <string>

#include "e2e_support.h"
#include "headless_chromium.h"

namespace fs = std::filesystem;

namespace {

using e2e::bodyAttribute;
using e2e::BrowserRun;

// Every elevation label of every plot against every mark of that plot (lights, prior lights,
// the error plot's points and rings): the pairs whose boxes meet, and how many labels there are.
const std::string kProbe = e2e::probeOnReady(R"JS(function () {
  var met = [], labels = 0;
  function meet(a, b) { return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom; }
  Array.prototype.forEach.call(document.querySelectorAll("svg"), function (svg) {
    var marks = svg.querySelectorAll("circle.light, path.prior-light, circle.error-light, circle.pictured");
    Array.prototype.forEach.call(svg.querySelectorAll("text.elevation"), function (label) {
      ++labels;
      var box = label.getBoundingClientRect();
      Array.prototype.forEach.call(marks, function (m) {
        if (meet(box, m.getBoundingClientRect()))
          met.push(label.textContent + " and " + (m.getAttribute("data-image") || m.getAttribute("class")));
      });
    });
  });
  body.setAttribute("data-probe-labels", String(labels));
  body.setAttribute("data-probe-labels-under-marks", met.join("; "));
  body.setAttribute("data-probe-page-width", String(document.documentElement.scrollWidth));
  body.setAttribute("data-probe-viewport", window.innerWidth + "x" + window.innerHeight);
}
)JS");

}  // namespace

TEST_CASE("no elevation ring label of the report light plot lies under a light and the page fits 800 and 1400 px") {
  const fs::path work = e2e::freshDir("report-plot");
  const fs::path capture = e2e::processedCapture(work);
  // One light moved to 64 degrees of elevation at azimuth 112.5, where "el 60°" was drawn: a
  // light at a dome's upper ring, as in a real capture.
  const fs::path carrierFile = capture / "assembly-files" / "carrier.xml";
  std::string carrier = e2e::bytesOf(carrierFile);
  const std::size_t light = carrier.find("<light ");
  REQUIRE(light != std::string::npos);
  const std::size_t end = carrier.find("/>", light);
  std::string element = carrier.substr(light, end - light);
  for (const auto& [name, value] : {std::pair<std::string, std::string>{"elevationDeg", "64"}, {"azimuthDeg", "112.5"}}) {
    const std::size_t at = element.find(" " + name + "=\"");
    REQUIRE(at != std::string::npos);
    const std::size_t from = at + name.size() + 3;
    element.replace(from, element.find('"', from) - from, value);
  }
  carrier.replace(light, end - light, element);
  std::ofstream(carrierFile, std::ios::binary | std::ios::trunc) << carrier;
  const fs::path page = work / "report.html";
  const e2e::CommandResult made = e2e::surrogate("report " + e2e::quote(capture) + " -o " + e2e::quote(page));
  INFO(made.output);
  REQUIRE(made.exitCode == 0);
  const fs::path probed = e2e::probedCopy(page, "probed.html", kProbe);
  static const std::string chromium = e2e::chromiumOrSkip("the report's plot test");
  for (const int width : {1400, 800}) {
    INFO("window " << width << "x1000");
    const BrowserRun b = e2e::runChromium(
        chromium, "--hide-scrollbars --window-size=" + std::to_string(width) + ",1000 --dump-dom",
        e2e::fileUrl(probed), work);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    CHECK(bodyAttribute(b.dom, "data-probe-labels") == "3");  // el 0, 30 and 60 of the light plot
    CHECK(bodyAttribute(b.dom, "data-probe-labels-under-marks") == "");
    CHECK(std::atoi(bodyAttribute(b.dom, "data-probe-viewport").c_str()) == width);
    CHECK(std::atoi(bodyAttribute(b.dom, "data-probe-page-width").c_str()) <= width);
  }
}
