// Issue 52 (an audit that knows its own error): prior work on real photographs (PSBox
// LightProbe-1, tests/data/real-rti/SOURCE.md) laid out as RTIBuilder leaves it: the set's
// reference lights as an .lp and a PTM fitted to them by `surrogate fit`. A light differs only
// beyond both the two lights' combined uncertainty and the threshold, and the verdict names both;
// a threshold given to one audit is that audit's alone.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../audit/prior_rti.h"
#include "e2e_support.h"
#include "real_sets.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kImages = 12;
// The light moved in the prior that must be named, and by how much.
constexpr int kMoved = 2;  // Image_03
constexpr double kMoveDegrees = 10;
// Surrogate's lights on this set are 1 to 2.5 degrees from the references (docs/hrti-math.md):
// the distance to a light moved by 10 degrees lies within this of 10.
constexpr double kOurError = 3;

fs::path probeSet() { return e2e::realData("lightprobe-1"); }

// PSBox's reference lights, y up as in an .lp.
std::vector<test::Light> referenceLights() {
  std::vector<test::Light> out = e2e::psboxLights("lightprobe-1");
  REQUIRE(out.size() == kImages);
  return out;
}

std::string imageName(int i) { return std::string("Image_") + (i < 9 ? "0" : "") + std::to_string(i + 1) + ".JPG"; }

// The set's photographs in jpeg-exports/, and the prior work RTIBuilder would leave: the
// reference lights as assembly-files/probe.lp (Windows paths, CRLF), light `moved` (-1: none)
// raised by kMoveDegrees, and finished-files/probe.ptm fitted to that .lp by `surrogate fit`
// outside the capture, then put where RTIBuilder writes it.
fs::path probeCapture(const std::string& name, int moved) {
  const fs::path dir = e2e::freshDir(name);
  const fs::path capture = dir / "capture";
  for (const char* folder : {"jpeg-exports", "assembly-files", "finished-files"}) fs::create_directories(capture / folder);
  for (int i = 0; i < kImages; ++i) fs::copy_file(probeSet() / imageName(i), capture / "jpeg-exports" / imageName(i));
  std::ostringstream lp;
  lp.precision(9);
  lp << kImages << "\r\n";
  const std::vector<test::Light> reference = referenceLights();
  for (int i = 0; i < kImages; ++i) {
    const test::Light l = i == moved ? test::tilted(reference[i], kMoveDegrees) : reference[i];
    lp << "jpeg-exports\\" << imageName(i) << " " << l[0] << " " << l[1] << " " << l[2] << "\r\n";
  }
  test::writeText((capture / "assembly-files" / "probe.lp").string(), lp.str());
  const e2e::CommandResult fit = e2e::surrogate("fit --lp " + e2e::quote(capture / "assembly-files" / "probe.lp") +
                                                " -o " + e2e::quote(dir / "probe.ptm") + " --quiet");
  INFO(fit.output);
  REQUIRE(fit.exitCode == 0);
  fs::rename(dir / "probe.ptm", capture / "finished-files" / "probe.ptm");
  return capture;
}

std::string partFigure(const std::string& json, const std::string& part) {
  const std::regex figure("\\{\"part\":\"" + part + "\",\"state\":\"([a-z ]+)\",\"figure\":\"([^\"]*)\"");
  std::smatch m;
  REQUIRE(std::regex_search(json, m, figure));
  return m[1].str() + ": " + m[2].str();
}

}  // namespace

// Before: one reference light 2.3 degrees from Surrogate's against the 2.0-degree threshold made
// the audit say NOT REPRODUCED, exit 4, though the prior's model was as good as Surrogate's
// (29.01 against 28.98 dB) and the 2.3 degrees were Surrogate's own error.
TEST_CASE("a correct prior of real photographs is reproduced, its lights judged within their uncertainty",
          "[e2e][audit]") {
  const fs::path capture = probeCapture("audit-probe", -1);
  const e2e::CommandResult r = e2e::surrogate("audit " + e2e::quote(capture) + " --json -o " +
                                              e2e::quote(capture.parent_path() / "work"));
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK(r.output.rfind("{\"reproduced\":true,\"exitCode\":0,", 0) == 0);
  const std::string lights = partFigure(r.output, "lights");
  INFO(lights);
  CHECK(lights.rfind("reproduced: all 12 lights agree with Surrogate's", 0) == 0);
  CHECK(partFigure(r.output, "model").rfind("reproduced: ", 0) == 0);
  // The verdict names the largest distance with Surrogate's uncertainty (a number: each light
  // of this run states one), the prior's (an .lp states none) and the threshold.
  CHECK(std::regex_search(lights, std::regex("largest Image_[0-9]{2}\\.JPG: [0-9.]+ deg apart; within (the threshold "
                                             "2\\.0 deg, beyond )?the combined uncertainty [0-9.]+ deg \\(ours "
                                             "[0-9]+\\.[0-9], the prior states none\\)(; threshold 2\\.0 deg)?\\)")));
  // Every light: its distance within the threshold or the combined uncertainty, which is ours.
  const std::regex angle("\\{\"image\":\"(Image_[0-9]{2}\\.JPG)\",\"degrees\":([0-9.]+),\"uncertaintyDegrees\":([0-9.]+),"
                         "\"ourUncertaintyDegrees\":([0-9.]+),\"priorUncertaintyDegrees\":null,\"differs\":false");
  const std::string all = r.output.substr(r.output.find("\"angles\":["));
  int judged = 0;
  for (std::sregex_iterator it(all.begin(), all.end(), angle), end; it != end; ++it, ++judged) {
    INFO((*it)[1]);
    CHECK(std::stod((*it)[2]) <= std::max(2.0, std::stod((*it)[3])) + 0.05);  // rounded to 0.1
    CHECK((*it)[3] == (*it)[4]);
  }
  CHECK(judged == kImages);
}

// A prior light moved by 10 degrees is beyond any uncertainty: named with its distance, the
// uncertainty and the threshold. A threshold given once is shown and used by that audit alone;
// before, it stood: the same `audit PRIOR` later answered REPRODUCED without saying why. The
// carrier of the audit given --threshold records it in its Audit step as carriers always did,
// so the later audit also shows what becomes of an older carrier holding one.
TEST_CASE("a prior light moved 10 degrees is named, and a threshold given once is that audit's only", "[e2e][audit]") {
  const fs::path capture = probeCapture("audit-probe-moved", kMoved);
  const fs::path work = capture.parent_path() / "work";
  const std::string audit = "audit " + e2e::quote(capture) + " -o " + e2e::quote(work);
  const std::regex named(imageName(kMoved) + ": ([0-9.]+) deg apart; beyond the combined uncertainty ([0-9.]+) deg "
                         "\\(ours [0-9]+\\.[0-9], the prior states none\\) and the threshold 2\\.0 deg");

  const e2e::CommandResult r = e2e::surrogate(audit + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK(r.output.find(": not reproduced (exit 4; threshold 2.0 deg); " + imageName(kMoved) + ": ") != std::string::npos);
  std::smatch m;
  REQUIRE(std::regex_search(r.output, m, named));
  CHECK(std::stod(m[1]) == Approx(kMoveDegrees).margin(kOurError));
  CHECK(std::stod(m[2]) < std::stod(m[1]));

  const e2e::CommandResult wide = e2e::surrogate(audit + " --quiet --threshold 15");
  INFO(wide.output);
  CHECK(wide.exitCode == 0);
  CHECK(wide.output.find(": reproduced (exit 0; threshold 15.0 deg)") != std::string::npos);
  CHECK(e2e::bytesOf(work / "assembly-files" / "carrier.xml").find("<param name=\"angleThresholdDegrees\" value=\"15\"/>") !=
        std::string::npos);
  // Not a standing choice of the work folder: its run history says it was that run's only.
  const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(work) + " --json");
  INFO(info.output);
  CHECK(info.output.find("\"options\":[]") != std::string::npos);
  CHECK(info.output.find("Audit angleThresholdDegrees = 15 (this run only)") != std::string::npos);

  // Asked again without it: judged at the default, run again, and every verdict line says so.
  const e2e::CommandResult again = e2e::surrogate(audit);
  INFO(again.output);
  CHECK(again.exitCode == 4);
  CHECK(again.output.rfind("NOT REPRODUCED  finished-files/probe.ptm with the lights of assembly-files/probe.lp "
                           "(threshold 2.0 deg)\n  lights     differs     1 of 12 images differ by more than both "
                           "their combined uncertainty and the threshold 2.0 degrees: ", 0) == 0);
  CHECK(std::regex_search(again.output, named));
  CHECK(again.output.find(", just run; threshold 2.0 degrees") != std::string::npos);
  CHECK(e2e::bytesOf(work / "assembly-files" / "carrier.xml").find("<param name=\"angleThresholdDegrees\" value=\"2\"/>") !=
        std::string::npos);
}
