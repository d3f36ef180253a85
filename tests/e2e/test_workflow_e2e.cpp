// The capture's memory, end to end: the user guide's iterative walk-through (run, exclude, fix
// a sphere, fix a highlight, pack, verify), failed runs, changed originals, stale results,
// stray files, concurrent commands and processes killed midway.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "bag_check.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

carrier::Carrier carrierOf(const fs::path& capture) {
  return carrier::loadCarrier(capture / "assembly-files/carrier.xml");
}

const carrier::Step* stepOf(const carrier::Carrier& c, const std::string& component) {
  for (const carrier::Step& s : c.process)
    if (s.component == component) return &s;
  return nullptr;
}

std::vector<carrier::Intervention> interventions(const carrier::Carrier& c) {
  std::vector<carrier::Intervention> out;
  for (const carrier::Step& s : c.process) out.insert(out.end(), s.interventions.begin(), s.interventions.end());
  return out;
}

bool hasIntervention(const carrier::Carrier& c, const std::string& kind, const std::string& target) {
  for (const carrier::Intervention& i : interventions(c))
    if (i.kind == kind && i.target == target) return true;
  return false;
}

// Every file the carrier records is on disk with the recorded size and SHA-256: the carrier
// and the files agree. Returns the disagreements.
std::vector<std::string> disagreements(const fs::path& capture) {
  std::vector<std::string> out;
  const carrier::Carrier c = carrierOf(capture);
  for (const carrier::FileRecord& f : c.files) {
    const fs::path p = capture / f.path;
    if (!fs::is_regular_file(p)) {
      out.push_back(f.path + " missing");
      continue;
    }
    if (digestFile(p).sha256 != f.sha256) out.push_back(f.path + " differs");
  }
  // Nothing in Surrogate's output folders that the carrier does not describe (but the report).
  for (const char* dir : {"assembly-files", "finished-files"}) {
    if (!fs::exists(capture / dir)) continue;
    for (const auto& e : fs::recursive_directory_iterator(capture / dir)) {
      const std::string rel = fs::relative(e.path(), capture).generic_string();
      if (e.is_regular_file() && rel != "assembly-files/carrier.xml" && rel != "finished-files/report.html" &&
          !c.findFileByPath(rel))
        out.push_back(rel + " not described");
    }
  }
  return out;
}

// What disagreements() returns when the carrier and the files agree (compared as a vector so
// that a failure prints what disagrees).
const std::vector<std::string> kAgree;

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

}  // namespace

TEST_CASE("the guide's iterative walk-through ends with every decision recorded", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("walk"), 8);
  runIn(capture, "--title \"Stela 12\" --creator \"Ana Silva:photographer\" --meta \"site=Museum store 3\"");
  runIn(capture, "--exclude IMG_0003 --reason \"the flash did not fire\" --operator \"Ana Silva\"");
  runIn(capture, "--sphere 339,57,45 --reason \"the detected circle was cut by the frame edge\"");
  runIn(capture, "--highlight IMG_0004:0=326,70 --reason \"a reflection on the rim\"");

  carrier::Carrier c = carrierOf(capture);
  CHECK(c.header.title == "Stela 12");
  REQUIRE(c.header.creators.size() == 1);
  CHECK(c.header.creators[0].name == "Ana Silva");
  REQUIRE(c.header.meta.size() == 1);
  CHECK(c.header.meta[0].second == "Museum store 3");
  CHECK(hasIntervention(c, "exclude-image", "IMG_0003"));
  CHECK(hasIntervention(c, "manual-sphere", "0"));
  CHECK(hasIntervention(c, "manual-highlight", "IMG_0004:0"));
  for (const carrier::Intervention& i : interventions(c))
    if (i.kind == "exclude-image") CHECK(i.who == "Ana Silva");  // kept from the run that decided it
  // Four runs in the history, each with its command line.
  REQUIRE(c.header.runs.size() == 4);
  CHECK(c.header.runs[1].outcome == "completed");
  CHECK(std::find(c.header.runs[1].arguments.begin(), c.header.runs[1].arguments.end(), "--exclude") !=
        c.header.runs[1].arguments.end());
  // The excluded image is not fitted.
  const carrier::Result* ingest = c.findResult(stepOf(c, "CaptureIngest")->id);
  REQUIRE(ingest != nullptr);
  for (const carrier::DataItem* in : ingest->itemsOf("input"))
    CHECK(c.findFile(*in->get("file"))->path.find("IMG_0003") == std::string::npos);
  CHECK(disagreements(capture) == kAgree);

  // info lists the standing decisions with who, when and why.
  const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(capture));
  CHECK_THAT(info.output, Catch::Contains("the flash did not fire"));
  CHECK_THAT(info.output, Catch::Contains("by Ana Silva"));
  CHECK_THAT(info.output, Catch::Contains("manual-highlight IMG_0004:0"));

  // A withdrawal is explicit, needs a reason, and is recorded.
  CHECK(e2e::surrogate("run " + e2e::quote(capture) + " --forget-exclusion IMG_0003 --quiet").exitCode == 2);
  CHECK(e2e::surrogate("run " + e2e::quote(capture) + " --forget-exclusion IMG_0005 --reason x --quiet").exitCode == 2);
  runIn(capture, "--forget-exclusion IMG_0003 --reason \"the flash fired after all\"");
  c = carrierOf(capture);
  CHECK_FALSE(hasIntervention(c, "exclude-image", "IMG_0003"));
  CHECK(hasIntervention(c, "manual-sphere", "0"));
  CHECK_THAT(c.header.runs.back().notes.front(), Catch::Contains("the flash fired after all"));

  // pack after a changed result re-runs with the recorded decisions, and says so.
  std::ofstream(capture / "finished-files/normals.png", std::ios::app) << "x";
  const fs::path bag = capture.parent_path() / "bag";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag));
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK_THAT(pack.output, Catch::Contains("with the decisions its carrier records"));
  c = carrierOf(capture);
  CHECK(c.header.title == "Stela 12");
  CHECK(c.header.meta.size() == 1);
  CHECK(hasIntervention(c, "manual-sphere", "0"));
  CHECK(hasIntervention(c, "manual-highlight", "IMG_0004:0"));
  CHECK(c.header.runs.back().command == "pack");
  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --quiet");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
}

TEST_CASE("a failed run leaves the previous results and carrier whole, and is in the history", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("failed"), 8);
  fs::remove(capture / "jpeg-exports/IMG_0008.jpg");  // one shot without an export
  runIn(capture, "--title \"Good run\"");
  const auto before = e2e::snapshot(capture / "finished-files");
  // The exports cannot be the source: found only when the images are selected, mid-run.
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --source export --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains("IMG_0008"));
  CHECK(e2e::snapshot(capture / "finished-files") == before);
  const carrier::Carrier c = carrierOf(capture);
  CHECK(c.header.title == "Good run");
  for (const carrier::Step& s : c.process) CHECK(c.findResult(s.id)->status == "completed");
  REQUIRE(c.header.runs.size() == 2);
  CHECK(c.header.runs[1].outcome == "failed");
  CHECK_THAT(c.header.runs[1].notes.back(), Catch::Contains("IMG_0008"));
  // The process list is the completed run's; the failed run's decision stands for the next run,
  // recorded with the plan it made.
  CHECK(stepOf(c, "CaptureIngest")->param("source") == "auto");
  REQUIRE_FALSE(c.header.runs[1].planned.empty());
  CHECK(c.header.runs[1].planned.front().param("source") == "export");
  CHECK(carrier::standingProcess(c).front().param("source") == "export");
  CHECK(disagreements(capture) == kAgree);
  CHECK_FALSE(fs::exists(capture / ".surrogate/staging"));
}

TEST_CASE("decisions given on a failed run stand, so a refusal's advice followed frame by frame adds up", "[e2e][workflow]") {
  // Two frames at 5 % exposure (the generator's weak flash): IMG_0003 of one capture and IMG_0008
  // of another of the same seed, whose other frames are the same bytes.
  const fs::path dir = e2e::freshDir("failed-decisions");
  auto generate = [&](const std::string& name, int darkFrame) {
    const fs::path out = dir / name;
    const e2e::CommandResult g = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(out) +
                                               " --images 12 --width 400 --height 300 --sphere-radius 50"
                                               " --formats jpeg --dark-frame " + std::to_string(darkFrame));
    REQUIRE(g.exitCode == 0);
    fs::remove_all(out / "truth");
    return out;
  };
  const fs::path capture = generate("capture", 3);
  fs::copy_file(generate("other", 8) / "jpeg-exports/IMG_0008.jpg", capture / "jpeg-exports/IMG_0008.jpg",
                fs::copy_options::overwrite_existing);
  const fs::path lp = dir / "lights.lp";
  auto lights = [&](const std::string& options) {
    return e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(lp) + " --quiet " + options);
  };
  const e2e::CommandResult first = lights("");
  INFO(first.output);
  CHECK(first.exitCode == 1);
  CHECK_THAT(first.output, Catch::Contains("IMG_0003") && Catch::Contains("IMG_0008"));
  // The refusal's advice, one frame at a time: each run fails until the last, and the
  // exclusion of the run before stands (it was dropped, and the third run named IMG_0003 again).
  const e2e::CommandResult second = lights("--exclude IMG_0003 --reason \"weak flash\"");
  INFO(second.output);
  CHECK(second.exitCode == 1);
  CHECK_THAT(second.output, Catch::Contains("--exclude IMG_0008"));
  const std::string info = e2e::surrogate("info " + e2e::quote(capture)).output;
  CHECK_THAT(info, Catch::Contains("excluded images: IMG_0003") && Catch::Contains("those of r2, which failed"));
  const e2e::CommandResult third = lights("--exclude IMG_0008 --reason \"weak flash again\"");
  INFO(third.output);
  REQUIRE(third.exitCode == 0);
  const carrier::Carrier c = carrierOf(capture);
  CHECK(hasIntervention(c, "exclude-image", "IMG_0003"));
  CHECK(hasIntervention(c, "exclude-image", "IMG_0008"));
  CHECK(c.header.runs.size() == 3);
  std::ifstream in(lp);
  int count = 0;
  in >> count;
  CHECK(count == 10);
}

TEST_CASE("a changed original is a fixity failure in run, pack and verify, never a new baseline", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("flip"), 8);
  runIn(capture, "");
  const std::string recorded = carrierOf(capture).findFileByPath("original-captures/IMG_0005.dng")->sha256;
  // A bag of the good state, for verify below.
  const fs::path good = capture.parent_path() / "good.tar";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(good) + " --quiet").exitCode == 0);

  flipByte(capture / "original-captures/IMG_0005.dng", 5000);
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  CHECK(run.exitCode == 3);
  CHECK_THAT(run.output, Catch::Contains("original-captures/IMG_0005.dng"));
  const fs::path bag = capture.parent_path() / "bag.zip";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
  CHECK(pack.exitCode == 3);
  CHECK_THAT(pack.output, Catch::Contains("original-captures/IMG_0005.dng"));
  CHECK_FALSE(fs::exists(bag));
  CHECK(carrierOf(capture).findFileByPath("original-captures/IMG_0005.dng")->sha256 == recorded);

  // The same flip inside a bag, manifests redone: verify still fails on the carrier's record.
  const fs::path dir = capture.parent_path() / "flipped-bag";
  REQUIRE(e2e::runShell("mkdir -p " + e2e::quote(dir) + " && tar -xf " + e2e::quote(good) + " -C " + e2e::quote(dir)).exitCode == 0);
  fs::path root;
  for (const auto& e : fs::directory_iterator(dir)) root = e.path();
  fs::copy_file(capture / "original-captures/IMG_0005.dng", root / "data/original-captures/IMG_0005.dng",
                fs::copy_options::overwrite_existing);
  CHECK(e2e::surrogate("verify " + e2e::quote(root) + " --quiet").exitCode == 3);

  // A deliberate replacement is accepted only with a recorded reason, for exactly this state.
  runIn(capture, "--accept-changed original-captures/IMG_0005.dng --reason \"re-copied from the card\"");
  const carrier::Carrier c = carrierOf(capture);
  CHECK(hasIntervention(c, "accept-changed-original", "original-captures/IMG_0005.dng"));
  CHECK(c.findFileByPath("original-captures/IMG_0005.dng")->sha256 != recorded);
  flipByte(capture / "original-captures/IMG_0005.dng", 6000);  // a later change is not accepted
  CHECK(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 3);
  fs::remove(capture / "original-captures/IMG_0006.dng");
  flipByte(capture / "original-captures/IMG_0005.dng", 6000);  // back as accepted
  const e2e::CommandResult gone = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  CHECK(gone.exitCode == 3);
  CHECK_THAT(gone.output, Catch::Contains("IMG_0006.dng"));
}

TEST_CASE("after lights only, a changed original still fails and is not re-recorded", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("flip-lights"), 8);
  REQUIRE(e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "l.lp") + " --quiet").exitCode == 0);
  const std::string recorded = carrierOf(capture).findFileByPath("original-captures/IMG_0002.dng")->sha256;
  flipByte(capture / "original-captures/IMG_0002.dng", 4000);
  CHECK(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 3);
  CHECK(carrierOf(capture).findFileByPath("original-captures/IMG_0002.dng")->sha256 == recorded);
  CHECK(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 3);
  CHECK(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "b.zip") + " --quiet").exitCode == 3);
}

TEST_CASE("results a run no longer makes are moved aside, never bagged", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("stale"), 12);
  runIn(capture, "--basis ptm-rgb --basis hsh3");
  runIn(capture, "--basis ptm-lrgb");
  CHECK_FALSE(fs::exists(capture / "finished-files/hsh3.rti"));
  CHECK(fs::exists(capture / "superseded-files/r2/finished-files/hsh3.rti"));
  const carrier::Carrier c = carrierOf(capture);
  bool noted = false;
  for (const std::string& n : c.header.runs.back().notes) noted = noted || n.find("hsh3.rti") != std::string::npos;
  CHECK(noted);
  // A plain run keeps the basis choice.
  runIn(capture, "");
  CHECK(stepOf(carrierOf(capture), "RtiFit")->param("basis") == "ptm-lrgb");
  CHECK_FALSE(fs::exists(capture / "finished-files/hsh2.rti"));

  const fs::path bag = capture.parent_path() / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  CHECK_FALSE(fs::exists(bag / "data/superseded-files"));
  // A stale result slipped into the bag with its manifests redone is not sound.
  fs::copy_file(capture / "superseded-files/r2/finished-files/hsh3.rti", bag / "data/finished-files/hsh3.rti");
  REQUIRE(e2e::runShell("cd " + e2e::quote(bag) + " && sha256sum data/finished-files/hsh3.rti >> manifest-sha256.txt && "
                        "sha512sum data/finished-files/hsh3.rti >> manifest-sha512.txt && "
                        "grep -v manifest- tagmanifest-sha256.txt > t && for m in manifest-sha256.txt manifest-sha512.txt; do sha256sum $m >> t; done && mv t tagmanifest-sha256.txt && "
                        "grep -v manifest- tagmanifest-sha512.txt > t && for m in manifest-sha256.txt manifest-sha512.txt; do sha512sum $m >> t; done && mv t tagmanifest-sha512.txt").exitCode == 0);
  const e2e::CommandResult v = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(v.output);
  CHECK(v.exitCode == 3);
  CHECK_THAT(v.output, Catch::Contains("data/finished-files/hsh3.rti"));
  // And a file dropped into the output folders is refused by pack, by name.
  std::ofstream(capture / "finished-files/mine.rti") << "someone else's";
  const e2e::CommandResult refused = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "b2.zip") + " --quiet");
  CHECK(refused.exitCode == 1);
  CHECK_THAT(refused.output, Catch::Contains("finished-files/mine.rti"));
}

TEST_CASE("a card with .DS_Store, Thumbs.db and notes packs and verifies sound", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("card"), 8);
  std::ofstream(capture / "original-captures/.DS_Store") << "finder";
  std::ofstream(capture / "original-captures/._IMG_0001.dng") << "appledouble";
  std::ofstream(capture / "jpeg-exports/Thumbs.db") << "explorer";
  std::ofstream(capture / "notes.txt") << "shot on 2026-11-30, dome B";
  std::ofstream(capture / "original-captures/.x.part-1-0") << "an interrupted copy";
  runIn(capture, "");
  const carrier::Carrier c = carrierOf(capture);
  CHECK(c.findFileByPath("notes.txt") != nullptr);
  CHECK(c.findFileByPath("notes.txt")->role == "other");
  CHECK(c.findFileByPath("original-captures/.x.part-1-0") != nullptr);
  CHECK(c.findFileByPath("original-captures/.DS_Store") == nullptr);
  CHECK(c.findFileByPath("jpeg-exports/Thumbs.db") == nullptr);
  for (const char* archive : {"bag", "bag.zip"}) {
    const fs::path bag = capture.parent_path() / archive;
    const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
    INFO(pack.output);
    REQUIRE(pack.exitCode == 0);
    const bagcheck::BagFiles files = bagcheck::readBag(bag);
    CHECK(bagcheck::validate(files).empty());
    CHECK(files.files.count("data/notes.txt") == 1);
    CHECK(files.files.count("data/original-captures/.DS_Store") == 0);
    CHECK(files.files.count("data/jpeg-exports/Thumbs.db") == 0);
    const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(bag));
    INFO(verify.output);
    CHECK(verify.exitCode == 0);
  }
  // Output inside the originals' folder is refused; so is a package inside the capture.
  CHECK(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(capture / "original-captures/bag.zip")).exitCode == 1);
  CHECK(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(capture / "bag.zip")).exitCode == 1);
  CHECK(e2e::surrogate("lights " + e2e::quote(capture) + " -o " + e2e::quote(capture / "jpeg-exports/x.lp")).exitCode == 1);
  CHECK_FALSE(fs::exists(capture / "original-captures/bag.zip"));
}

TEST_CASE("a symbolic link in the capture is refused by name", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("link"), 8);
  fs::copy_file(capture / "original-captures/IMG_0001.dng", capture.parent_path() / "outside.dng");
  fs::create_symlink(capture.parent_path() / "outside.dng", capture / "original-captures/IMG_0009.dng");
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains("original-captures/IMG_0009.dng"));
  CHECK_THAT(r.output, Catch::Contains("symbolic link"));
  CHECK_FALSE(fs::exists(capture / "assembly-files/carrier.xml"));
}

TEST_CASE("one command at a time works on a capture", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("lock"), 8);
  runIn(capture, "");
  // Another holder of the lock (here flock(1), the same advisory lock) makes run and pack stop,
  // naming the reason, and change nothing.
  const auto before = e2e::snapshot(capture);
  const std::string hold = "flock " + e2e::quote(capture / ".surrogate/lock") + " sleep 3 & sleep 0.5; ";
  const e2e::CommandResult run = e2e::runShell(hold + SURROGATE_EXE + std::string(" run ") + e2e::quote(capture) + " --quiet 2>&1; echo rc=$?; wait");
  CHECK_THAT(run.output, Catch::Contains("another Surrogate command is working on this capture"));
  CHECK_THAT(run.output, Catch::Contains("rc=1"));
  const e2e::CommandResult pack = e2e::runShell(hold + SURROGATE_EXE + std::string(" pack ") + e2e::quote(capture) + " -o " +
                                                e2e::quote(capture.parent_path() / "b.zip") + " --quiet 2>&1; echo rc=$?; wait");
  CHECK_THAT(pack.output, Catch::Contains("rc=1"));
  CHECK(e2e::snapshot(capture) == before);

  // Two real runs at once: whichever way they meet, the carrier and the files agree after.
  const e2e::CommandResult both = e2e::runShell(std::string(SURROGATE_EXE) + " run " + e2e::quote(capture) +
                                                " --exclude IMG_0002 --reason a --quiet & sleep 0.05; " + SURROGATE_EXE + " run " +
                                                e2e::quote(capture) + " --exclude IMG_0007 --reason b --quiet; wait");
  INFO(both.output);
  CHECK(disagreements(capture) == kAgree);
}

// A command killed while it wrote a file atomically (the report, written after the commit)
// leaves the temporary ".NAME.part-PID-N" beside it: the next command on the capture removes it.
TEST_CASE("the next command removes what a killed atomic write left in the output folders", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("part-leftover"), 8);
  runIn(capture, "--basis ptm-lrgb");
  const fs::path report = capture / "finished-files/.report.html.part-999999-0";
  const fs::path image = capture / "assembly-files/.spheres.png.part-999999-1";
  std::ofstream(report) << "<html>half a report";
  std::ofstream(image) << "half a picture";
  CHECK_FALSE(disagreements(capture).empty());
  runIn(capture, "--basis ptm-lrgb");
  CHECK_FALSE(fs::exists(report));
  CHECK_FALSE(fs::exists(image));
  CHECK(disagreements(capture) == kAgree);
  CHECK_THAT(e2e::bytesOf(capture / "assembly-files/carrier.xml"),
             Catch::Contains("interrupted while it wrote assembly-files/.spheres.png.part-999999-1 and 1 more"));
}

TEST_CASE("kill -9 during run or commit leaves the old or the new state, never a mix", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("kill"), 12);
  runIn(capture, "--basis ptm-rgb");
  auto results = [&] {  // the results, without the report (which holds the time it was made)
    auto files = e2e::snapshot(capture / "finished-files");
    files.erase("report.html");
    return files;
  };
  const auto old = results();
  // Killed at several points of a run that changes every result.
  for (int ms : {50, 150, 300, 450, 600}) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      execl(SURROGATE_EXE, SURROGATE_EXE, "run", capture.c_str(), "--basis", "hsh2", "--quiet", "--threads", "1",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    INFO("killed after " << ms << " ms");
    // Untouched, or complete; or, killed inside the commit, finished by the next command.
    if (!fs::exists(capture / ".surrogate/commit")) CHECK(disagreements(capture) == kAgree);
    const e2e::CommandResult again = e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-rgb --quiet");
    INFO(again.output);
    REQUIRE(again.exitCode == 0);
    CHECK(disagreements(capture) == kAgree);
    CHECK(results() == old);  // the same decisions give the same bytes
  }
  // Killed at several points of a pack that has to process first (a result changed): the
  // package is whole under its name or absent, and the capture is the old or the new state.
  for (int ms : {100, 300, 500, 700}) {
    std::ofstream(capture / "finished-files/normals.png", std::ios::app) << "x";
    const fs::path out = capture.parent_path() / ("killed-" + std::to_string(ms) + ".tar");
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      execl(SURROGATE_EXE, SURROGATE_EXE, "pack", capture.c_str(), "-o", out.c_str(), "--quiet", "--threads", "1",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    INFO("pack killed after " << ms << " ms");
    if (fs::exists(out)) CHECK(e2e::surrogate("verify " + e2e::quote(out) + " --quiet").exitCode == 0);
    const e2e::CommandResult again = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
    INFO(again.output);
    REQUIRE(again.exitCode == 0);
    CHECK(disagreements(capture) == kAgree);
    CHECK(results() == old);
  }
  // Dying while the report is written, after the commit (a kill above may land there too, by
  // chance): the output folders hold only what the carrier describes, and the next command
  // removes the half-written page from the work folder and says so.
  const e2e::CommandResult reportCrash = e2e::runShell("SURROGATE_FAULT_INJECTION=report " + std::string(SURROGATE_EXE) +
                                                       " run " + e2e::quote(capture) + " --basis hsh2 --quiet");
  CHECK(reportCrash.exitCode == 137);
  CHECK_FALSE(fs::exists(capture / "finished-files/report.html"));
  CHECK(disagreements(capture) == kAgree);
  bool halfPage = false;
  for (const auto& e : fs::directory_iterator(capture / ".surrogate"))
    halfPage = halfPage || e.path().filename().string().rfind(".report.html.part-", 0) == 0;
  CHECK(halfPage);
  runIn(capture, "--basis ptm-rgb");
  CHECK(disagreements(capture) == kAgree);
  CHECK(fs::exists(capture / "finished-files/report.html"));
  for (const auto& e : fs::directory_iterator(capture / ".surrogate"))
    CHECK(e.path().filename().string().find(".part-") == std::string::npos);
  CHECK_THAT(e2e::bytesOf(capture / "assembly-files/carrier.xml"), Catch::Contains("interrupted while it wrote .surrogate/.report.html.part-"));

  // Dying in the middle of a commit (results moved, carrier not yet): the next command finishes
  // the commit, so the new state is whole.
  const e2e::CommandResult crash = e2e::runShell("SURROGATE_FAULT_INJECTION=commit " + std::string(SURROGATE_EXE) +
                                                 " run " + e2e::quote(capture) + " --basis hsh2 --quiet");
  CHECK(crash.exitCode == 137);
  CHECK(fs::exists(capture / ".surrogate/commit"));
  CHECK(fs::exists(capture / "finished-files/hsh2.rti"));
  CHECK(carrierOf(capture).findFileByPath("finished-files/hsh2.rti") == nullptr);  // the old carrier, still
  const fs::path bag = capture.parent_path() / "bag.tar";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK_FALSE(fs::exists(capture / ".surrogate/commit"));
  const carrier::Carrier c = carrierOf(capture);
  CHECK(c.findFileByPath("finished-files/hsh2.rti") != nullptr);
  CHECK(c.findFileByPath("finished-files/ptm-rgb.ptm") == nullptr);
  CHECK(disagreements(capture) == kAgree);
  CHECK(e2e::surrogate("verify " + e2e::quote(bag) + " --quiet").exitCode == 0);
}

TEST_CASE("pack processes again, with the recorded decisions, a capture recorded by an older stage version", "[e2e][workflow]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("oldversion"), 8);
  runIn(capture, "--exclude IMG_0002 --reason \"blurred\"");
  carrier::Carrier c = carrierOf(capture);
  const std::string current = c.process.front().version;
  c.process.front().version = "0";  // as an older Surrogate would have recorded it
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  const fs::path bag = capture.parent_path() / "bag";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag));
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK_THAT(pack.output, Catch::Contains("recorded by version 0"));
  c = carrierOf(capture);
  CHECK(c.process.front().version == current);
  CHECK(hasIntervention(c, "exclude-image", "IMG_0002"));
  CHECK(e2e::surrogate("verify " + e2e::quote(bag) + " --quiet").exitCode == 0);
}
