// The report of a generated capture in a real browser (Debian's chromium, headless): it loads
// without console output or script errors, plots one point per light and renders the
// relighting view; at 1400 and 800 px wide the viewer is on the first screen and nothing
// reaches past the viewport's edges (screenshots kept in the build tree,
// tests/report/artefacts/report-1400.png and report-800.png); the page's relighting of a PTM
// and of HSH models gives the pixels of `surrogate render` (src/fit/render.cpp) and changes
// with the light. Also `surrogate report` on a bag directory and a .tar.
//
// Without chromium on PATH (or in $SURROGATE_CHROMIUM), the browser tests exit with code 77,
// which ctest reports as skipped. scripts/install-deps installs it, so CI runs them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "carrier/carrier.h"
#include "e2e_support.h"
#include "headless_chromium.h"
#include "formats/lp.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

using e2e::bodyAttribute;
using e2e::BrowserRun;
using e2e::consoleLines;

const std::string& chromium() {
  static const std::string program = e2e::chromiumOrSkip("the report's browser test");
  return program;
}

// Loads `page` in headless chromium with `extra` flags, after the page's scripts ran.
BrowserRun load(const fs::path& page, const fs::path& work, const std::string& extra) {
  return e2e::runChromium(chromium(), extra, e2e::fileUrl(page), work);
}

// Loads `page` (with `hash`, e.g. "#model=1&light=0.5,0.5,0.7") at `width` x `height` and
// returns chromium's DOM after the page's scripts ran.
BrowserRun loadAt(const fs::path& page, const fs::path& work, int width, int height, const std::string& hash = "") {
  return e2e::runChromium(chromium(),
                          "--hide-scrollbars --window-size=" + std::to_string(width) + "," + std::to_string(height) +
                              " --dump-dom",
                          e2e::fileUrl(page) + hash, work);
}

int intAttribute(const std::string& dom, const std::string& name) {
  return std::atoi(bodyAttribute(dom, name).c_str());
}

// "x,y:r,g,b;..." of the page (data-relight-probes), and the same texels of a picture.
struct Probe {
  int x = 0, y = 0, rgb[3] = {0, 0, 0};
};

std::vector<Probe> parseProbes(const std::string& text) {
  std::vector<Probe> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ';');) {
    Probe p;
    if (std::sscanf(item.c_str(), "%d,%d:%d,%d,%d", &p.x, &p.y, &p.rgb[0], &p.rgb[1], &p.rgb[2]) == 5) out.push_back(p);
  }
  return out;
}

// The mean of R, G and B over a picture written by `surrogate render` (8-bit).
double meanOf(const cv::Mat& bgr) {
  const cv::Scalar m = cv::mean(bgr);
  return (m[0] + m[1] + m[2]) / 3;
}

int lightsInCarrier(const fs::path& capture) {
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  int n = 0;
  for (const carrier::Result& r : c.data) n = std::max(n, static_cast<int>(r.itemsOf("light").size()));
  return n;
}

}  // namespace

TEST_CASE("the report of a run opens in headless chromium without errors, one point per light") {
  const fs::path work = e2e::freshDir("report-browser");
  const fs::path capture = e2e::smallCapture(work, 12);
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const fs::path page = capture / "finished-files/report.html";
  REQUIRE(fs::is_regular_file(page));
  // The report is a view, not a recorded output: the carrier does not list it.
  CHECK(carrier::loadCarrier(capture / "assembly-files/carrier.xml").findFileByPath("finished-files/report.html") == nullptr);

  const int lights = lightsInCarrier(capture);
  REQUIRE(lights == 12);
  REQUIRE(formats::readLp(capture / "assembly-files/lights.lp").size() == 12u);

  const BrowserRun b = load(page, work, "--dump-dom");
  INFO(b.log);
  REQUIRE(b.exitCode == 0);
  CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(b.dom, "data-errors").empty());
  CHECK(consoleLines(b.log).empty());
  CHECK(bodyAttribute(b.dom, "data-lights-plotted") == std::to_string(lights));
  CHECK(bodyAttribute(b.dom, "data-lights-expected") == std::to_string(lights));
  CHECK(bodyAttribute(b.dom, "data-relight") == "rendered");
  // The relit object is neither black nor blown out (the generated relief is mid-grey-brown).
  const double mean = std::atof(bodyAttribute(b.dom, "data-relight-mean").c_str());
  INFO("mean brightness of the relit view: " << mean);
  CHECK(mean > 30);
  CHECK(mean < 230);

  fs::copy_file(page, fs::path(REPORT_ARTEFACT_DIR) / "report.html", fs::copy_options::overwrite_existing);
}

TEST_CASE("at 1400 and 800 px wide the report shows the viewer on the first screen and nothing past the edges") {
  const fs::path work = e2e::freshDir("report-layout");
  const fs::path capture = e2e::smallCapture(work, 12);
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const fs::path page = capture / "finished-files/report.html";
  const fs::path artefacts = REPORT_ARTEFACT_DIR;
  fs::create_directories(artefacts);
  // A laptop's first screen: 900 px of window, of which chromium gives the page what is left.
  const int windowHeight = 900;
  for (const int width : {1400, 800}) {
    INFO("window width " << width);
    const BrowserRun b = loadAt(page, work, width, windowHeight);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    REQUIRE(bodyAttribute(b.dom, "data-ready") == "yes");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    const std::string viewport = bodyAttribute(b.dom, "data-viewport");
    const int viewportWidth = std::atoi(viewport.c_str());
    const int viewportHeight = std::atoi(viewport.substr(viewport.find('x') + 1).c_str());
    INFO("viewport " << viewport << ", viewer from " << bodyAttribute(b.dom, "data-viewer-top") << " to "
                     << bodyAttribute(b.dom, "data-viewer-bottom") << " px");
    CHECK(viewportWidth == width);
    REQUIRE(viewportHeight > 600);
    // The viewer, whole, on the first screen: before the plot, the pictures and the tables.
    CHECK(intAttribute(b.dom, "data-viewer-top") > 0);
    CHECK(intAttribute(b.dom, "data-viewer-bottom") <= viewportHeight);
    // The model's own resolution (400x300 here), not stretched.
    CHECK(intAttribute(b.dom, "data-viewer-width") == 402);  // 400 px and a 1 px border each side
    // Nothing wider than the window, no element past its left or right edge.
    CHECK(intAttribute(b.dom, "data-page-width") <= width);
    CHECK(bodyAttribute(b.dom, "data-outside").empty());

    const fs::path shot = artefacts / ("report-" + std::to_string(width) + ".png");
    fs::remove(shot);
    const BrowserRun s = load(page, work, "--hide-scrollbars --window-size=" + std::to_string(width) +
                                              ",1800 --screenshot=" + e2e::quote(shot));
    INFO(s.log);
    CHECK(s.exitCode == 0);
    REQUIRE(fs::is_regular_file(shot));
    const cv::Mat picture = cv::imread(shot.string(), cv::IMREAD_COLOR);
    REQUIRE_FALSE(picture.empty());
    CHECK(picture.cols == width);
  }
}

TEST_CASE("the page relights PTM and HSH models with the pixels of surrogate render, and a new light changes them") {
  const fs::path work = e2e::freshDir("report-relight");
  struct Case {
    std::string runOptions;
    std::vector<std::string> models;  // data-relight-models, in the page's order
  };
  // The default run fits a PTM and an HSH; an HSH-only run must be relightable too.
  const std::vector<Case> cases = {{"", {"ptm-lrgb", "hsh2"}}, {"--basis hsh3", {"hsh3"}}};
  // Two lights far apart (x right, y up, z to the camera), as `surrogate render --light` takes them.
  const std::vector<std::string> lights = {"0.5,0.5,0.7071", "-0.8,-0.2,0.3"};
  int caseIndex = 0;
  for (const Case& c : cases) {
    const fs::path dir = work / ("case" + std::to_string(caseIndex++));
    fs::create_directories(dir);
    const fs::path capture = e2e::smallCapture(dir, 12);  // hsh3 needs 9 photographs at least
    const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet " + c.runOptions);
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    const fs::path page = capture / "finished-files/report.html";
    for (std::size_t m = 0; m < c.models.size(); ++m) {
      const fs::path model = capture / "finished-files" / (c.models[m] + (c.models[m].rfind("ptm", 0) == 0 ? ".ptm" : ".rti"));
      REQUIRE(fs::is_regular_file(model));
      std::vector<double> means;
      for (const std::string& light : lights) {
        INFO("model " << c.models[m] << ", light " << light);
        const BrowserRun b = loadAt(page, dir, 1400, 900, "#model=" + std::to_string(m) + "&light=" + light);
        INFO(b.log);
        REQUIRE(b.exitCode == 0);
        REQUIRE(bodyAttribute(b.dom, "data-relight") == "rendered");
        CHECK(bodyAttribute(b.dom, "data-errors").empty());
        CHECK(bodyAttribute(b.dom, "data-relight-model") == c.models[m]);
        std::string expectedModels;
        for (const std::string& name : c.models) expectedModels += (expectedModels.empty() ? "" : " ") + name;
        CHECK(bodyAttribute(b.dom, "data-relight-models") == expectedModels);

        const fs::path rendered = dir / "rendered.png";
        const e2e::CommandResult r = e2e::surrogate("render " + e2e::quote(model) + " --light " + light + " -o " +
                                                    e2e::quote(rendered));
        INFO(r.output);
        REQUIRE(r.exitCode == 0);
        const cv::Mat bgr = cv::imread(rendered.string(), cv::IMREAD_COLOR);
        REQUIRE_FALSE(bgr.empty());
        const double pageMean = std::atof(bodyAttribute(b.dom, "data-relight-mean").c_str());
        INFO("mean brightness: page " << pageMean << ", surrogate render " << meanOf(bgr));
        // Rounding of the last bit may differ on a few texels; 0.05 of a level over the picture.
        CHECK(std::abs(pageMean - meanOf(bgr)) < 0.05);
        const std::vector<Probe> probes = parseProbes(bodyAttribute(b.dom, "data-relight-probes"));
        REQUIRE(probes.size() == 9u);
        for (const Probe& p : probes) {
          const cv::Vec3b v = bgr.at<cv::Vec3b>(p.y, p.x);
          for (int ch = 0; ch < 3; ++ch) {
            INFO("texel " << p.x << "," << p.y << " channel " << ch);
            CHECK(std::abs(p.rgb[ch] - int(v[2 - ch])) <= 1);
          }
        }
        means.push_back(pageMean);
      }
      // The relight changes the pixels: the two lights give pictures of different brightness.
      REQUIRE(means.size() == 2u);
      CHECK(std::abs(means[0] - means[1]) > 1.0);
    }
  }
}

TEST_CASE("hostile text in the carrier shows as text in the browser and runs no script") {
  const fs::path work = e2e::freshDir("report-hostile");
  const fs::path capture = e2e::smallCapture(work, 8);
  const std::string hostile = "<img src=x onerror=document.body.dataset.pwned=1><script>document.body.dataset.pwned=2</script>";
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --title " + e2e::quote(hostile) +
                                                " --meta " + e2e::quote("site=" + hostile));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const BrowserRun b = load(capture / "finished-files/report.html", work, "--dump-dom");
  INFO(b.log);
  REQUIRE(b.exitCode == 0);
  CHECK(bodyAttribute(b.dom, "data-pwned").empty());
  CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(consoleLines(b.log).empty());
  CHECK_THAT(b.dom, Catch::Contains("&lt;img src=x onerror="));
}

TEST_CASE("surrogate report reads a capture, a bag directory and a .tar bag in place") {
  const fs::path work = e2e::freshDir("report-bag");
  const fs::path capture = e2e::smallCapture(work, 8);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 0);
  REQUIRE(fs::exists(capture / "finished-files/report.html"));
  // --no-report also removes the previous report, which would no longer match the carrier.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --no-report").exitCode == 0);
  CHECK_FALSE(fs::exists(capture / "finished-files/report.html"));

  // A bag as `surrogate pack` lays it out: the capture's files under data/.
  const fs::path bag = work / "stela-bag";
  fs::create_directories(bag / "data");
  for (const char* dir : {"original-captures", "jpeg-exports", "assembly-files", "finished-files"})
    fs::copy(capture / dir, bag / "data" / dir, fs::copy_options::recursive);
  std::ofstream(bag / "bagit.txt") << "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n";
  REQUIRE(e2e::runShell("tar -cf " + e2e::quote(work / "stela-bag.tar") + " -C " + e2e::quote(work) + " stela-bag").exitCode == 0);

  for (const fs::path& source : {capture, bag, work / "stela-bag.tar"}) {
    INFO(source);
    const fs::path out = work / (source.filename().string() + ".html");
    const e2e::CommandResult r = e2e::surrogate("report " + e2e::quote(source) + " -o " + e2e::quote(out) + " --json");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    CHECK_THAT(r.output, Catch::Contains("\"lights\":8"));
    CHECK_THAT(r.output, Catch::Contains("\"relightable\":true"));
    CHECK_THAT(r.output, Catch::Contains("\"pictures\":7"));
    const std::string html = e2e::bytesOf(out);
    CHECK_THAT(html, Catch::Contains("id=\"hemisphere\""));
  }

  const e2e::CommandResult missing = e2e::surrogate("report " + e2e::quote(work / "nowhere") + " -o x.html");
  CHECK(missing.exitCode == 1);
  CHECK_THAT(missing.output, Catch::Contains("nowhere"));
  const e2e::CommandResult usage = e2e::surrogate("report " + e2e::quote(capture));
  CHECK(usage.exitCode == 2);
}

TEST_CASE("the report of a dome capture plots the lights of its .lp file") {
  const fs::path work = e2e::freshDir("report-dome");
  const fs::path capture = e2e::smallCapture(work, 8);
  // Lights as a dome would give them: an .lp at the top of the capture (estimated here once).
  REQUIRE(e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(work / "dome.lp") + " --quiet").exitCode == 0);
  fs::remove_all(capture / "assembly-files");
  fs::copy_file(work / "dome.lp", capture / "dome.lp");
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --lp dome.lp --json");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK_THAT(run.output, Catch::Contains("LightsFromFile"));
  const std::string html = e2e::bytesOf(capture / "finished-files/report.html");
  CHECK_THAT(html, Catch::Contains("data-lights-expected=\"8\""));
  CHECK_THAT(html, Catch::Contains("No sphere was detected or recorded"));
}
