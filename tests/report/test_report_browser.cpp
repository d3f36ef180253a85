// The report of a generated capture in a real browser (Debian's chromium, headless): it loads
// without console output or script errors, plots one point per light and renders the
// relighting view; at 1400 and 800 px wide the viewer is on the first screen and nothing
// reaches past the viewport's edges (screenshots kept in the build tree,
// tests/report/artefacts/report-1400.png and report-800.png); the page's relighting of a PTM
// and of HSH models gives the pixels of `surrogate render` (src/fit/render.cpp) and changes
// with the light (a model over the size budget, averaged down, against the render of the same
// average); a run at 1200x800 keeps its page within the budget. Also `surrogate report` on a bag
// directory and a .tar.
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
#include "page_bytes.h"
#include "formats/lp.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "report/report.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

using e2e::bodyAttribute;
using e2e::BrowserRun;
using e2e::consoleLines;
using report_test::pictureBytes;

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

// Block averages of `planes` arrays of width x height texels of `values` bytes each, over
// blocks of step x step texels (fewer at the right and bottom edges), rounded half up: what
// report/embed.h says the relighting copy of a model holds, computed here texel by texel.
std::vector<std::uint8_t> blockAverages(const std::vector<std::uint8_t>& in, int width, int height, int values,
                                        int planes, int step) {
  const int w = (width + step - 1) / step, h = (height + step - 1) / step;
  std::vector<std::uint8_t> out;
  for (int c = 0; c < planes; ++c)
    for (int by = 0; by < h; ++by)
      for (int bx = 0; bx < w; ++bx)
        for (int v = 0; v < values; ++v) {
          long sum = 0, n = 0;
          for (int y = by * step; y < std::min(height, (by + 1) * step); ++y)
            for (int x = bx * step; x < std::min(width, (bx + 1) * step); ++x, ++n)
              sum += in[((static_cast<std::size_t>(c) * height + y) * width + x) * values + v];
          out.push_back(static_cast<std::uint8_t>((sum + n / 2) / n));
        }
  return out;
}

// `model` (.ptm or .rti) block-averaged by `step`, written to `out`: the model the page's
// relighting view holds, as a file `surrogate render` reads.
void writeReducedModel(const fs::path& model, int step, const fs::path& out) {
  if (model.extension() == ".ptm") {
    formats::PtmFile ptm = formats::readPtm(model);
    const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
    formats::PtmFile reduced = ptm;
    reduced.width = (ptm.width + step - 1) / step;
    reduced.height = (ptm.height + step - 1) / step;
    reduced.coefficients = blockAverages(ptm.coefficients, ptm.width, ptm.height, 6, lrgb ? 1 : 3, step);
    if (lrgb) reduced.rgb = blockAverages(ptm.rgb, ptm.width, ptm.height, 3, 1, step);
    formats::writePtm(out, reduced);
  } else {
    formats::HshFile hsh = formats::readRti(model);
    formats::HshFile reduced = hsh;
    reduced.width = (hsh.width + step - 1) / step;
    reduced.height = (hsh.height + step - 1) / step;
    reduced.coefficients = blockAverages(hsh.coefficients, hsh.width, hsh.height, 3 * hsh.terms, 1, step);
    formats::writeRti(out, reduced);
  }
}

// Compares the page's first rendering (mean and probes) with a picture `surrogate render`
// wrote of the same model at the same light.
void checkSameRendering(const BrowserRun& b, const fs::path& rendered) {
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
}

}  // namespace

TEST_CASE("the report of a 1200x800 capture is within the size budget and its reduced models relight as surrogate render relights them") {
  // The demo's size (scripts/demo: 24 images of 1200x800; 12 here): its two models kept whole
  // made a page of 27 MB. Each is now averaged by 3 (400x267) to keep within kRelightModelBytes.
  const fs::path work = e2e::freshDir("report-budget");
  const fs::path capture = work / "capture";
  const e2e::CommandResult made = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture) +
                                                " --images 12 --width 1200 --height 800 --seed 1");
  REQUIRE(made.exitCode == 0);
  fs::remove_all(capture / "truth");
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const fs::path page = capture / "finished-files/report.html";
  const std::string html = e2e::bytesOf(page);
  INFO("page " << html.size() << " bytes, of which pictures " << pictureBytes(html));
  CHECK(html.size() - pictureBytes(html) <= report::kReportBudgetBytes);
  CHECK(html.size() <= report::kReportBudgetBytes);  // with the generated capture's pictures too

  // The page's rendering at reduced coordinates against `surrogate render` of the reduced model
  // (averaged by this test): the same pixels, as for a model kept whole.
  const std::vector<std::string> models = {"ptm-lrgb.ptm", "hsh2.rti"};
  const std::string light = "-0.8,-0.2,0.3";
  for (std::size_t m = 0; m < models.size(); ++m) {
    INFO("model " << models[m]);
    const BrowserRun b = loadAt(page, work, 1400, 900, "#model=" + std::to_string(m) + "&light=" + light);
    INFO(b.log);
    REQUIRE(b.exitCode == 0);
    REQUIRE(bodyAttribute(b.dom, "data-relight") == "rendered");
    CHECK(bodyAttribute(b.dom, "data-errors").empty());
    CHECK(intAttribute(b.dom, "data-viewer-width") == 402);  // 400 texels and the border
    const fs::path reduced = work / ("reduced-" + models[m]);
    writeReducedModel(capture / "finished-files" / models[m], 3, reduced);
    const fs::path rendered = work / "rendered.png";
    const e2e::CommandResult r =
        e2e::surrogate("render " + e2e::quote(reduced) + " --light " + light + " -o " + e2e::quote(rendered));
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    checkSameRendering(b, rendered);
  }
}

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
  // It opens at the normalised mean of the carrier's light directions (x right, y up, z to the
  // camera), not at a fixed light that may lie outside the captured range.
  const carrier::Carrier recorded = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  double x = 0, y = 0, z = 0;
  for (const carrier::Result& r : recorded.data)
    for (const carrier::DataItem* l : r.itemsOf("light")) {
      const double norm = std::hypot(l->number("x"), l->number("y"), l->number("z"));
      x += l->number("x") / norm;
      y += l->number("y") / norm;
      z += l->number("z") / norm;
    }
  const double pi = 3.14159265358979323846, n = std::hypot(x, y, z);
  const std::string opened = bodyAttribute(b.dom, "data-relight-light");
  INFO("opened at " << opened << "; mean direction " << x / n << "," << y / n << "," << z / n);
  CHECK(std::atof(opened.c_str()) == Approx(std::atan2(y, x) * 180 / pi).margin(0.051));
  CHECK(std::atof(opened.substr(opened.find(',') + 1).c_str()) == Approx(std::asin(z / n) * 180 / pi).margin(0.051));

  fs::create_directories(REPORT_ARTEFACT_DIR);  // run alone (ctest), no other test made it
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
    std::vector<int> steps;           // each model's block side in the page
  };
  // The default run fits a PTM and an HSH; an HSH-only run must be relightable too. At 400x300
  // the PTM (9 bytes a texel, 1.08 MB) and the HSH of order 2 (12, 1.44 MB) are kept whole; the
  // HSH of order 3 (27, 3.24 MB) is over kRelightModelBytes and averaged by 2 (0.81 MB): the
  // page is then compared with the render of the model averaged by this test.
  const std::vector<Case> cases = {{"", {"ptm-lrgb", "hsh2"}, {1, 1}}, {"--basis hsh3", {"hsh3"}, {2}}};
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

        fs::path shown = model;
        if (c.steps[m] > 1) {
          shown = dir / ("reduced-" + model.filename().string());
          writeReducedModel(model, c.steps[m], shown);
        }
        const fs::path rendered = dir / "rendered.png";
        const e2e::CommandResult r = e2e::surrogate("render " + e2e::quote(shown) + " --light " + light + " -o " +
                                                    e2e::quote(rendered));
        INFO(r.output);
        REQUIRE(r.exitCode == 0);
        checkSameRendering(b, rendered);
        means.push_back(std::atof(bodyAttribute(b.dom, "data-relight-mean").c_str()));
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
