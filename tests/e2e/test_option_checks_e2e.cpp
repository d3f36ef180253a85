// Every option value is checked before any processing: a bad one is exit 1 or 2 (never 5, an
// internal error such as an OpenCV assertion), the output names the option and the value,
// and nothing is written into the capture.
//
// Two kinds of checks: those that need no capture (cli/option_checks.h: numbers, UTF-8 text,
// --meta keys), made while the command line is read; and those against the frame
// (run/request_checks.h: a circle, region or point outside the 400x300 frame of
// e2e::smallCapture), made once the capture's images are known, before any step runs.
#include <catch2/catch.hpp>

#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>

#include "carrier/carrier.h"
#include "core/error.h"
#include "e2e_support.h"
#include "pipeline/context.h"
#include "run/plan.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

// Every entry under `root`, folders too (so that an empty assembly-files/ counts), with the
// SHA-256 of each file; without Surrogate's working area .surrogate/ (the capture's lock,
// capture/lock.h), which is not part of the capture's state.
std::map<std::string, std::string> state(const fs::path& root) {
  std::map<std::string, std::string> out = e2e::snapshot(root);
  for (const auto& entry : fs::recursive_directory_iterator(root))
    out.emplace(fs::relative(entry.path(), root).generic_string(), "");
  for (auto it = out.begin(); it != out.end();)
    it = it->first.rfind(".surrogate", 0) == 0 ? out.erase(it) : std::next(it);
  return out;
}

// Runs `surrogate run CAPTURE <options>` on a fresh copy of the small capture and requires a
// refusal: exit 1 or 2, the output naming each of `named`, and the capture untouched.
e2e::CommandResult requireRefused(const std::string& options, const std::vector<std::string>& named) {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("option-checks"));
  const auto before = state(capture);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet " + options);
  INFO("surrogate run CAPTURE --quiet " << options << "\n" << r.output);
  CHECK((r.exitCode == 1 || r.exitCode == 2));
  CHECK_THAT(r.output, !Catch::Contains("internal error"));
  for (const std::string& n : named) CHECK_THAT(r.output, Catch::Contains(n));
  CHECK(state(capture) == before);
  CHECK_FALSE(fs::exists(capture / "assembly-files"));
  CHECK_FALSE(fs::exists(capture / "finished-files"));
  return r;
}

}  // namespace

TEST_CASE("the small capture has the 400x300 frame the frame checks below assume") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("option-checks-frame"));
  const e2e::CommandResult r =
      e2e::surrogate("info " + e2e::quote(capture / "original-captures/IMG_0001.dng") + " --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("\"width\":400") && Catch::Contains("\"height\":300"));
}

// ---- Checks that need no capture: they pass as soon as the command line is read ------------

TEST_CASE("a memory budget beyond any machine is refused as such, not as too small") {
  // 1e20 G once overflowed the size in bytes and was refused as "0.0K is too small".
  const auto r = requireRefused("--memory 99999999999999999999G", {"--memory", "more memory than any machine has"});
  CHECK_THAT(r.output, !Catch::Contains("too small"));
}

TEST_CASE("a circle given by hand with a radius of 0 or below is refused by its radius") {
  requireRefused("--sphere 339,57,-5", {"--sphere 339,57,-5", "radius"});
  // Not "no usable highlight": the radius is what is wrong.
  const e2e::CommandResult r = requireRefused("--sphere 339,57,0 --reason typo", {"--sphere 339,57,0", "radius"});
  CHECK_THAT(r.output, !Catch::Contains("highlight"));
  requireRefused("--sphere 339,57,2 --reason typo", {"--sphere 339,57,2", "radius"});
}

TEST_CASE("a circle given by hand with a negative centre or not three numbers is refused") {
  requireRefused("--sphere -3,57,45", {"--sphere -3,57,45", "negative"});
  requireRefused("--sphere 339,57,nan", {"--sphere", "339,57,nan"});
  requireRefused("--sphere 339,57", {"--sphere", "339,57"});
}

TEST_CASE("a highlight given by hand with negative coordinates or a bad IMAGE:SPHERE is refused") {
  requireRefused("--highlight IMG_0004:0=-1,70", {"--highlight IMG_0004:0=-1,70", "negative"});
  requireRefused("--highlight IMG_0004:x=326,70", {"--highlight IMG_0004:x=326,70", "must be sphere1 for the first sphere"});
  requireRefused("--highlight :0=326,70", {"--highlight :0=326,70", "image"});
  requireRefused("--highlight IMG_0004:0=326", {"--highlight", "326"});
  requireRefused("--highlight IMG_0004:0=inf,70", {"--highlight", "inf,70"});
}

TEST_CASE("a sphere search region with no area or fractional pixels is refused") {
  requireRefused("--sphere-roi 0,0,-5,10", {"--sphere-roi 0,0,-5,10", "above 0"});
  requireRefused("--sphere-roi 0,0,0,100", {"--sphere-roi 0,0,0,100"});
  requireRefused("--sphere-roi 0,0,10.5,100", {"--sphere-roi 0,0,10.5,100", "whole numbers"});
  requireRefused("--sphere-roi -5,0,100,100", {"--sphere-roi -5,0,100,100", "negative"});
}

TEST_CASE("lens and sphere measures must be finite above 0 and of a real size") {
  requireRefused("--light-model perspective --focal-length 1e20 --pixel-pitch 0.006",
                 {"--focal-length 1e20", "millimetres"});
  requireRefused("--focal-length 0", {"--focal-length 0"});
  requireRefused("--focal-length -50", {"--focal-length -50"});
  requireRefused("--focal-length inf", {"--focal-length", "inf"});
  requireRefused("--pixel-pitch 2", {"--pixel-pitch 2"});
  requireRefused("--pixel-pitch 0", {"--pixel-pitch 0"});
  requireRefused("--sphere-diameter 0", {"--sphere-diameter 0"});
  requireRefused("--sphere-diameter 1e9", {"--sphere-diameter 1e9"});
  requireRefused("--light-model fisheye", {"--light-model fisheye"});
}

TEST_CASE("a metadata key that pack could not write into bag-info.txt is refused by run") {
  requireRefused("--meta 'my key=v'", {"--meta my key=v", "my key"});
  requireRefused("--meta 'Site:Room=3'", {"--meta Site:Room=3"});
  requireRefused("--meta Payload-Oxum=5.1", {"--meta Payload-Oxum=5.1", "computed"});
  requireRefused("--meta =v", {"--meta =v"});
}

TEST_CASE("an empty image name to exclude or an empty creator is refused") {
  requireRefused("--exclude '' --reason 'the flash did not fire'", {"--exclude", "image"});
  requireRefused("--creator ''", {"--creator"});
}

TEST_CASE("text options with control characters or invalid UTF-8 are refused naming the option") {
  requireRefused("--title \"$(printf 'Stela\\001 12')\"", {"--title Stela\\x01 12", "control character"});
  requireRefused("--title \"$(printf 'Stela \\377')\"", {"--title Stela \\xFF", "UTF-8"});
  requireRefused("--creator \"$(printf 'Ana\\nSilva')\"", {"--creator Ana\\x0ASilva"});
  requireRefused("--meta \"$(printf 'site=Museum\\033[2J')\"", {"--meta site=Museum\\x1B[2J"});
  requireRefused("--operator \"$(printf 'Ana\\300\\200')\"", {"--operator Ana\\xC0\\x80", "UTF-8"});
  requireRefused("--exclude IMG_0003 --reason \"$(printf 'bad\\tflash')\"", {"--reason bad\\x09flash"});
  // Well-formed UTF-8 is text like any other (checked on a run that stops at another option).
  const e2e::CommandResult r = requireRefused("--title 'Estela de Mérida' --sphere 1,1,0", {"--sphere 1,1,0"});
  CHECK_THAT(r.output, !Catch::Contains("--title"));
}

// ---- Checks against the frame: made once the capture's images are known -------------------
// (run::checkRequestAgainstFrame, called by runCapture after the capture scan.)

TEST_CASE("a circle given by hand with its centre outside the frame is refused") {
  requireRefused("--sphere 900,57,45 --reason typo", {"--sphere 900,57,45", "400x300"});
  requireRefused("--sphere 339,300,45 --reason typo", {"--sphere 339,300,45", "400x300"});
}

TEST_CASE("a circle given by hand larger than the frame allows is refused") {
  requireRefused("--sphere 339,57,400 --reason typo", {"--sphere 339,57,400", "150"});
}

TEST_CASE("a sphere search region reaching outside the frame is refused") {
  requireRefused("--sphere-roi 500,0,100,100", {"--sphere-roi 500,0,100,100", "400x300"});
  requireRefused("--sphere-roi 350,0,100,100", {"--sphere-roi 350,0,100,100", "400x300"});
}

TEST_CASE("a highlight given by hand outside the frame or off its given circle is refused") {
  requireRefused("--highlight IMG_0004:0=900,70 --reason typo", {"--highlight IMG_0004:sphere1=900,70", "400x300"});
  requireRefused("--sphere 339,57,45 --reason moved --highlight IMG_0004:0=100,200 --reason typo",
                 {"--highlight IMG_0004:sphere1=100,200", "339,57,45"});
  requireRefused("--sphere 339,57,45 --reason moved --highlight IMG_0004:1=330,60 --reason typo",
                 {"--highlight IMG_0004:sphere2=330,60", "names sphere 2, but only 1 circle(s)"});
}

TEST_CASE("too few photographs for a basis: the message names the basis used and suggests one that fits") {
  // No --basis given: the default ptm-lrgb (6 terms) cannot fit the 4 photographs left; hsh2 can.
  const auto byDefault = requireRefused("--exclude IMG_0001 --reason a --exclude IMG_0002 --reason b --exclude "
                                        "IMG_0003 --reason c --exclude IMG_0004 --reason d",
                                        {"the default basis ptm-lrgb (no --basis given)", "has 4 once 4 excluded",
                                         "(--basis hsh2)"});
  CHECK(byDefault.exitCode == 2);
  CHECK_THAT(byDefault.output, !Catch::Contains("--basis ptm-lrgb"));  // once said "e.g. --basis ptm-lrgb"
  // Given: named as given, and the suggestion is another basis, never the refused one.
  const auto given = requireRefused("--basis hsh3", {"--basis hsh3: fits 9 coefficients", "has 8", "(--basis ptm-lrgb)"});
  CHECK(given.output.find("--basis hsh3") == given.output.rfind("--basis hsh3"));
  // Fewer than any basis needs: no basis suggested.
  const auto none = requireRefused("--basis hsh2 --exclude IMG_0001 --reason a --exclude IMG_0002 --reason b --exclude "
                                   "IMG_0003 --reason c --exclude IMG_0004 --reason d --exclude IMG_0005 --reason e",
                                   {"--basis hsh2: fits 4 coefficients", "No basis fits fewer than 4 photographs"});
  CHECK(none.output.find("--basis", none.output.find("fits 4")) == std::string::npos);
}

TEST_CASE("surrogate fit names the basis it would use when the .lp has too few photographs") {
  const fs::path dir = e2e::freshDir("fit-few");
  const fs::path capture = e2e::smallCapture(dir);
  const fs::path lp = dir / "four.lp";
  {
    std::ofstream out(lp);
    out << "4\n";
    for (int i = 1; i <= 4; ++i)
      out << (capture / ("jpeg-exports/IMG_000" + std::to_string(i) + ".jpg")).string() << " 0.1 0.2 0.97\n";
  }
  const auto ptm = e2e::surrogate("fit --lp " + e2e::quote(lp) + " -o " + e2e::quote(dir / "m.ptm"));
  INFO(ptm.output);
  CHECK(ptm.exitCode == 2);
  CHECK_THAT(ptm.output, Catch::Contains("the default basis ptm-lrgb of a .ptm file (no --basis given)") &&
                             Catch::Contains("lists 4") && Catch::Contains("--basis hsh2"));
  const auto hsh3 = e2e::surrogate("fit --lp " + e2e::quote(lp) + " -o " + e2e::quote(dir / "m.rti") + " --basis hsh3");
  INFO(hsh3.output);
  CHECK(hsh3.exitCode == 2);
  CHECK_THAT(hsh3.output, Catch::Contains("--basis hsh3: fits 9 coefficients") && Catch::Contains("--basis hsh2"));
  CHECK_FALSE(fs::exists(dir / "m.ptm"));
}

TEST_CASE("a crop or grey region reaching outside the frame is refused before any processing") {
  requireRefused("--crop 0,100,250,250", {"--crop 0,100,250,250", "400x300"});
  requireRefused("--wb-region 380,200,60,60", {"--wb-region 380,200,60,60", "400x300"});
}

// ---- The stages check again: a recorded carrier never went through the command line ------

namespace {

// The light estimation of the small capture recorded with its sphere given by hand, the
// perspective model and a highlight given by hand; `change` edits the record, which is then
// re-executed on a copy of the capture's originals. Returns the error that stopped it.
Error replayedError(const std::function<void(carrier::Carrier&)>& change) {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("option-checks-replay"));
  const e2e::CommandResult r = e2e::surrogate(
      "lights " + e2e::quote(capture) + " -o " + e2e::quote(capture.parent_path() / "lights.lp") +
      " --quiet --sphere 339,57,45 --reason 'given' --highlight IMG_0004:0=330,50 --reason 'given'"
      " --light-model perspective --focal-length 50 --pixel-pitch 0.006");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  change(c);
  const fs::path again = e2e::freshDir("option-checks-replayed") / "capture";
  fs::create_directories(again);
  for (const char* dir : {"original-captures", "jpeg-exports"})
    fs::copy(capture / dir, again / dir, fs::copy_options::recursive);
  try {
    run::replayCarrier(again, c, pipeline::RunSettings{});
  } catch (const Error& e) {
    return e;
  }
  FAIL("the re-execution of the changed carrier succeeded");
  return Error(ErrorKind::Internal, "", "", "");
}

carrier::Intervention& interventionOf(carrier::Carrier& c, const std::string& kind) {
  for (carrier::Step& s : c.process)
    for (carrier::Intervention& i : s.interventions)
      if (i.kind == kind) return i;
  FAIL("no intervention " << kind);
  throw std::logic_error("unreachable");
}

carrier::Step& stepOf(carrier::Carrier& c, const std::string& component) {
  for (carrier::Step& s : c.process)
    if (s.component == component) return s;
  FAIL("no step " << component);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("a recorded circle outside the frame or with a radius below 0 stops re-execution as bad input") {
  for (const std::string value : {"900,57,45", "339,57,-5", "339,57,400"}) {
    const Error e = replayedError([&](carrier::Carrier& c) { interventionOf(c, "manual-sphere").value = value; });
    INFO(e.what());
    CHECK(e.kind() == ErrorKind::Input);
    CHECK_THAT(e.file(), Catch::Contains(value));
  }
}

TEST_CASE("a recorded highlight off its sphere stops re-execution as bad input") {
  const Error e = replayedError([](carrier::Carrier& c) { interventionOf(c, "manual-highlight").value = "100,200"; });
  INFO(e.what());
  CHECK(e.kind() == ErrorKind::Input);
  CHECK_THAT(e.file(), Catch::Contains("100,200"));
}

TEST_CASE("a recorded focal length that gives no finite light direction stops re-execution and names it") {
  const Error e = replayedError([](carrier::Carrier& c) { stepOf(c, "LightDirections").setParam("focalLengthMm", "1e20"); });
  INFO(e.what());
  CHECK(e.kind() == ErrorKind::Input);
  CHECK_THAT(e.message(), Catch::Contains("focal length"));
  const Error n = replayedError([](carrier::Carrier& c) { stepOf(c, "LightDirections").setParam("pixelPitchMm", "nan"); });
  INFO(n.what());
  CHECK(n.kind() == ErrorKind::Input);
  CHECK_THAT(n.file(), Catch::Contains("pixelPitchMm"));
}
