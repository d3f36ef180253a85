// The report of a generated capture in a real browser (Debian's chromium, headless): it loads
// without console output or script errors, plots one point per light and renders the
// relighting view; a screenshot is kept as a test artefact in the build tree
// (tests/report/artefacts/). Also `surrogate report` on a bag directory and a .tar.
//
// Without chromium on PATH (or in $SURROGATE_CHROMIUM), the browser tests exit with code 77,
// which ctest reports as skipped. scripts/install-deps installs it, so CI runs them.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "carrier/carrier.h"
#include "e2e_support.h"
#include "formats/lp.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

std::string chromium() {
  std::vector<std::string> candidates = {"chromium", "chromium-browser"};
  if (const char* env = std::getenv("SURROGATE_CHROMIUM"); env && *env) candidates = {env};
  for (const std::string& name : candidates) {
    if (e2e::runShell("command -v " + e2e::quote(name) + " >/dev/null").exitCode == 0) return name;
  }
  std::cerr << "SKIPPED: chromium is not installed (apt-get install chromium, or run "
               "scripts/install-deps); the report's browser test needs it\n";
  std::exit(77);
}

struct BrowserRun {
  int exitCode = -1;
  std::string dom;     // stdout of --dump-dom
  std::string stderr_; // chromium's log, with the page's console messages
};

// Loads `page` in headless chromium with its own profile folder, after the page's scripts ran.
BrowserRun load(const fs::path& page, const fs::path& work, const std::string& extra) {
  const fs::path profile = work / "chromium-profile";
  const fs::path out = work / "dom.html", err = work / "chromium.log";
  const std::string command = "timeout 120 " + chromium() +
                              " --headless=new --no-sandbox --disable-gpu --no-first-run "
                              "--enable-logging=stderr --v=0 --user-data-dir=" + e2e::quote(profile) + " " +
                              extra + " " + e2e::quote("file://" + fs::absolute(page).string()) + " > " +
                              e2e::quote(out) + " 2> " + e2e::quote(err);
  BrowserRun r;
  r.exitCode = e2e::runShell(command).exitCode;
  r.dom = e2e::bytesOf(out);
  r.stderr_ = e2e::bytesOf(err);
  return r;
}

std::string bodyAttribute(const std::string& dom, const std::string& name) {
  std::smatch body;
  if (!std::regex_search(dom, body, std::regex("<body[^>]*>"))) return "";
  std::smatch m;
  const std::string tag = body.str();
  if (!std::regex_search(tag, m, std::regex(name + "=\"([^\"]*)\""))) return "";
  return m[1].str();
}

// Lines of chromium's log that are the page's console messages (errors, CSP violations...).
std::vector<std::string> consoleLines(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.find(":CONSOLE") != std::string::npos) out.push_back(line);
  return out;
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
  INFO(b.stderr_);
  REQUIRE(b.exitCode == 0);
  CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(bodyAttribute(b.dom, "data-errors").empty());
  CHECK(consoleLines(b.stderr_).empty());
  CHECK(bodyAttribute(b.dom, "data-lights-plotted") == std::to_string(lights));
  CHECK(bodyAttribute(b.dom, "data-lights-expected") == std::to_string(lights));
  CHECK(bodyAttribute(b.dom, "data-relight") == "rendered");
  // The relit object is neither black nor blown out (the generated relief is mid-grey-brown).
  const double mean = std::atof(bodyAttribute(b.dom, "data-relight-mean").c_str());
  INFO("mean brightness of the relit view: " << mean);
  CHECK(mean > 30);
  CHECK(mean < 230);

  // A screenshot for people to look at (kept in the build tree).
  const fs::path artefacts = REPORT_ARTEFACT_DIR;
  fs::create_directories(artefacts);
  const fs::path shot = artefacts / "report.png";
  fs::remove(shot);
  const BrowserRun s = load(page, work, "--hide-scrollbars --window-size=1280,2400 --screenshot=" + e2e::quote(shot));
  INFO(s.stderr_);
  CHECK(s.exitCode == 0);
  REQUIRE(fs::is_regular_file(shot));
  CHECK(fs::file_size(shot) > 20000);
  CHECK(e2e::bytesOf(shot).compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  fs::copy_file(page, artefacts / "report.html", fs::copy_options::overwrite_existing);
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
  INFO(b.stderr_);
  REQUIRE(b.exitCode == 0);
  CHECK(bodyAttribute(b.dom, "data-pwned").empty());
  CHECK(bodyAttribute(b.dom, "data-ready") == "yes");
  CHECK(consoleLines(b.stderr_).empty());
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
