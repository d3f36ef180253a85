// The viewer `surrogate publish` writes (index.html and viewer-data.js) in a real browser:
// Debian's chromium, headless, opening the folder from file:// with software WebGL. It loads
// with no console message and no script error; in its test mode (?test) it records the
// pixels of its three views on <body> as PNG data URLs, which are compared here with
// `surrogate render` of the .ptm/.rti (relighting), with the normals and albedo pictures
// `surrogate run` writes (the other views), and with the independent reader of web_reader.h
// reading the same folder; a second light changes the pixels. Also with Deep Zoom tiles.
//
// Without chromium on PATH (or in $SURROGATE_CHROMIUM) the tests exit with code 77, which
// ctest reports as skipped; scripts/install-deps installs it.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "e2e_support.h"
#include "fitted_capture.h"
#include "headless_chromium.h"
#include "web_reader.h"

namespace fs = std::filesystem;

namespace {

using e2e::bodyAttribute;
using e2e::BrowserRun;
using e2e::consoleLines;

// Opens `page` with `query` (e.g. "?light=0.5,0.5,0.7&test") and returns the DOM after the
// page's scripts ran. Software WebGL (SwiftShader) is asked for by name, as a machine without
// a GPU needs.
BrowserRun open(const fs::path& page, const std::string& query, const fs::path& work) {
  static const std::string chromium = e2e::chromiumOrSkip("the viewer's browser test");
  return e2e::runChromium(chromium, "--enable-unsafe-swiftshader --window-size=1200,900 --dump-dom",
                          e2e::fileUrl(page) + query, work);
}

// A view the page recorded (data-pixels-NAME, a PNG data URL).
std::vector<int> recordedView(const BrowserRun& b, const std::string& name, int width, int height) {
  const std::string uri = bodyAttribute(b.dom, "data-pixels-" + name);
  const std::string prefix = "data:image/png;base64,";
  if (uri.compare(0, prefix.size(), prefix) != 0) throw std::runtime_error("no " + name + " view recorded");
  const std::string png = webtest::decodeBase64(uri.substr(prefix.size()));
  const cv::Mat bgr = cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())),
                                   cv::IMREAD_COLOR);
  if (bgr.cols != width || bgr.rows != height) throw std::runtime_error("the " + name + " view has the wrong size");
  return webtest::rgbValues(bgr);
}

std::vector<int> picture(const fs::path& png) {
  cv::Mat m = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
  if (m.depth() == CV_16U) m.convertTo(m, CV_8U, 1.0 / 257.0);  // round(v / 257), as the viewer's copy
  if (m.channels() == 1) cv::cvtColor(m, m, cv::COLOR_GRAY2BGR);
  return webtest::rgbValues(m);
}

double meanAbsDifference(const std::vector<int>& a, const std::vector<int>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
  return sum / static_cast<double>(a.size());
}

const std::vector<std::string> kModels = {"ptm-lrgb", "ptm-rgb", "hsh2", "hsh3"};
// Two lights far apart (x right, y up, z to the camera), as `surrogate render --light` takes them.
const std::vector<std::array<double, 3>> kLights = {{0.5, 0.5, 0.7071}, {-0.8, -0.2, 0.3}};

std::string lightText(const std::array<double, 3>& l) {
  std::ostringstream s;
  s << l[0] << "," << l[1] << "," << l[2];
  return s.str();
}

fs::path modelFile(const fs::path& capture, const std::string& name) {
  return capture / "finished-files" / (name + (name.rfind("ptm", 0) == 0 ? ".ptm" : ".rti"));
}

using publishtest::fittedCapture;
using publishtest::renderedBySurrogate;

// The viewer of `folder` against `surrogate render` of `model` at both lights, and against the
// independent reader when the viewer holds the plane files' own bytes (`samePlanes`; tiles
// are JPEG blocks of their own, with an error of their own); returns the relit pictures.
std::vector<std::vector<int>> checkRelighting(const fs::path& folder, const fs::path& model, const fs::path& work,
                                              bool samePlanes = true) {
  const webtest::WebModel web = webtest::readWebModel(folder);
  std::vector<std::vector<int>> relit;
  for (const auto& l : kLights) {
    INFO(folder.filename().string() << " at light " << lightText(l));
    const BrowserRun b = open(folder / "index.html", "?light=" + lightText(l) + "&test", work);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    REQUIRE(bodyAttribute(b.dom, "data-size") == std::to_string(web.width) + "x" + std::to_string(web.height));
    relit.push_back(recordedView(b, "relight", web.width, web.height));
    const auto reference = renderedBySurrogate(model, l, work / "rendered.png");
    const auto reader = webtest::renderAt(web, l[0], l[1], l[2]);
    const double psnr = webtest::psnr(relit.back(), reference);
    const int fromReader = webtest::maxAbsDifference(relit.back(), reader);
    WARN(folder.filename().string() << " light " << lightText(l) << ": PSNR " << psnr
                                    << " dB against surrogate render, at most " << fromReader
                                    << " levels from the independent reader, mean "
                                    << meanAbsDifference(relit.back(), reader));
    // The JPEG error of quality 95 (docs/formats.md, "The error of the web copy": 40 dB and
    // more at quality 90); a swapped term, channel or row order gives less than 25 dB.
    CHECK(psnr >= 38);
    // The same planes as the reader decodes: the browser's JPEG decoder and its float32
    // arithmetic may move a value by a level or two where the reader's rounding is at .5.
    if (samePlanes) {
      CHECK(fromReader <= 2);
      CHECK(meanAbsDifference(relit.back(), reader) < 0.05);
    }
  }
  // The light moves the shading: the two pictures differ by several levels on average.
  CHECK(meanAbsDifference(relit[0], relit[1]) > 5);
  return relit;
}

}  // namespace

TEST_CASE("the published viewer opens from file:// in headless chromium with no console message") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("viewer-plain");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "web")).exitCode == 0);
  for (const std::string& name : kModels) {
    INFO(name);
    const BrowserRun b = open(work / "web" / name / "index.html", "", work);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-rendered") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    CHECK(consoleLines(b.log).empty());
  }
  fs::remove_all(work);
}

TEST_CASE("the published viewer relights PTM LRGB PTM RGB HSH2 and HSH3 as surrogate render within the JPEG error") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("viewer-relight");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "web")).exitCode == 0);
  for (const std::string& name : kModels) checkRelighting(work / "web" / name, modelFile(capture, name), work);
  fs::remove_all(work);
}

TEST_CASE("the viewer's normals and albedo views show the pictures surrogate run writes within the JPEG error") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("viewer-maps");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(modelFile(capture, "ptm-lrgb")) + " -o " + e2e::quote(work / "web")).exitCode == 0);
  const BrowserRun b = open(work / "web" / "index.html", "?test", work);
  INFO(b.log);
  REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(b.dom, "data-errors").empty());
  // normals.png and albedo.png are the DerivedMaps stage's, of the first model fitted (PTM LRGB).
  for (const std::string view : {"normals", "albedo"}) {
    const auto shown = recordedView(b, view, 400, 300);
    const auto written = picture(capture / "finished-files" / (view + ".png"));
    const double psnr = webtest::psnr(shown, written);
    WARN(view << ": PSNR " << psnr << " dB against finished-files/" << view << ".png");
    CHECK(psnr >= 38);
  }
  // The normals view is not the albedo view (the buttons are wired to different pictures).
  CHECK(meanAbsDifference(recordedView(b, "normals", 400, 300), recordedView(b, "albedo", 400, 300)) > 10);
  fs::remove_all(work);
}

TEST_CASE("the viewer of a model published as Deep Zoom tiles relights it as surrogate render") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("viewer-tiles");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(modelFile(capture, "hsh2")) + " -o " + e2e::quote(work / "web") +
                         " --tiles deepzoom --tile-size 128").exitCode == 0);
  REQUIRE(fs::is_regular_file(work / "web" / "plane_0.dzi"));
  REQUIRE_FALSE(fs::exists(work / "web" / "plane_0.jpg"));
  checkRelighting(work / "web", modelFile(capture, "hsh2"), work, false);
  fs::remove_all(work);
}
