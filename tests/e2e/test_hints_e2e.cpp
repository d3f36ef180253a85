// What a new user meets (issue 43, items 3 and 4): the warnings of a run named where the user
// looks (`run` prints each one's text, at most a screenful; `info` lists them all, as text and
// JSON), and a suggestion for each common mistake: a mistyped option or command, an image name
// that differs only in case, a folder inside a capture given for the capture, a capture given
// to `verify`. A run refused for a mistyped value leaves the capture byte-identical: no failed
// run enters the carrier's history.
//
// The warnings come from damaged XMP sidecars (not XML at all): the ingest step logs one
// warning per sidecar it cannot read (stages/ingest_stage.cpp), and the JSON is read back by
// Debian's Python json module, not by our writer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <regex>

#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

// A small capture whose first `damaged` shots have an XMP sidecar that is not XML.
fs::path captureWithDamagedSidecars(const std::string& name, int images, int damaged) {
  const fs::path capture = e2e::smallCapture(e2e::freshDir(name), images);
  for (int i = 1; i <= damaged; ++i) {
    char stem[16];
    std::snprintf(stem, sizeof stem, "IMG_%04d", i);
    std::ofstream(capture / "original-captures" / (std::string(stem) + ".xmp")) << "this is not XMP\n";
  }
  return capture;
}

// The warnings the capture's carrier records, as the carrier library reads them.
std::size_t recordedWarnings(const fs::path& capture) {
  std::size_t n = 0;
  for (const surrogate::carrier::LogEntry& e : surrogate::carrier::loadCarrier(capture / "assembly-files/carrier.xml").log)
    n += e.level == "warning";
  return n;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The lines of `text` from the one starting with `first` to the end.
std::string from(const std::string& text, const std::string& first) {
  const std::size_t at = text.find(first);
  return at == std::string::npos ? "" : text.substr(at);
}

}  // namespace

TEST_CASE("run prints each warning's text under its step and info lists them as text and JSON", "[e2e][hints]") {
  const fs::path capture = captureWithDamagedSidecars("warnings-few", 8, 3);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --no-report");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  // A heading for the ingest step, then one line per damaged sidecar, naming it. (The fit of
  // this generated capture logs one more warning, on pixels without a PTM maximum.)
  const std::size_t recorded = recordedWarnings(capture);
  CHECK(recorded >= 3);
  const std::string heading = std::to_string(recorded) + " warnings in the carrier's log:\n";
  CHECK_THAT(r.output, Contains(heading + "    s1 CaptureIngest:\n      original-captures/IMG_0001.xmp: the XMP sidecar cannot be read. "));
  CHECK(count(r.output, "\n      ") == recorded);
  for (const char* name : {"IMG_0001.xmp", "IMG_0002.xmp", "IMG_0003.xmp"})
    CHECK(count(from(r.output, "warnings in the carrier's log"), name) == 1);
  CHECK_THAT(r.output, !Contains("more:"));

  const e2e::CommandResult text = e2e::surrogate("info " + e2e::quote(capture));
  INFO(text.output);
  REQUIRE(text.exitCode == 0);
  CHECK_THAT(text.output, Contains(heading + "    s1 CaptureIngest:\n      original-captures/IMG_0001.xmp: the XMP sidecar cannot be read. "));
  CHECK(count(text.output, ": the XMP sidecar cannot be read. ") == 3);

  // The JSON, read by Python's json module: the capture's object nests the carrier's.
  const e2e::CommandResult json = e2e::runShell(
      std::string(SURROGATE_EXE) + " info " + e2e::quote(capture) + " --json 2>/dev/null | /usr/bin/python3 -c '"
      "import json, sys\n"
      "w = json.load(sys.stdin)[\"carrier\"][\"warnings\"]\n"
      "print(len(w))\n"
      "for x in w:\n"
      "  if \": the XMP sidecar cannot\" in x[\"text\"]: print(x[\"step\"], x[\"component\"], bool(x[\"time\"]), x[\"text\"][30:62])'");
  INFO(json.output);
  REQUIRE(json.exitCode == 0);
  CHECK(json.output == std::to_string(recorded) + "\n"
                       "s1 CaptureIngest True : the XMP sidecar cannot be read\n"
                       "s1 CaptureIngest True : the XMP sidecar cannot be read\n"
                       "s1 CaptureIngest True : the XMP sidecar cannot be read\n");
}

TEST_CASE("a carrier without warnings says so in info", "[e2e][hints]") {
  const fs::path capture = e2e::processedCapture(e2e::freshDir("warnings-none"));
  // The carrier without its log's warnings, written by the carrier library.
  surrogate::carrier::Carrier c = surrogate::carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  c.log.erase(std::remove_if(c.log.begin(), c.log.end(), [](const auto& e) { return e.level == "warning"; }), c.log.end());
  surrogate::carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  const e2e::CommandResult text = e2e::surrogate("info " + e2e::quote(capture));
  INFO(text.output);
  REQUIRE(text.exitCode == 0);
  CHECK_THAT(text.output, Contains("\n  warnings: none\n"));
  const e2e::CommandResult json = e2e::surrogate("info " + e2e::quote(capture) + " --json");
  CHECK_THAT(json.output, Contains("\"warnings\":[]"));
}

TEST_CASE("run prints at most 15 lines of warnings and counts the rest, which info lists", "[e2e][hints]") {
  const fs::path capture = captureWithDamagedSidecars("warnings-many", 20, 20);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --no-report");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  // 20 warnings of the ingest step first: its heading, 13 of them and the line counting the
  // others (those 7 and any a later step logged).
  const std::size_t recorded = recordedWarnings(capture);
  CHECK(recorded >= 20);
  const std::string listing = from(r.output, "  " + std::to_string(recorded) + " warnings in the carrier's log:\n");
  REQUIRE_FALSE(listing.empty());
  CHECK_THAT(listing, Contains("\n    s1 CaptureIngest:\n"));
  CHECK(count(listing, ": the XMP sidecar cannot be read. ") == 13);
  CHECK_THAT(listing, Contains("\n    and " + std::to_string(recorded - 13) + " more: surrogate info " + capture.string() +
                               " lists them all\n"));
  CHECK(count(listing, "\n") == 1 + 15);

  const e2e::CommandResult text = e2e::surrogate("info " + e2e::quote(capture));
  CHECK(count(text.output, ": the XMP sidecar cannot be read. ") == 20);
  CHECK_THAT(text.output, !Contains("more:"));
}

TEST_CASE("a mistyped option or command is a usage error that suggests the nearest name", "[e2e][hints]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("typo-option"));
  const e2e::CommandResult titel = e2e::surrogate("run " + e2e::quote(capture) + " --titel Stela");
  INFO(titel.output);
  CHECK(titel.exitCode == 2);
  CHECK_THAT(titel.output, Contains("unknown option \"--titel\": did you mean --title?"));
  CHECK_FALSE(fs::exists(capture / "assembly-files"));

  const e2e::CommandResult verfy = e2e::surrogate("verfy x.zip");
  INFO(verfy.output);
  CHECK(verfy.exitCode == 2);
  CHECK_THAT(verfy.output, Contains("unknown command \"verfy\"; did you mean verify?"));
  const e2e::CommandResult help = e2e::surrogate("help pakc");
  CHECK(help.exitCode == 2);
  CHECK_THAT(help.output, Contains("did you mean pack?"));

  // Nothing near: no guess, the list or --help instead.
  const e2e::CommandResult far = e2e::surrogate("frobnicate");
  CHECK(far.exitCode == 2);
  CHECK_THAT(far.output, !Contains("did you mean") && Contains("the commands are run, pack"));
  const e2e::CommandResult farOption = e2e::surrogate("info x --colour");
  CHECK(farOption.exitCode == 2);
  CHECK_THAT(farOption.output, !Contains("did you mean") && Contains("(see --help)"));
  // A prefix of one option: --reexec for --reexecute.
  const e2e::CommandResult prefix = e2e::surrogate("verify x.zip --reexec");
  CHECK(prefix.exitCode == 2);
  CHECK_THAT(prefix.output, Contains("did you mean --reexecute?"));
}

TEST_CASE("an excluded name that differs only in case is refused with the file's name and nothing recorded", "[e2e][hints]") {
  const fs::path capture = e2e::processedCapture(e2e::freshDir("exclude-case"));
  const auto before = e2e::snapshot(capture);
  const std::string carrierBefore = e2e::bytesOf(capture / "assembly-files/carrier.xml");

  const e2e::CommandResult stem =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --exclude img_0003 --reason 'flash did not fire'");
  INFO(stem.output);
  CHECK(stem.exitCode == 2);
  CHECK_THAT(stem.output, Contains("--exclude img_0003: names no image of the capture; did you mean IMG_0003?"));
  const e2e::CommandResult file =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --exclude img_0003.JPG --reason 'flash did not fire'");
  INFO(file.output);
  CHECK(file.exitCode == 2);
  CHECK_THAT(file.output, Contains("did you mean IMG_0003.jpg?"));
  const e2e::CommandResult near =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --exclude IMG_003 --reason 'flash did not fire'");
  INFO(near.output);
  CHECK(near.exitCode == 2);
  // One edit from IMG_0003, two from every other shot.
  CHECK_THAT(near.output, Contains("--exclude IMG_003: names no image of the capture; did you mean IMG_0003?"));
  const e2e::CommandResult far =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --exclude DSC_1234 --reason 'flash did not fire'");
  CHECK(far.exitCode == 2);
  CHECK_THAT(far.output, Contains("--exclude DSC_1234: names no image of the capture. Give the file name"));

  // A highlight given by hand for an image named in the wrong case: refused before the run too.
  const e2e::CommandResult highlight =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --highlight img_0004:0=200,150 --reason 'by eye'");
  INFO(highlight.output);
  CHECK(highlight.exitCode == 2);
  // The sphere named as people name it (the bare index 0 is the first sphere, sphere1).
  CHECK_THAT(highlight.output, Contains("--highlight img_0004:sphere1=200,150: names no image of the capture; did you mean IMG_0004?"));

  // No failed run in the history: the carrier and every file are as they were, byte for byte.
  CHECK(e2e::bytesOf(capture / "assembly-files/carrier.xml") == carrierBefore);
  auto after = e2e::snapshot(capture);
  for (auto it = after.begin(); it != after.end();) it = it->first.rfind(".surrogate", 0) == 0 ? after.erase(it) : std::next(it);
  auto expected = before;
  for (auto it = expected.begin(); it != expected.end();)
    it = it->first.rfind(".surrogate", 0) == 0 ? expected.erase(it) : std::next(it);
  CHECK(after == expected);

  // The name as the suggestion gives it is taken.
  const e2e::CommandResult good =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --no-report --exclude IMG_0003 --reason 'flash did not fire'");
  INFO(good.output);
  CHECK(good.exitCode == 0);
}

TEST_CASE("a folder inside a capture given for the capture is refused naming its parent", "[e2e][hints]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("subfolder"));
  const auto before = e2e::snapshot(capture);
  for (const std::string sub : {"original-captures", "jpeg-exports/"}) {
    const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture / sub) + " --quiet");
    INFO(r.output);
    CHECK(r.exitCode == 2);
    const std::string name = sub.back() == '/' ? sub.substr(0, sub.size() - 1) : sub;
    CHECK_THAT(r.output, Contains("is the " + name + " folder of a capture; run works on the capture folder, its parent: "
                                  "surrogate run " + capture.string() + "\n"));
  }
  const e2e::CommandResult pack =
      e2e::surrogate("pack " + e2e::quote(capture / "original-captures") + " -o " + e2e::quote(capture.parent_path() / "p.zip"));
  INFO(pack.output);
  CHECK(pack.exitCode == 2);
  CHECK_THAT(pack.output, Contains("surrogate pack " + capture.string() + "\n"));
  // Nothing written in the capture or its folders.
  CHECK(e2e::snapshot(capture) == before);
  CHECK_FALSE(fs::exists(capture / "original-captures/.surrogate"));
  CHECK_FALSE(fs::exists(capture / ".surrogate"));
}

TEST_CASE("verify given a capture says to pack it first", "[e2e][hints]") {
  const fs::path capture = e2e::processedCapture(e2e::freshDir("verify-capture"));
  const e2e::CommandResult r = e2e::surrogate("verify " + e2e::quote(capture));
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Contains(capture.string() + ": is a capture, not a package: pack it first with surrogate pack " +
                                capture.string() + " -o OUT, then verify OUT"));
  // A capture never processed is a capture too.
  const fs::path fresh = e2e::smallCapture(e2e::freshDir("verify-fresh"));
  const e2e::CommandResult f = e2e::surrogate("verify " + e2e::quote(fresh) + " --json");
  INFO(f.output);
  CHECK(f.exitCode == 2);
  CHECK_THAT(f.output, Contains("pack it first") && Contains("\"exitCode\":2"));
}
