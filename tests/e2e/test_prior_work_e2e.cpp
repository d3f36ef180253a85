// Prior work (issue 17, item 1): a capture laid out as RTIBuilder leaves it, with their .lp
// (Windows paths, CRLF), their .ptm and their log XML in assembly-files/ and finished-files/.
// Surrogate records those files (role prior, kind, what they say of their making), never
// changes them, packs them in their own METS group and verifies their fixity; a changed one is
// a fixity failure, and one where a run would write its own result stops the run first.
// The prior files are written here from the layouts of docs/formats.md, and their hashes are
// checked with sha256sum, independently of Surrogate's digests.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <vector>

#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr const char* kPriorLp = "assembly-files/stela12.lp";
constexpr const char* kPriorLog = "assembly-files/stela12_log.xml";
constexpr const char* kPriorPtm = "finished-files/stela12.ptm";

void writeBytes(const fs::path& file, const std::string& bytes) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << bytes;
}

// A PTM_1.2 LRGB file as docs/formats.md ("Header", "Payload and row order") lays it out: six
// header lines ended by LF, then 6 coefficient bytes per texel, then 3 colour bytes per texel.
std::string ptmLrgb(int width, int height) {
  std::string out = "PTM_1.2\nPTM_FORMAT_LRGB\n" + std::to_string(width) + "\n" + std::to_string(height) +
                    "\n0.25 0.25 0.125 0.5 0.5 1\n200 200 128 128 128 0\n";
  const int texels = width * height;
  for (int i = 0; i < texels * 6; ++i) out += static_cast<char>((i * 37) % 256);
  for (int i = 0; i < texels * 3; ++i) out += static_cast<char>((i * 11) % 256);
  return out;
}

// An .lp as RTIBuilder writes it on Windows: backslash paths, CRLF line ends, a blank line.
std::string rtibuilderLp(int images) {
  std::string out = std::to_string(images) + "\r\n";
  for (int n = 1; n <= images; ++n)
    out += "jpeg-exports\\IMG_000" + std::to_string(n) + ".jpg 0.5 0.5 0.7071067811865476\r\n";
  return out + "\r\n";
}

const char* kLogXml =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\r\n"
    "<RTIBuilderLog version=\"2.0.2\" software=\"RTIBuilder\">\r\n"
    "  <step name=\"PTMFitter\" basis=\"LRGB\"/>\r\n"
    "</RTIBuilderLog>\r\n";

// A capture with the three prior files and a .DS_Store in finished-files/.
fs::path rtibuilderCapture(const std::string& name) {
  const fs::path capture = e2e::smallCapture(e2e::freshDir(name), 8);
  writeBytes(capture / kPriorLp, rtibuilderLp(8));
  writeBytes(capture / kPriorLog, kLogXml);
  writeBytes(capture / kPriorPtm, ptmLrgb(4, 3));
  writeBytes(capture / "finished-files/.DS_Store", "finder");
  return capture;
}

carrier::Carrier carrierOf(const fs::path& capture) {
  return carrier::loadCarrier(capture / "assembly-files/carrier.xml");
}

e2e::CommandResult runIn(const fs::path& capture) {
  return e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
}

// SHA-256 by sha256sum(1), not by Surrogate's code.
std::string sha256sum(const fs::path& file) {
  const e2e::CommandResult r = e2e::runShell("sha256sum " + e2e::quote(file));
  REQUIRE(r.exitCode == 0);
  return r.output.substr(0, 64);
}

struct PriorRecord {
  std::string path, sha256, kind, madeBy;
  std::uint64_t size = 0;
  bool operator==(const PriorRecord& o) const {
    return path == o.path && sha256 == o.sha256 && kind == o.kind && madeBy == o.madeBy && size == o.size;
  }
};

std::vector<PriorRecord> priorRecords(const carrier::Carrier& c) {
  std::vector<PriorRecord> out;
  for (const carrier::FileRecord& f : c.files)
    if (f.role == "prior") out.push_back({f.path, f.sha256, f.priorKind, f.madeBy, f.size});
  return out;
}

// The text of METS's fileGrp USE="prior-work" (empty when there is none).
std::string priorGroup(const std::string& mets) {
  const auto start = mets.find("<mets:fileGrp ID=\"fileGrp-prior-work\" USE=\"prior-work\">");
  if (start == std::string::npos) return "";
  return mets.substr(start, mets.find("</mets:fileGrp>", start) - start);
}

}  // namespace

TEST_CASE("prior work is recorded with its kind and maker and kept byte for byte across runs", "[e2e][prior]") {
  const fs::path capture = rtibuilderCapture("prior-record");
  const std::string lp = e2e::bytesOf(capture / kPriorLp), log = e2e::bytesOf(capture / kPriorLog),
                    ptm = e2e::bytesOf(capture / kPriorPtm);
  const e2e::CommandResult first = runIn(capture);
  INFO(first.output);
  REQUIRE(first.exitCode == 0);

  const carrier::Carrier c = carrierOf(capture);
  const std::vector<PriorRecord> prior = priorRecords(c);
  REQUIRE(prior.size() == 3);
  const std::map<std::string, std::pair<std::string, std::string>> expected = {
      {kPriorLp, {"lp", ""}},
      {kPriorLog, {"log", "RTIBuilderLog version=\"2.0.2\" software=\"RTIBuilder\""}},
      {kPriorPtm, {"rti", "PTM_1.2 PTM_FORMAT_LRGB"}}};
  for (const PriorRecord& r : prior) {
    INFO(r.path);
    REQUIRE(expected.count(r.path) == 1);
    CHECK(r.kind == expected.at(r.path).first);
    CHECK(r.madeBy == expected.at(r.path).second);
    CHECK(r.sha256 == sha256sum(capture / r.path));
    CHECK(r.size == fs::file_size(capture / r.path));
    CHECK(carrier::isEvidenceRole("prior"));
  }
  CHECK(c.findFileByPath("finished-files/.DS_Store") == nullptr);
  // Surrogate's own results are still its own.
  REQUIRE(c.findFileByPath("finished-files/ptm-lrgb.ptm") != nullptr);
  CHECK(c.findFileByPath("finished-files/ptm-lrgb.ptm")->role == "result");
  // Nothing of the prior work changed.
  CHECK(e2e::bytesOf(capture / kPriorLp) == lp);
  CHECK(e2e::bytesOf(capture / kPriorLog) == log);
  CHECK(e2e::bytesOf(capture / kPriorPtm) == ptm);

  const e2e::CommandResult second = runIn(capture);
  INFO(second.output);
  REQUIRE(second.exitCode == 0);
  CHECK(priorRecords(carrierOf(capture)) == prior);
  CHECK(e2e::bytesOf(capture / kPriorPtm) == ptm);
}

TEST_CASE("pack bags prior work in its own METS group and verify checks its fixity", "[e2e][prior]") {
  // Never processed: pack runs the pipeline first, which records the prior work.
  const fs::path capture = rtibuilderCapture("prior-pack");
  const fs::path bag = capture.parent_path() / "bag";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  for (const char* path : {kPriorLp, kPriorLog, kPriorPtm})
    CHECK(e2e::bytesOf(bag / "data" / path) == e2e::bytesOf(capture / path));
  CHECK_FALSE(fs::exists(bag / "data/finished-files/.DS_Store"));
  const std::string group = priorGroup(e2e::bytesOf(bag / "metadata/mets.xml"));
  for (const char* path : {kPriorLp, kPriorLog, kPriorPtm})
    CHECK_THAT(group, Catch::Contains(std::string("xlink:href=\"data/") + path + "\""));
  CHECK_THAT(group, !Catch::Contains("ptm-lrgb.ptm"));  // Surrogate's result is not prior work
  const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(bag));
  CHECK_THAT(info.output, Catch::Matches("[\\s\\S]*prior work +3 files[\\s\\S]*"));

  const e2e::CommandResult sound = e2e::surrogate("verify " + e2e::quote(bag) + " --quiet");
  INFO(sound.output);
  CHECK(sound.exitCode == 0);
  const e2e::CommandResult reexecuted = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --quiet");
  INFO(reexecuted.output);
  CHECK(reexecuted.exitCode == 0);

  std::ofstream(bag / "data" / kPriorPtm, std::ios::binary | std::ios::app) << "x";
  const e2e::CommandResult altered = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(altered.output);
  CHECK(altered.exitCode == 3);
  CHECK_THAT(altered.output, Catch::Contains(std::string("data/") + kPriorPtm));
}

// The carrier describes each file (what prior work says of its making, formats, camera
// metadata): a description rewritten in the capture's carrier and packed again is consistent
// everywhere in the bag, so only re-running the steps can tell, and it must.
TEST_CASE("a file description rewritten in the carrier and packed again does not re-execute as sound", "[e2e][prior]") {
  const fs::path capture = rtibuilderCapture("prior-forged");
  REQUIRE(runIn(capture).exitCode == 0);
  const fs::path carrierFile = capture / "assembly-files/carrier.xml";
  std::string text = e2e::bytesOf(carrierFile);
  const std::string made = "madeBy=\"PTM_1.2 PTM_FORMAT_LRGB\"";
  REQUIRE(text.find(made) != std::string::npos);
  text.replace(text.find(made), made.size(), "madeBy=\"RTIBuilder 2.0.2\"");
  writeBytes(carrierFile, text);
  const fs::path bag = capture.parent_path() / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);

  CHECK(e2e::surrogate("verify " + e2e::quote(bag) + " --quiet").exitCode == 0);  // fixity holds
  const e2e::CommandResult reexecuted = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute");
  INFO(reexecuted.output);
  CHECK(reexecuted.exitCode == 4);
  CHECK_THAT(reexecuted.output, Catch::Contains("FAIL  reexecute.files"));
  CHECK_THAT(reexecuted.output, Catch::Contains(std::string("file ") + kPriorPtm +
                                                " @madeBy: recorded \"RTIBuilder 2.0.2\", reproduced \"PTM_1.2 PTM_FORMAT_LRGB\""));
}

TEST_CASE("a prior file changed between runs is refused as changed evidence naming it", "[e2e][prior]") {
  const fs::path capture = rtibuilderCapture("prior-changed");
  REQUIRE(runIn(capture).exitCode == 0);
  const std::string recorded = carrierOf(capture).findFileByPath(kPriorLp)->sha256;
  writeBytes(capture / kPriorLp, rtibuilderLp(8) + "\r\n");
  const e2e::CommandResult r = runIn(capture);
  INFO(r.output);
  CHECK(r.exitCode == 3);
  CHECK_THAT(r.output, Catch::Contains(kPriorLp));
  CHECK_THAT(r.output, Catch::Contains("Prior work"));
  CHECK(carrierOf(capture).findFileByPath(kPriorLp)->sha256 == recorded);
  // pack refuses it the same way, naming it.
  const e2e::CommandResult pack =
      e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "b.zip") + " --quiet");
  INFO(pack.output);
  CHECK(pack.exitCode == 3);
  CHECK_THAT(pack.output, Catch::Contains(kPriorLp));
  CHECK_FALSE(fs::exists(capture.parent_path() / "b.zip"));
}

TEST_CASE("a prior file where the run writes its own result stops the run before anything is written", "[e2e][prior]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("prior-collision"), 8);
  const std::string ptm = ptmLrgb(4, 3);
  writeBytes(capture / "finished-files/ptm-lrgb.ptm", ptm);
  const e2e::CommandResult r = runIn(capture);
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Catch::Contains("finished-files/ptm-lrgb.ptm"));
  CHECK_THAT(r.output, Catch::Contains("prior work"));
  CHECK(e2e::bytesOf(capture / "finished-files/ptm-lrgb.ptm") == ptm);
  CHECK(e2e::snapshot(capture / "finished-files").size() == 1);
  CHECK_FALSE(fs::exists(capture / "assembly-files"));
}

TEST_CASE("after a run a new file is prior work but a file where Surrogate writes is its own", "[e2e][prior]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("prior-later"), 8);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --quiet").exitCode == 0);
  // A leftover at a path the next run writes (as an interrupted run could leave), and a file
  // someone added.
  writeBytes(capture / "finished-files/hsh2.rti", "not a finished result");
  writeBytes(capture / "finished-files/relight/stela12.ptm", ptmLrgb(2, 2));
  const e2e::CommandResult r =
      e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --basis hsh2 --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrierOf(capture);
  REQUIRE(c.findFileByPath("finished-files/hsh2.rti") != nullptr);
  CHECK(c.findFileByPath("finished-files/hsh2.rti")->role == "result");
  bool logged = false;
  for (const carrier::LogEntry& e : c.log)
    logged = logged || e.text.rfind("finished-files/hsh2.rti is not in the carrier but lies where this run writes", 0) == 0;
  CHECK(logged);
  CHECK(e2e::bytesOf(capture / "finished-files/hsh2.rti") != "not a finished result");
  const carrier::FileRecord* added = c.findFileByPath("finished-files/relight/stela12.ptm");
  REQUIRE(added != nullptr);
  CHECK(added->role == "prior");
  CHECK(added->priorKind == "rti");
  CHECK(added->sha256 == sha256sum(capture / "finished-files/relight/stela12.ptm"));
}
