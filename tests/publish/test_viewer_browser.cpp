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

#include <algorithm>
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

namespace {

// Text as an HTML serializer writes it in element content (the HTML standard's "escaping a
// string": & < > and no-break space; quotes stay), which is how --dump-dom shows text nodes.
std::string asSerializedText(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

// The content of the first element of `dom` that has id="ID" (no nesting of the same tag).
std::string elementById(const std::string& dom, const std::string& tag, const std::string& id) {
  const std::string open = "<" + tag + " id=\"" + id + "\"";
  const std::size_t at = dom.find(open);
  if (at == std::string::npos) return "";
  const std::size_t begin = dom.find('>', at) + 1;
  return dom.substr(begin, dom.find("</" + tag + ">", begin) - begin);
}

// Every href="..." inside the element of id `id` (the index's list of models).
std::vector<std::string> linksIn(const std::string& dom, const std::string& tag, const std::string& id) {
  const std::string list = elementById(dom, tag, id);
  std::vector<std::string> out;
  for (std::size_t at = list.find("href=\""); at != std::string::npos; at = list.find("href=\"", at + 1)) {
    const std::size_t begin = at + 6;
    out.push_back(list.substr(begin, list.find('"', begin) - begin));
  }
  return out;
}

// A title no page may run or render as markup: a script that would mark <body>, an element
// with an event handler, a bold tag, an ampersand and quotes.
const std::string kHostileTitle =
    "<script>document.body.setAttribute('data-pwned','yes')</script><img src=x onerror=\"document.body."
    "setAttribute('data-pwned','img')\"> Stela <b>12</b> & \"friends\"";
const std::string kLicense = "https://creativecommons.org/licenses/by/4.0/";

// A capture run with two models, a web copy and a hostile title, creators, rights and licence.
fs::path describedCapture(const fs::path& dir) {
  const fs::path capture = e2e::smallCapture(dir, 12);
  const auto r = e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --basis hsh2 --publish --no-report" +
                                " --title " + e2e::quote(kHostileTitle) + " --creator " +
                                e2e::quote("Ana Silva:photographer") + " --creator " + e2e::quote("Rui <i>Costa</i>") +
                                " --rights " + e2e::quote("Study only; ask the museum") + " --license " +
                                e2e::quote(kLicense));
  if (r.exitCode != 0) throw std::runtime_error("surrogate run failed: " + r.output);
  return capture;
}

// The title, creators, rights and licence as the page shows them: text, never markup.
void checkDescription(const BrowserRun& b, const std::string& page) {
  INFO(page);
  CHECK(bodyAttribute(b.dom, "data-pwned").empty());
  CHECK(b.dom.find("<b>12</b>") == std::string::npos);
  CHECK(b.dom.find("<img") == std::string::npos);
  CHECK(b.dom.find("<i>Costa") == std::string::npos);
  CHECK(elementById(b.dom, "h1", "title") == asSerializedText(kHostileTitle));
  CHECK(b.dom.find("<title>" + asSerializedText(kHostileTitle)) != std::string::npos);
  const std::string creators = elementById(b.dom, "p", "creators");
  CHECK(creators.find("Ana Silva (photographer)") != std::string::npos);
  CHECK(creators.find("Rui &lt;i&gt;Costa&lt;/i&gt; (creator)") != std::string::npos);
  CHECK(elementById(b.dom, "p", "rights") == "Rights: Study only; ask the museum");
  CHECK(elementById(b.dom, "p", "license").find("<a href=\"" + kLicense + "\"") != std::string::npos);
  CHECK(consoleLines(b.log).empty());
}

}  // namespace

TEST_CASE("the web copy's pages show the title creators rights and licence as text and the index links every model") {
  const fs::path work = e2e::freshDir("viewer-described");
  const fs::path capture = describedCapture(work);
  const fs::path web = capture / "finished-files" / "web";
  for (const std::string basis : {"ptm-lrgb", "hsh2"}) {
    const BrowserRun b = open(web / basis / "index.html", "", work);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    checkDescription(b, basis);
    CHECK(elementById(b.dom, "p", "basis") ==
          std::string("Model: ") + (basis == "hsh2" ? "HSH order 2" : "PTM LRGB") + " (" + basis + ")");
  }

  // The index: the same description, a link per model folder, each to that model's viewer.
  const BrowserRun index = open(web / "index.html", "", work);
  INFO(index.log);
  REQUIRE(index.exitCode == 0);
  checkDescription(index, "index.html");
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(web))
    if (entry.is_directory()) folders.push_back(entry.path().filename().string());
  std::sort(folders.begin(), folders.end());
  REQUIRE(folders == std::vector<std::string>{"hsh2", "ptm-lrgb"});
  std::vector<std::string> links = linksIn(index.dom, "ul", "models");
  std::sort(links.begin(), links.end());
  CHECK(links == std::vector<std::string>{"hsh2/index.html", "ptm-lrgb/index.html"});
  for (const std::string& link : links) {
    INFO(link);
    const BrowserRun target = open(web / link, "", work);  // as the link resolves from the index
    REQUIRE(target.exitCode == 0);
    CHECK(bodyAttribute(target.dom, "data-rendered") == "yes");
    CHECK(elementById(target.dom, "p", "basis").find("(" + link.substr(0, link.find('/')) + ")") != std::string::npos);
  }

  // The carrier records the index as a result of the last WebCopy step.
  const std::string carrier = e2e::bytesOf(capture / "assembly-files" / "carrier.xml");
  CHECK(carrier.find("path=\"finished-files/web/index.html\"") != std::string::npos);

  // `surrogate publish` of the capture writes the same pages, the same bytes twice over.
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "a")).exitCode == 0);
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "b")).exitCode == 0);
  for (const std::string file : {"index.html", "ptm-lrgb/index.html", "hsh2/index.html", "hsh2/viewer-data.js"}) {
    INFO(file);
    CHECK(e2e::bytesOf(work / "a" / file) == e2e::bytesOf(work / "b" / file));
    CHECK(!e2e::bytesOf(work / "a" / file).empty());
  }
  CHECK(e2e::bytesOf(work / "a" / "ptm-lrgb" / "index.html") == e2e::bytesOf(web / "ptm-lrgb" / "index.html"));
  const BrowserRun published = open(work / "a" / "index.html", "", work);
  checkDescription(published, "publish's index.html");
  std::vector<std::string> publishedLinks = linksIn(published.dom, "ul", "models");
  REQUIRE(publishedLinks.size() == 2);
  for (const std::string& link : publishedLinks) CHECK(fs::is_regular_file(work / "a" / link));
  fs::remove_all(work);
}

namespace {

struct Camera {
  double zoom = 0, x = 0, y = 0;
};

Camera recordedCamera(const BrowserRun& b, int gesture) {
  std::istringstream in(bodyAttribute(b.dom, "data-camera-gesture-" + std::to_string(gesture)));
  Camera c;
  if (!(in >> c.zoom >> c.x >> c.y)) throw std::runtime_error("no camera recorded for gesture " + std::to_string(gesture));
  return c;
}

// The share of pixels of `shown` that differ by more than 2 levels from the unzoomed relit
// picture `whole` magnified by the camera: pixel (x, y) shows texel floor(origin + (p + 0.5) / zoom).
double mismatchWithMagnified(const std::vector<int>& shown, const std::vector<int>& whole, const Camera& c, int w, int h) {
  int bad = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int tx = static_cast<int>(std::floor(c.x + (x + 0.5) / c.zoom));
      const int ty = static_cast<int>(std::floor(c.y + (y + 0.5) / c.zoom));
      bool differs = tx < 0 || ty < 0 || tx >= w || ty >= h;
      for (int k = 0; k < 3 && !differs; ++k)
        differs = std::abs(shown[(y * w + x) * 3 + k] - whole[(ty * w + tx) * 3 + k]) > 2;
      bad += differs;
    }
  return static_cast<double>(bad) / (w * h);
}

int at(const std::vector<int>& picture, int w, int x, int y, int k) { return picture[(y * w + x) * 3 + k]; }

}  // namespace

TEST_CASE("the viewer zooms about the cursor pans pinches and resets and relights the zoomed texels") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("viewer-zoom");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(modelFile(capture, "ptm-rgb")) + " -o " + e2e::quote(work / "web")).exitCode == 0);
  const int w = 400, h = 300;
  // Canvas pixels: a wheel turn towards the screen at (120.5, 90.5); a drag by (30, 20); a
  // pinch spreading two fingers 40 pixels either side of (200.5, 150.5) to twice as far; the
  // wheel far in and far out (the limits); the reset button.
  const std::string gestures = "wheel,120.5,90.5,-500;drag,200.5,150.5,230.5,170.5;pinch,200.5,150.5,40,2;"
                               "wheel,200.5,150.5,-100000;wheel,200.5,150.5,100000;wheel,60.5,60.5,-300;reset;"
                               // The light on the picture: Shift+drag, then the button and a plain drag.
                               "wheel,200.5,150.5,-400;shiftdrag,200.5,150.5,350.5,60.5;mode,light;drag,200.5,150.5,60.5,250.5;"
                               "mode,pan;drag,200.5,150.5,150.5,150.5";
  const BrowserRun b = open(work / "web" / "index.html", "?light=-0.8,-0.2,0.3&test&gestures=" + gestures, work);
  INFO(b.log);
  REQUIRE(b.exitCode == 0);
  REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(b.dom, "data-errors").empty());
  CHECK(consoleLines(b.log).empty());
  const auto whole = recordedView(b, "relight", w, h);
  // The unzoomed view is what surrogate render gives (the relighting test checks all bases).
  CHECK(webtest::psnr(whole, renderedBySurrogate(modelFile(capture, "ptm-rgb"), {-0.8, -0.2, 0.3}, work / "r.png")) >= 38);
  std::vector<std::vector<int>> shown;
  std::vector<Camera> camera;
  for (int g = 0; g < 13; ++g) {
    shown.push_back(recordedView(b, "gesture-" + std::to_string(g), w, h));
    camera.push_back(recordedCamera(b, g));
    INFO("gesture " << g << ": zoom " << camera[g].zoom << " origin " << camera[g].x << "," << camera[g].y);
    // Every view is the relit model magnified: the shader relights the texels in view (until
    // gesture 8 moves the light).
    if (g <= 7) CHECK(mismatchWithMagnified(shown[g], whole, camera[g], w, h) < 0.01);
  }
  // The wheel zooms in about the cursor: the texel under it stays under it, and so does its
  // relit colour; the picture is larger (it differs from the unzoomed one).
  CHECK(camera[0].zoom > 1.5);
  CHECK(std::abs(camera[0].x + 120.5 / camera[0].zoom - 120.5) < 0.5);
  CHECK(std::abs(camera[0].y + 90.5 / camera[0].zoom - 90.5) < 0.5);
  for (int k = 0; k < 3; ++k) CHECK(at(shown[0], w, 120, 90, k) == at(whole, w, 120, 90, k));
  CHECK(meanAbsDifference(shown[0], whole) > 1);
  // The drag moves the picture with the pointer: 30 and 20 canvas pixels, at the same zoom.
  CHECK(camera[1].zoom == camera[0].zoom);
  CHECK(std::abs(camera[1].x - (camera[0].x - 30 / camera[0].zoom)) < 1 / camera[0].zoom);
  CHECK(std::abs(camera[1].y - (camera[0].y - 20 / camera[0].zoom)) < 1 / camera[0].zoom);
  for (int k = 0; k < 3; ++k) CHECK(std::abs(at(shown[1], w, 250, 180, k) - at(shown[0], w, 220, 160, k)) <= 2);
  // The pinch doubles the zoom about the fingers' midpoint.
  CHECK(std::abs(camera[2].zoom / camera[1].zoom - 2) < 0.05);
  CHECK(std::abs((camera[2].x + 200.5 / camera[2].zoom) - (camera[1].x + 200.5 / camera[1].zoom)) < 1 / camera[1].zoom);
  // The limits: 32 canvas pixels a texel at most, the whole model at least (and then the
  // picture is the unzoomed one exactly).
  CHECK(camera[3].zoom == 32);
  CHECK(camera[4].zoom == 1);
  CHECK(camera[4].x == 0);
  CHECK(shown[4] == whole);
  // Reset after a zoom: the whole model again.
  CHECK(camera[5].zoom > 1.2);
  CHECK(camera[6].zoom == 1);
  CHECK(shown[6] == whole);
  // Shift+drag and a drag in the light mode move the light and leave the view where it is; the
  // pictures then differ (another light); back in the pan mode a drag pans and keeps the light.
  const auto lightOf = [&](int g) { return bodyAttribute(b.dom, "data-light-gesture-" + std::to_string(g)); };
  CHECK(lightOf(6) == lightOf(7));
  for (const auto& [g, before] : {std::pair<int, int>{8, 7}, {10, 8}}) {
    INFO("gesture " << g);
    CHECK(camera[g].zoom == camera[7].zoom);
    CHECK(camera[g].x == camera[7].x);
    CHECK(camera[g].y == camera[7].y);
    CHECK(lightOf(g) != lightOf(before));
    CHECK(meanAbsDifference(shown[g], shown[before]) > 5);
  }
  CHECK(lightOf(11) == lightOf(10));
  CHECK(lightOf(12) == lightOf(10));
  CHECK(camera[12].zoom == camera[7].zoom);
  CHECK(std::abs(camera[12].x - (camera[7].x + 50 / camera[7].zoom)) < 1 / camera[7].zoom);
  fs::remove_all(work);
}
