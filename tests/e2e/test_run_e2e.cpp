#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"
#include "report/report.h"

namespace fs = std::filesystem;
using namespace surrogate;

TEST_CASE("surrogate run records every file with its hash, metadata and decode parameters") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("run"));
  const auto before = e2e::snapshot(capture);

  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --title Test --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);

  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");  // validates
  CHECK(c.header.title == "Test");
  int originals = 0, exports = 0;
  for (const carrier::FileRecord& f : c.files) {
    if (f.role != "original" && f.role != "export") continue;
    originals += f.role == "original";
    exports += f.role == "export";
    CHECK(f.sha256 == digestFile(capture / f.path).sha256);
    CHECK(f.size == fs::file_size(capture / f.path));
    REQUIRE(f.imageSize.has_value());
    CHECK(f.imageSize->first == 400);
    CHECK_FALSE(f.pairedWith.empty());
    bool hasMake = false;
    for (const auto& [k, v] : f.camera) hasMake = hasMake || (k == "make" && v == "Surrogate");
    if (f.role == "original") CHECK(hasMake);
    if (f.role == "export") CHECK(f.unrecordedProcessing);
  }
  CHECK(originals == 8);
  CHECK(exports == 8);

  const carrier::Step& decode = c.process.at(1);
  CHECK(decode.component == "ImageDecode");
  CHECK(decode.hasParam("demosaic"));
  CHECK(decode.hasParam("whiteBalance"));
  const carrier::Result* decoded = c.findResult(decode.id);
  REQUIRE(decoded != nullptr);
  CHECK(decoded->status == "completed");
  const auto items = decoded->itemsOf("decoded");
  REQUIRE(items.size() == 8);
  CHECK_THAT(*items[0]->get("decoder"), Catch::Contains("LibRaw"));
  CHECK(*items[0]->get("transfer") == "linear");

  // Nothing in the capture's own folders changed; Surrogate only added its two folders and
  // its working area (the lock, .surrogate/).
  auto after = e2e::snapshot(capture);
  for (const auto& [path, hash] : before) {
    INFO(path);
    REQUIRE(after.count(path) == 1);
    CHECK(after[path] == hash);
  }
  for (const auto& [path, hash] : after) {
    if (before.count(path)) continue;
    const bool ours = path.rfind("assembly-files/", 0) == 0 || path.rfind("finished-files/", 0) == 0 ||
                      path == ".surrogate/lock";
    INFO(path);
    CHECK(ours);
  }

  // The run's report shows its pictures from the pixels the steps held; `surrogate report`
  // decodes them from the files. The two pages differ only in the time they were made.
  const fs::path again = e2e::freshDir("run-report") / "report.html";
  const e2e::CommandResult rep = e2e::surrogate("report " + e2e::quote(capture) + " -o " + e2e::quote(again));
  INFO(rep.output);
  REQUIRE(rep.exitCode == 0);
  const auto withoutTime = [](const std::string& page) {
    return std::regex_replace(page, std::regex("report made [^<]* by Surrogate"), "report made (time) by Surrogate");
  };
  const std::string fromRun = e2e::bytesOf(capture / "finished-files/report.html");
  CHECK(fromRun.find("src=\"data:image/jpeg;base64,") != std::string::npos);
  CHECK(withoutTime(fromRun) == withoutTime(e2e::bytesOf(again)));
}

TEST_CASE("with four models the run's report shares the page's bytes among them as surrogate report does") {
  // At 400x300 each model takes a quarter of the models' bytes (0.75 MB): the PTMs (9 and 18
  // bytes a texel, 1.08 and 2.16 MB whole) and the HSHs (12 and 27) are averaged down. The
  // run makes its copies as the fits write the models; a run that keeps the recorded four
  // (no --basis) must share alike.
  const fs::path capture = e2e::smallCapture(e2e::freshDir("four-models"), 12);
  const auto withoutTime = [](const std::string& page) {
    return std::regex_replace(page, std::regex("report made [^<]* by Surrogate"), "report made (time) by Surrogate");
  };
  for (const std::string& options : {std::string("--basis ptm-lrgb --basis ptm-rgb --basis hsh2 --basis hsh3"), std::string("--threads 1")}) {
    INFO(options);
    const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet " + options);
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    const fs::path again = e2e::freshDir("four-models-report") / "report.html";
    REQUIRE(e2e::surrogate("report " + e2e::quote(capture) + " -o " + e2e::quote(again)).exitCode == 0);
    const std::string fromRun = e2e::bytesOf(capture / "finished-files/report.html");
    CHECK(withoutTime(fromRun) == withoutTime(e2e::bytesOf(again)));
    CHECK(fromRun.size() <= report::kReportBudgetBytes);
    for (const char* model : {"\"basis\":\"ptm-lrgb\"", "\"basis\":\"ptm-rgb\"", "\"basis\":\"hsh2\"", "\"basis\":\"hsh3\""})
      CHECK(fromRun.find(model) != std::string::npos);
  }
}

TEST_CASE("decoding is deterministic: two runs decode identical pixels") {
  const fs::path a = e2e::smallCapture(e2e::freshDir("det-a"));
  const fs::path b = e2e::smallCapture(e2e::freshDir("det-b"));
  REQUIRE(e2e::surrogate("run " + e2e::quote(a) + " --quiet --threads 1").exitCode == 0);
  REQUIRE(e2e::surrogate("run " + e2e::quote(b) + " --quiet --threads 2").exitCode == 0);
  const carrier::Carrier ca = carrier::loadCarrier(a / "assembly-files/carrier.xml");
  const carrier::Carrier cb = carrier::loadCarrier(b / "assembly-files/carrier.xml");
  const auto da = ca.findResult("s2")->itemsOf("decoded");
  const auto db = cb.findResult("s2")->itemsOf("decoded");
  REQUIRE(da.size() == db.size());
  for (std::size_t i = 0; i < da.size(); ++i) CHECK(*da[i]->get("pixelSha256") == *db[i]->get("pixelSha256"));
}

TEST_CASE("an excluded image needs a reason and is recorded as a human intervention") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("exclude"));
  const e2e::CommandResult missing = e2e::surrogate("run " + e2e::quote(capture) + " --exclude IMG_0003");
  CHECK(missing.exitCode == 2);
  CHECK_THAT(missing.output, Catch::Contains("--reason"));

  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) +
                                              " --quiet --operator Tester --exclude IMG_0003 "
                                              "--reason 'the flash did not fire'");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  const auto interventions = c.process.at(0).interventionsOfKind("exclude-image");
  REQUIRE(interventions.size() == 1);
  CHECK(interventions[0]->reason == "the flash did not fire");
  CHECK(interventions[0]->who == "Tester");
  CHECK(c.findResult("s1")->itemsOf("input").size() == 7);
  bool logged = false;
  for (const carrier::LogEntry& e : c.log)
    logged = logged || (e.level == "intervention" && e.who == "Tester" &&
                        e.text.find("the flash did not fire") != std::string::npos);
  CHECK(logged);

  const e2e::CommandResult unknown = e2e::surrogate("run " + e2e::quote(capture) +
                                                    " --quiet --exclude IMG_9999 --reason typo");
  CHECK(unknown.exitCode == 2);
  CHECK_THAT(unknown.output, Catch::Contains("IMG_9999"));
}

TEST_CASE("user metadata and creators go into the carrier's header") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("meta"));
  const e2e::CommandResult r = e2e::surrogate(
      "run " + e2e::quote(capture) +
      " --quiet --creator 'Ana Silva:photographer' --meta Source-Organization=Museum --meta 'Object=Stela 12'");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  REQUIRE(c.header.creators.size() == 1);
  CHECK(c.header.creators[0].name == "Ana Silva");
  CHECK(c.header.creators[0].role == "photographer");
  REQUIRE(c.header.meta.size() == 2);
  CHECK(c.header.meta[1].second == "Stela 12");
  bool hasLibRaw = false;
  for (const carrier::Software& s : c.header.software) hasLibRaw = hasLibRaw || s.name == "LibRaw";
  CHECK(hasLibRaw);
}

TEST_CASE("surrogate info describes a capture and its carrier") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("info"));
  const e2e::CommandResult before = e2e::surrogate("info " + e2e::quote(capture));
  INFO(before.output);
  CHECK(before.exitCode == 0);
  CHECK_THAT(before.output, Catch::Contains("8 originals"));
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 0);
  const e2e::CommandResult json = e2e::surrogate("info --json " + e2e::quote(capture / "assembly-files/carrier.xml"));
  CHECK(json.exitCode == 0);
  CHECK_THAT(json.output, Catch::Contains("\"component\":\"ImageDecode\""));
}

TEST_CASE("XMP sidecars are kept verbatim and a damaged one is a warning, not a failed run") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("sidecar"));
  const std::string packet =
      "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"><rdf:RDF "
      "xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"><rdf:Description "
      "xmlns:crs=\"http://ns.adobe.com/camera-raw-settings/1.0/\" crs:Exposure2012=\"+0.35\"/>"
      "</rdf:RDF></x:xmpmeta>";
  { std::ofstream(capture / "original-captures/IMG_0001.xmp", std::ios::binary) << packet; }
  { std::ofstream(capture / "original-captures/IMG_0002.xmp", std::ios::binary) << "<x:xmpmeta"; }

  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  const carrier::FileRecord* good = c.findFileByPath("original-captures/IMG_0001.xmp");
  const carrier::FileRecord* bad = c.findFileByPath("original-captures/IMG_0002.xmp");
  REQUIRE(good != nullptr);
  REQUIRE(bad != nullptr);
  CHECK(good->role == "sidecar");
  CHECK_THAT(good->xmp, Catch::Contains("crs:Exposure2012=\"+0.35\""));
  CHECK(bad->sha256 == digestFile(capture / bad->path).sha256);
  bool warned = false;
  for (const carrier::LogEntry& e : c.log)
    warned = warned || (e.level == "warning" && e.text.find("IMG_0002.xmp") != std::string::npos);
  CHECK(warned);
}
