// Every warning of a run says whether the result is usable and what to do, in plain words,
// with the figure as detail (issue 56, item 2; src/core/advice.h). Captures made to raise the
// warnings a first real run meets: XMP sidecars that are not XML, photographs processed by
// other software (--source export on a capture with originals), and a capture whose PTM has no maximum in part of the frame (the normal map's
// fallback, half the pixels on the first real DNG capture the issue ran). The carrier is read
// by the carrier library, the words are matched by a regular expression written here.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>

#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

std::vector<surrogate::carrier::LogEntry> warningsOf(const fs::path& capture) {
  std::vector<surrogate::carrier::LogEntry> out;
  for (const surrogate::carrier::LogEntry& e : surrogate::carrier::loadCarrier(capture / "assembly-files/carrier.xml").log)
    if (e.level == "warning") out.push_back(e);
  return out;
}

// "WHAT. Usable[ with care]|Not usable[: WHY]. What to do: TODO.[ (DETAIL)]"
void requireAdvice(const std::string& text) {
  static const std::regex advice(R"(^[^\n]+\. (Usable|Usable with care|Not usable)(: [^\n]+)?\. What to do: [^\n]+\.( \([^\n]+\))?$)");
  INFO(text);
  CHECK(std::regex_match(text, advice));
}

}  // namespace

TEST_CASE("each warning of a run says whether the result is usable and what to do", "[e2e][warnings]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("warning-words"), 8);
  std::ofstream(capture / "original-captures/IMG_0002.xmp") << "this is not XMP\n";
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --source export --no-report");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const auto warnings = warningsOf(capture);
  // The damaged sidecar and the exports' unrecorded processing at least.
  REQUIRE(warnings.size() >= 2);
  bool sidecar = false, exports = false;
  for (const auto& w : warnings) {
    requireAdvice(w.text);
    sidecar = sidecar || w.text.find("IMG_0002.xmp: the XMP sidecar cannot be read") != std::string::npos;
    exports = exports || (w.text.find("processed by other software") != std::string::npos &&
                          w.text.find("--source original") != std::string::npos);
  }
  CHECK(sidecar);
  CHECK(exports);
  // Where the user looks: the run's own output carries the same words.
  CHECK_THAT(r.output, Contains("What to do: "));
}

TEST_CASE("the normal map fallback warning says the map is usable and how to compare with HSH", "[e2e][warnings]") {
  // Dust, glare and a mirrored room: a PTM with no maximum in more than 5 % of the frame.
  const fs::path capture = e2e::generatedWithTruth(
      "warning-fallback", "--images 16 --width 600 --height 400 --formats jpeg --glare 0.5 --dust 5 --reflections");
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --no-report --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  bool fallback = false;
  for (const auto& w : warningsOf(capture)) {
    requireAdvice(w.text);
    if (w.text.find("no valid PTM maximum") == std::string::npos) continue;
    fallback = true;
    CHECK_THAT(w.text, Contains(". Usable: the normal map is complete"));
    CHECK_THAT(w.text, Contains("--basis hsh2 --basis ptm-lrgb"));
    // The figure as detail: "(N pixels (P %) had no valid PTM maximum ...)".
    CHECK(std::regex_search(w.text, std::regex(R"(\(\d+ pixels \(\d+\.\d\d %\) had no valid PTM maximum)")));
  }
  REQUIRE(fallback);
  // The advice holds: with hsh2 named first, the normals come from the HSH fit, and its
  // warning (if any) is not about PTM maxima.
  const e2e::CommandResult again =
      e2e::surrogate("run " + e2e::quote(capture) + " --no-report --quiet --basis hsh2 --basis ptm-lrgb");
  INFO(again.output);
  REQUIRE(again.exitCode == 0);
  const surrogate::carrier::Carrier c = surrogate::carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  bool fromHsh = false;
  for (const surrogate::carrier::Step& s : c.process)
    if (s.component == "DerivedMaps") fromHsh = s.param("model", "") == "hsh2";
  CHECK(fromHsh);
  for (const auto& w : warningsOf(capture)) CHECK(w.text.find("no valid PTM maximum") == std::string::npos);
}
