// A change of descriptive metadata alone (title, creator, rights, licence, --meta) runs no
// processing step again (run/descriptive_run.h): a run in the history that changes only the
// carrier's header and the report. Anything that may change a result still processes as before.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <thread>

#include "bag_check.h"
#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

carrier::Carrier carrierOf(const fs::path& capture) {
  return carrier::loadCarrier(capture / "assembly-files/carrier.xml");
}

// One section of the carrier's XML text, from its start tag to its end tag, as written.
std::string section(const std::string& xml, const std::string& name) {
  const auto begin = xml.find("<" + name + ">") != std::string::npos ? xml.find("<" + name + ">") : xml.find("<" + name + " ");
  const auto end = xml.find("</" + name + ">");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  return xml.substr(begin, end - begin);
}

// Every result file (the output folders but the carrier and the report): its bytes and its
// modification time, which a rewrite with the same bytes would change.
struct ResultFile {
  std::string bytes;
  fs::file_time_type mtime;
  bool operator==(const ResultFile& o) const { return bytes == o.bytes && mtime == o.mtime; }
};
std::map<std::string, ResultFile> results(const fs::path& capture) {
  std::map<std::string, ResultFile> out;
  for (const char* dir : {"assembly-files", "finished-files"})
    for (const auto& e : fs::recursive_directory_iterator(capture / dir)) {
      const std::string rel = fs::relative(e.path(), capture).generic_string();
      if (e.is_regular_file() && rel != "assembly-files/carrier.xml" && rel != "finished-files/report.html")
        out[rel] = {e2e::bytesOf(e.path()), fs::last_write_time(e.path())};
    }
  return out;
}

std::string runIn(const fs::path& capture, const std::string& options) {
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " " + options + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  return r.output;
}

void flipByte(const fs::path& file, std::streamoff at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  const char c = static_cast<char>(f.get());
  f.seekp(at);
  f.put(static_cast<char>(c ^ 0x5a));
}

const char* kNoStepRan = "descriptive metadata only: no processing step ran again";

}  // namespace

TEST_CASE("a title, creator, rights, licence or --meta change alone runs no step again", "[e2e][workflow][descriptive]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("descriptive"), 8);
  runIn(capture, "--title \"Stela 12\"");
  const std::string firstXml = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  // The first run's change list states the title it was given (issue 56), as later runs do.
  {
    const carrier::Carrier first = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
    REQUIRE(first.header.runs.size() == 1);
    CHECK(first.header.runs[0].notes == std::vector<std::string>{"title \"Stela 12\""});
  }
  const auto firstResults = results(capture);
  REQUIRE(firstResults.count("finished-files/ptm-lrgb.ptm"));

  struct Change {
    std::string options, note;
    std::function<bool(const carrier::Header&)> recorded;
  };
  const std::vector<Change> changes = {
      {"--title \"Stela 12, north face\"", "title \"Stela 12\" -> \"Stela 12, north face\"",
       [](const carrier::Header& h) { return h.title == "Stela 12, north face"; }},
      {"--creator \"Ana Silva:photographer\"", "added creator Ana Silva (photographer)",
       [](const carrier::Header& h) { return h.creators.size() == 1 && h.creators[0].name == "Ana Silva" && h.creators[0].role == "photographer"; }},
      {"--rights \"Museum staff and researchers may reuse\"", "rights \"Museum staff and researchers may reuse\"",
       [](const carrier::Header& h) { return h.rights == "Museum staff and researchers may reuse"; }},
      {"--license https://creativecommons.org/licenses/by/4.0/", "license https://creativecommons.org/licenses/by/4.0/",
       [](const carrier::Header& h) { return h.license == "https://creativecommons.org/licenses/by/4.0/"; }},
      {"--meta accession=2026/17", "metadata accession = \"2026/17\"",
       [](const carrier::Header& h) { return h.meta.size() == 1 && h.meta[0].first == "accession" && h.meta[0].second == "2026/17"; }},
  };
  std::size_t runs = carrierOf(capture).header.runs.size();
  for (const Change& change : changes) {
    INFO(change.options);
    const std::string before = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    const carrier::Carrier old = carrierOf(capture);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a step run again would get later times
    const auto t0 = std::chrono::steady_clock::now();
    const std::string said = runIn(capture, change.options);
    CHECK_THAT(said, Catch::Contains("Recorded the new description of") && !Catch::Contains("Processed"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    UNSCOPED_INFO("the run took " << seconds << " s");
    const std::string after = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    // Files, process, data (every result's started and ended time) and log byte for byte.
    for (const char* name : {"files", "process", "data", "log"}) CHECK(section(after, name) == section(before, name));
    CHECK(section(after, "files") == section(firstXml, "files"));
    CHECK(section(after, "data") == section(firstXml, "data"));
    CHECK(results(capture) == firstResults);  // no result file rewritten, not even with the same bytes
    const carrier::Carrier c = carrierOf(capture);
    CHECK(change.recorded(c.header));
    CHECK(c.header.created == old.header.created);
    REQUIRE(c.header.runs.size() == ++runs);
    const carrier::RunRecord& r = c.header.runs.back();
    CHECK(r.outcome == "completed");
    CHECK(r.id == "r" + std::to_string(runs));
    CHECK(r.command == "run");
    CHECK_FALSE(r.who.empty());
    CHECK_FALSE(r.started.empty());
    CHECK_FALSE(r.ended.empty());
    REQUIRE(r.notes.size() == 2);
    CHECK(r.notes[0] == change.note);
    CHECK_THAT(r.notes[1], Catch::StartsWith(kNoStepRan));
    // The earlier runs are as they were.
    for (std::size_t n = 0; n + 1 < c.header.runs.size(); ++n) CHECK(c.header.runs[n].notes == old.header.runs[n].notes);
  }
  // The report is made again from the new carrier.
  const std::string report = e2e::bytesOf(capture / "finished-files/report.html");
  CHECK_THAT(report, Catch::Contains("<title>Stela 12, north face"));
  CHECK_THAT(report, Catch::Contains("Ana Silva"));

  // Packed afterwards, the package re-executes sound, and its derived metadata carry the new
  // header (re-derived by verify from the carrier it holds).
  const fs::path bag = capture.parent_path() / "bag.zip";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK(results(capture) == firstResults);  // pack found the record complete: nothing processed
  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 2");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
  CHECK_THAT(verify.output, Catch::Contains("SOUND"));
  CHECK(std::regex_search(verify.output, std::regex("ok +reexecute\\.s[0-9]+\\.RtiFit")));
  const bagcheck::BagFiles files = bagcheck::readBag(bag);
  CHECK_THAT(files.files.at("metadata/mets.xml"), Catch::Contains("Stela 12, north face"));
  CHECK_THAT(files.files.at("metadata/crm.rdf"), Catch::Contains("Stela 12, north face"));
  CHECK_THAT(files.files.at("metadata/mets.xml"), Catch::Contains("Museum staff and researchers may reuse"));
}

TEST_CASE("a processing option, a changed original or a changed result still processes as before", "[e2e][workflow][descriptive]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("descriptive-not"), 8);
  runIn(capture, "");
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));

  SECTION("a processing option with the title: every step runs again") {
    const std::string before = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    runIn(capture, "--title \"Other\" --basis ptm-rgb");
    const carrier::Carrier c = carrierOf(capture);
    CHECK(c.header.title == "Other");
    CHECK(section(e2e::bytesOf(capture / "assembly-files/carrier.xml"), "data") != section(before, "data"));
    const carrier::Carrier old = carrier::parseCarrier(before, "before");
    for (const carrier::Result& r : c.data) CHECK(r.started > old.data.back().ended);
    CHECK(c.findFileByPath("finished-files/ptm-rgb.ptm") != nullptr);
    for (const std::string& n : c.header.runs.back().notes) CHECK(n.find(kNoStepRan) == std::string::npos);
  }
  SECTION("nothing changed at all: the run processes again, as it always has") {
    const carrier::Carrier old = carrierOf(capture);
    runIn(capture, "");
    const carrier::Carrier c = carrierOf(capture);
    REQUIRE(c.data.size() == old.data.size());
    CHECK(c.data.front().started > old.data.back().ended);
  }
  SECTION("a changed original with a title change is a fixity failure, as without it") {
    const std::string before = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    flipByte(capture / "original-captures/IMG_0003.dng", 5000);
    const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --title \"Changed\" --quiet");
    CHECK(r.exitCode == 3);
    CHECK_THAT(r.output, Catch::Contains("original-captures/IMG_0003.dng"));
    const carrier::Carrier c = carrierOf(capture);
    CHECK(c.header.title != "Changed");
    CHECK(c.header.runs.back().outcome == "failed");
    CHECK(section(e2e::bytesOf(capture / "assembly-files/carrier.xml"), "files") == section(before, "files"));
  }
  SECTION("a result changed on disk: the run makes the results again") {
    std::ofstream(capture / "finished-files/normals.png", std::ios::app) << "x";
    const carrier::Carrier old = carrierOf(capture);
    runIn(capture, "--title \"Changed\"");
    const carrier::Carrier c = carrierOf(capture);
    CHECK(c.header.title == "Changed");
    CHECK(c.data.front().started > old.data.back().ended);
    CHECK(c.findFileByPath("finished-files/normals.png")->size == old.findFileByPath("finished-files/normals.png")->size);
  }
  SECTION("a capture with a web copy: its pages show the title, so the run processes again") {
    runIn(capture, "--publish");
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    const carrier::Carrier old = carrierOf(capture);
    const std::string said = runIn(capture, "--title \"Stela 12, north face\"");
    CHECK_THAT(said, Catch::Contains("Processed"));
    const carrier::Carrier c = carrierOf(capture);
    CHECK(c.header.title == "Stela 12, north face");
    CHECK(c.data.back().started > old.data.back().ended);
    for (const std::string& n : c.header.runs.back().notes) CHECK(n.find(kNoStepRan) == std::string::npos);
    CHECK_THAT(e2e::bytesOf(capture / "finished-files/web/index.html"), Catch::Contains("Stela 12, north face"));
    // The package re-executes: the pages verify remakes from the header are the recorded ones.
    const fs::path package = capture.parent_path() / "web.zip";
    const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet");
    INFO(pack.output);
    REQUIRE(pack.exitCode == 0);
    const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(package) + " --reexecute --threads 2");
    INFO(verify.output);
    CHECK(verify.exitCode == 0);
  }
  SECTION("a photograph added: the run takes it in") {
    fs::copy_file(capture / "original-captures/IMG_0003.dng", capture / "original-captures/IMG_0009.dng");
    fs::copy_file(capture / "jpeg-exports/IMG_0003.jpg", capture / "jpeg-exports/IMG_0009.jpg");
    runIn(capture, "--title \"Changed\"");
    CHECK(carrierOf(capture).findFileByPath("original-captures/IMG_0009.dng") != nullptr);
  }
}

TEST_CASE("a descriptive run killed at any point leaves the old carrier or the new one", "[e2e][workflow][descriptive]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("descriptive-kill"), 8);
  runIn(capture, "--title \"T0\"");
  const auto firstResults = results(capture);

  // Dying inside the commit, the staged carrier not yet in place: the old carrier is whole, and
  // the next command finishes the commit.
  const std::string old = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  const e2e::CommandResult crash = e2e::runShell("SURROGATE_FAULT_INJECTION=commit " + std::string(SURROGATE_EXE) +
                                                 " run " + e2e::quote(capture) + " --title \"T1\" --quiet");
  CHECK(crash.exitCode == 137);
  CHECK(e2e::bytesOf(capture / "assembly-files/carrier.xml") == old);
  CHECK(results(capture) == firstResults);
  runIn(capture, "--title \"T2\"");
  carrier::Carrier c = carrierOf(capture);
  CHECK(c.header.title == "T2");
  REQUIRE(c.header.runs.size() == 3);
  CHECK(c.header.runs[1].notes.front() == "title \"T0\" -> \"T1\"");
  CHECK(c.header.runs[2].notes.front() == "title \"T1\" -> \"T2\"");
  CHECK(results(capture) == firstResults);

  // Killed (SIGKILL) at several points: the carrier is the old one or the new one, whole.
  int n = 3;
  for (int us : {0, 2000, 5000, 10000, 20000, 40000, 80000}) {
    const std::string title = "T" + std::to_string(n);
    const std::string before = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      execl(SURROGATE_EXE, SURROGATE_EXE, "run", capture.c_str(), "--title", title.c_str(), "--quiet",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(us));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    INFO("killed after " << us << " us");
    const std::string now = e2e::bytesOf(capture / "assembly-files/carrier.xml");
    if (now != before) CHECK(carrierOf(capture).header.title == title);
    CHECK(results(capture) == firstResults);
    // The next command finds the capture whole (finishing a commit the kill cut short).
    runIn(capture, "--title \"T" + std::to_string(n + 1) + "\"");
    CHECK(carrierOf(capture).header.title == "T" + std::to_string(n + 1));
    CHECK(results(capture) == firstResults);
    n += 2;
  }
}
