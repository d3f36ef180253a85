// The published viewer's layout and light disc in headless chromium, on a portrait model (a
// stela stands upright): at 1400x1000 and 800x1000 the page is no wider than the window and
// every button is on the first screen; the disc labels its azimuths and elevation rings, shows
// the elevations photographed (the carrier's lights) and says in words when the light is
// outside them; no number reads "-0.000" when the light is moved onto an axis. What the page
// does not record itself is measured by a probe script when the page is ready (probedCopy).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <regex>
#include <sstream>

#include "e2e_support.h"
#include "headless_chromium.h"

namespace fs = std::filesystem;

namespace {

using e2e::bodyAttribute;
using e2e::BrowserRun;

// When the page sets data-ready, records the window, the page's width, the buttons past
// the window's edges, the disc's labels and any negative zero in the page's text.
const std::string kProbe = e2e::probeOnReady(R"JS(function () {
  var w = window.innerWidth, h = window.innerHeight, outside = [], labels = [];
  Array.prototype.forEach.call(document.querySelectorAll("button"), function (b) {
    var r = b.getBoundingClientRect();
    if (r.top < 0 || r.left < 0 || r.bottom > h || r.right > w) outside.push(b.textContent.trim());
  });
  Array.prototype.forEach.call(document.querySelectorAll("#disc .disc-label"), function (l) { labels.push(l.textContent); });
  var zeros = body.innerText.match(/[-\u2212]0\.0+(?![0-9])/g) || [];
  body.setAttribute("data-probe-viewport", w + "x" + h);
  body.setAttribute("data-probe-page-width", String(document.documentElement.scrollWidth));
  body.setAttribute("data-probe-buttons", String(document.querySelectorAll("button").length));
  body.setAttribute("data-probe-buttons-outside", outside.join("|"));
  body.setAttribute("data-probe-disc-labels", labels.join("|"));
  body.setAttribute("data-probe-negative-zeros", zeros.join("|"));
  function text(id) { var e = document.getElementById(id); return e ? e.textContent : ""; }
  body.setAttribute("data-probe-readout", text("readout"));
  body.setAttribute("data-probe-photographed", text("photographed"));
  body.setAttribute("data-probe-note", text("light-note"));
}
)JS");

BrowserRun openInWindow(const fs::path& page, const std::string& query, int width, int height, const fs::path& work) {
  static const std::string chromium = e2e::chromiumOrSkip("the viewer's layout test");
  return e2e::runChromium(chromium,
                          "--enable-unsafe-swiftshader --hide-scrollbars --window-size=" + std::to_string(width) + "," +
                              std::to_string(height) + " --dump-dom",
                          e2e::fileUrl(page) + query, work);
}

// Opens `page` (a probed copy) with a viewport of `width` x `height`: chromium's --window-size
// includes what its window keeps for itself (some 140 px of height), measured once.
BrowserRun openAt(const fs::path& page, const std::string& query, int width, int height, const fs::path& work) {
  static int kept = -1;
  if (kept < 0) {
    const std::string viewport = bodyAttribute(openInWindow(page, "", 800, 1000, work).dom, "data-probe-viewport");
    kept = viewport.empty() ? 0 : std::max(0, 1000 - std::atoi(viewport.substr(viewport.find('x') + 1).c_str()));
  }
  return openInWindow(page, query, width, height + kept, work);
}

// A 240x320 (portrait) capture run and published once per process; its viewer with the probe.
struct Published {
  fs::path capture, page;
};
const Published& portrait() {
  static const Published p = [] {
    Published out;
    out.capture = e2e::generatedWithTruth("viewer-portrait", "--images 12 --width 240 --height 320 "
                                                             "--sphere-radius 36 --seed 7");
    const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(out.capture) + " --quiet");
    if (run.exitCode != 0) throw std::runtime_error("surrogate run failed: " + run.output);
    const fs::path web = out.capture.parent_path() / "web";
    const e2e::CommandResult publish = e2e::surrogate("publish " + e2e::quote(out.capture) + " -o " + e2e::quote(web));
    if (publish.exitCode != 0) throw std::runtime_error("surrogate publish failed: " + publish.output);
    out.page = e2e::probedCopy(web / "ptm-lrgb" / "index.html", "probed.html", kProbe);
    return out;
  }();
  return p;
}

// The lowest and highest elevation of the lights the carrier records, as the page shows them.
std::pair<std::string, std::string> photographedRange(const fs::path& capture) {
  const std::string carrier = e2e::bytesOf(capture / "assembly-files" / "carrier.xml");
  const std::regex elevation("<light [^>]*elevationDeg=\"([-0-9.eE]+)\"");
  std::vector<double> values;
  for (auto it = std::sregex_iterator(carrier.begin(), carrier.end(), elevation); it != std::sregex_iterator(); ++it)
    values.push_back(std::stod((*it)[1].str()));
  if (values.empty()) throw std::runtime_error("the carrier records no light elevation");
  char lo[32], hi[32];
  std::snprintf(lo, sizeof lo, "%.1f", *std::min_element(values.begin(), values.end()));
  std::snprintf(hi, sizeof hi, "%.1f", *std::max_element(values.begin(), values.end()));
  return {lo, hi};
}

}  // namespace

TEST_CASE("at 1400x1000 and 800x1000 the viewer is no wider than the window and every button is on the first screen") {
  const fs::path work = e2e::freshDir("viewer-layout");
  for (const int width : {1400, 800}) {
    INFO("window " << width << "x1000");
    const BrowserRun b = openAt(portrait().page, "", width, 1000, work);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    const std::string viewport = bodyAttribute(b.dom, "data-probe-viewport");
    INFO("viewport " << viewport);
    CHECK(std::atoi(viewport.c_str()) == width);
    CHECK(std::atoi(viewport.substr(viewport.find('x') + 1).c_str()) == 1000);
    CHECK(std::atoi(bodyAttribute(b.dom, "data-probe-page-width").c_str()) <= width);
    // Relight, Normals, Albedo, the two drag modes and Reset zoom.
    CHECK(bodyAttribute(b.dom, "data-probe-buttons") == "6");
    CHECK(bodyAttribute(b.dom, "data-probe-buttons-outside") == "");
  }
}

TEST_CASE("the viewer disc labels its angles shows the photographed elevations and says when the light is outside them") {
  const fs::path work = e2e::freshDir("viewer-disc");
  const auto [lowest, highest] = photographedRange(portrait().capture);
  // A light at 5 degrees of elevation, below every photographed one (15 degrees and up here).
  const BrowserRun low = openAt(portrait().page, "?light=0.9962,0,0.0872", 1400, 1000, work);
  INFO(low.log);
  REQUIRE(bodyAttribute(low.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(low.dom, "data-probe-disc-labels") ==
        "0\u00b0|90\u00b0|180\u00b0|\u221290\u00b0|el 0\u00b0|el 30\u00b0|el 60\u00b0");
  CHECK(low.dom.find("data-photographed=\"" + lowest + "," + highest + "\"") != std::string::npos);
  CHECK(bodyAttribute(low.dom, "data-probe-photographed") ==
        "Shaded band: the elevations the lights were photographed at, " + lowest + "\u00b0 to " + highest +
            "\u00b0. Outside it the relighting is extrapolated.");
  CHECK(bodyAttribute(low.dom, "data-probe-note") ==
        "Light at 5.0\u00b0 elevation: below the lowest photographed light (" + lowest +
            "\u00b0); the relighting is extrapolated, so it may show what is not on the object.");
  // Straight down the camera's axis, above every photographed light; then one inside the range.
  const BrowserRun high = openAt(portrait().page, "?light=0,0,1", 1400, 1000, work);
  CHECK_THAT(bodyAttribute(high.dom, "data-probe-note"),
             Catch::StartsWith("Light at 90.0\u00b0 elevation: above the highest photographed light (" + highest));
  const BrowserRun inside = openAt(portrait().page, "?light=0.5,0.5,0.7071", 1400, 1000, work);
  REQUIRE(bodyAttribute(inside.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(inside.dom, "data-probe-note") == "");
}

TEST_CASE("moving the viewer light onto the x or y axis never shows a negative zero") {
  const fs::path work = e2e::freshDir("viewer-zero");
  // Drags on the picture in light mode (canvas pixels of the 240x320 model, centre 120,160), each
  // ending a hundredth of a pixel off an axis: y (then x) a hair below zero.
  const std::pair<std::string, int> moves[] = {{"mode,light;drag,120,160,220,160.01", 1},
                                               {"mode,light;drag,120,160,119.99,60", 0}};
  for (const auto& [gestures, axis] : moves) {
    INFO(gestures);
    const BrowserRun b = openAt(portrait().page, "?test&gestures=" + gestures, 1400, 1000, work);
    INFO(b.log);
    REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    INFO("readout: " << bodyAttribute(b.dom, "data-probe-readout"));
    // The drag did move the light there: its recorded vector has the tiny negative component.
    std::istringstream light(bodyAttribute(b.dom, "data-light-gesture-1"));
    double l[3] = {0, 0, 0};
    light >> l[0] >> l[1] >> l[2];
    REQUIRE(l[axis] < 0);
    REQUIRE(l[axis] > -0.0005);
    CHECK(bodyAttribute(b.dom, "data-probe-readout").find(" 0.000") != std::string::npos);
    CHECK(bodyAttribute(b.dom, "data-probe-negative-zeros") == "");
  }
}
