// The capture's memory as data: a carrier's standing decisions, and a new command applied to
// them (run/plan.h). Built from carriers written here, not from a run.
#include <catch2/catch.hpp>

#include <algorithm>

#include "carrier/carrier.h"
#include "core/error.h"
#include "run/plan.h"

using namespace surrogate;
using run::RunRequest;

namespace {

// A carrier as three earlier runs would leave it: a title, a creator and metadata, an
// exclusion, a sphere given by hand, a threshold, a basis choice and a crop.
carrier::Carrier recorded() {
  carrier::Carrier c = carrier::newCarrier("Stela 12", {{"Ana Silva", "photographer"}});
  c.header.meta = {{"site", "store 3"}};
  carrier::Step& ingest = c.addStep("CaptureIngest", "1");
  ingest.setParam("source", "export");
  ingest.interventions.push_back({"exclude-image", "IMG_0003", "", "Ana Silva", "2026-11-01T10:00:00Z", "no flash"});
  c.addStep("ImageDecode", "1").setParam("demosaic", "AHD");
  carrier::Step& spheres = c.addStep("SphereDetection", "1");
  spheres.interventions.push_back({"manual-sphere", "0", "339,57,45", "Bo Chen", "2026-11-02T10:00:00Z", "cut by the edge"});
  c.addStep("HighlightDetection", "1").setParam("threshold", "0.9");
  c.addStep("LightDirections", "1").setParam("model", "orthographic");  // the default: not a decision
  c.addStep("Crop", "1").setParam("rectangle", "0,0,200,100");
  c.addStep("RtiFit", "1").setParam("basis", "hsh3");
  c.addStep("DerivedMaps", "1").setParam("model", "hsh3");
  return c;
}

}  // namespace

TEST_CASE("a carrier's standing decisions are read back with their who, when and why", "[stages][decisions]") {
  const RunRequest r = run::standingDecisions(recorded());
  CHECK(r.title == "Stela 12");
  REQUIRE(r.creators.size() == 1);
  CHECK(r.creators[0].role == "photographer");
  CHECK(r.source == "export");
  REQUIRE(r.exclusions.size() == 1);
  CHECK(r.exclusions[0].who == "Ana Silva");
  CHECK(r.exclusions[0].time == "2026-11-01T10:00:00Z");
  CHECK(r.exclusions[0].reason == "no flash");
  REQUIRE(r.stageInterventions.size() == 1);
  CHECK(r.stageInterventions[0].component == "SphereDetection");
  CHECK(r.stageInterventions[0].intervention.who == "Bo Chen");
  // Only parameters that differ from the stage's defaults are decisions.
  bool threshold = false, model = false;
  for (const auto& p : r.stageParams) {
    threshold = threshold || (p.component == "HighlightDetection" && p.name == "threshold" && p.value == "0.9");
    model = model || p.component == "LightDirections";
  }
  CHECK(threshold);
  CHECK_FALSE(model);
  REQUIRE(r.preprocessing.size() == 1);
  CHECK(r.preprocessing[0].component == "Crop");
  REQUIRE(r.bases);
  CHECK(*r.bases == std::vector<std::string>{"hsh3"});
}

TEST_CASE("a new command adds to and overrides the standing decisions, and says what changed", "[stages][decisions]") {
  RunRequest given;
  given.exclusions.push_back({"original-captures/IMG_0005.dng", "blurred", "", ""});
  given.exclusions.push_back({"IMG_0003.jpg", "still no flash", "", ""});  // the same shot as IMG_0003
  given.stageInterventions.push_back({"SphereDetection", {"manual-sphere", "0", "340,58,44", "", "", "refined"}});
  given.meta = {{"site", "store 4"}, {"project", "stelae"}};
  given.creators = {{"Bo Chen", "conservator"}};
  std::vector<std::string> changes;
  const RunRequest r = run::applyDecisions(run::standingDecisions(recorded()), given, changes);
  CHECK(r.title == "Stela 12");  // kept
  CHECK(r.creators.size() == 2);
  REQUIRE(r.meta.size() == 2);
  CHECK(r.meta[0] == std::make_pair(std::string("site"), std::string("store 4")));
  REQUIRE(r.exclusions.size() == 2);
  CHECK(r.exclusions[0].reason == "still no flash");
  REQUIRE(r.stageInterventions.size() == 1);
  CHECK(r.stageInterventions[0].intervention.value == "340,58,44");
  REQUIRE(r.bases);
  CHECK(*r.bases == std::vector<std::string>{"hsh3"});  // kept: not given
  CHECK(r.source == "export");
  bool replacedSphere = false;
  for (const std::string& c : changes) replacedSphere = replacedSphere || c.find("replaced the circle by hand of sphere1 (339,57,45") != std::string::npos;
  CHECK(replacedSphere);
}

TEST_CASE("withdrawing a decision is explicit, and one that does not stand is refused", "[stages][decisions]") {
  RunRequest given;
  given.withdrawals.push_back({"exclude-image", "IMG_0003.dng", "the flash fired after all"});
  given.withdrawals.push_back({"manual-sphere", "0", "detection is right"});
  std::vector<std::string> changes;
  const RunRequest r = run::applyDecisions(run::standingDecisions(recorded()), given, changes);
  CHECK(r.exclusions.empty());
  CHECK(r.stageInterventions.empty());
  REQUIRE(changes.size() == 2);
  CHECK_THAT(changes[0], Catch::Contains("the flash fired after all"));
  CHECK_THAT(changes[0], Catch::Contains("Ana Silva"));

  RunRequest wrong;
  wrong.withdrawals.push_back({"manual-highlight", "IMG_0004:0", "x"});
  CHECK_THROWS_AS(run::applyDecisions(run::standingDecisions(recorded()), wrong, changes), Error);
}

TEST_CASE("a reset withdraws every processing decision but keeps the header and accepted changes", "[stages][decisions]") {
  carrier::Carrier c = recorded();
  c.process[0].interventions.push_back({"accept-changed-original", "original-captures/IMG_0005.dng", "removed", "Ana Silva",
                                        "2026-11-03T10:00:00Z", "lost card"});
  RunRequest given;
  given.resetReason = "start again";
  std::vector<std::string> changes;
  const RunRequest r = run::applyDecisions(run::standingDecisions(c), given, changes);
  CHECK(r.title == "Stela 12");
  CHECK(r.meta.size() == 1);
  CHECK(r.exclusions.empty());
  CHECK(r.stageParams.empty());
  CHECK(r.preprocessing.empty());
  CHECK_FALSE(r.bases);
  CHECK(r.source.empty());
  REQUIRE(r.stageInterventions.size() == 1);
  CHECK(r.stageInterventions[0].intervention.kind == "accept-changed-original");
  REQUIRE(changes.size() == 1);
  CHECK_THAT(changes[0], Catch::Contains("start again"));
}

TEST_CASE("a dome .lp with sphere decisions standing is refused, naming the conflict", "[stages][decisions]") {
  RunRequest given;
  given.lp = "dome.lp";
  std::vector<std::string> changes;
  try {
    run::applyDecisions(run::standingDecisions(recorded()), given, changes);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK_THAT(e.message(), Catch::Contains("circle by hand of sphere1"));
  }
}

TEST_CASE("an accepted damaged image stands across runs until withdrawn, with its who, when and why", "[stages][decisions]") {
  carrier::Carrier c = recorded();
  for (carrier::Step& s : c.process)
    if (s.component == "ImageDecode")
      s.interventions.push_back({"accept-decoder-warning", "jpeg-exports/IMG_0004.jpg", "sha256:ab12", "Ana Silva",
                                 "2026-11-03T10:00:00Z", "the only frame of this light"});
  const RunRequest standing = run::standingDecisions(c);
  bool found = false;
  for (const auto& i : standing.stageInterventions)
    if (i.component == "ImageDecode" && i.intervention.kind == "accept-decoder-warning") {
      found = true;
      CHECK(i.intervention.who == "Ana Silva");
      CHECK(i.intervention.time == "2026-11-03T10:00:00Z");
      CHECK(i.intervention.value == "sha256:ab12");
    }
  CHECK(found);
  // A run with other options keeps it; planRun puts it on the ImageDecode step.
  std::vector<std::string> changes;
  RunRequest next = run::applyDecisions(standing, RunRequest{}, changes);
  const carrier::Carrier planned = run::planRun(SURROGATE_SOURCE_DIR, next);
  bool onDecode = false;
  for (const carrier::Step& s : planned.process)
    for (const carrier::Intervention& i : s.interventions)
      onDecode = onDecode || (s.component == "ImageDecode" && i.kind == "accept-decoder-warning" &&
                              i.target == "jpeg-exports/IMG_0004.jpg" && i.who == "Ana Silva");
  CHECK(onDecode);
  // Withdrawn by the shot's name, with a reason that goes into the history.
  RunRequest withdraw;
  withdraw.withdrawals.push_back({"accept-decoder-warning", "IMG_0004", "re-shot"});
  changes.clear();
  const RunRequest after = run::applyDecisions(standing, withdraw, changes);
  for (const auto& i : after.stageInterventions) CHECK(i.intervention.kind != "accept-decoder-warning");
  REQUIRE_FALSE(changes.empty());
  CHECK_THAT(changes.back(), Catch::Contains("accepted damage in jpeg-exports/IMG_0004.jpg") && Catch::Contains("re-shot"));
  // Withdrawing one that is not there names the option.
  RunRequest none;
  none.withdrawals.push_back({"accept-decoder-warning", "IMG_0009", "typo"});
  try {
    run::applyDecisions(standing, none, changes);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK_THAT(e.file(), Catch::Contains("--forget-damaged"));
  }
}

TEST_CASE("numbers from an older carrier's 17 digits are read as the same values in their short form",
          "[stages][decisions]") {
  // Before core/text.h's formatNumber, "%.17g" recorded the default threshold 0.8 as
  // 0.80000000000000004: that is the default, not a decision, and a value given as 0.95 again
  // is no change.
  carrier::Carrier c = carrier::newCarrier("Stela 12", {});
  c.addStep("CaptureIngest", "1");
  c.addStep("HighlightDetection", "2").setParam("threshold", "0.80000000000000004");
  carrier::Step& spheres = c.addStep("SphereDetection", "1");
  spheres.setParam("minConfidence", "0.94999999999999996");
  spheres.setParam("regions", "0,0,200,100");
  c.addStep("Crop", "1").setParam("margin", "0.29999999999999999");
  const RunRequest r = run::standingDecisions(c);
  bool threshold = false, confidence = false;
  for (const auto& p : r.stageParams) {
    threshold = threshold || p.name == "threshold";
    confidence = confidence || (p.name == "minConfidence" && p.value == "0.95");
  }
  CHECK_FALSE(threshold);
  CHECK(confidence);
  REQUIRE(r.preprocessing.size() == 1);
  CHECK(r.preprocessing[0].params == std::vector<std::pair<std::string, std::string>>{{"margin", "0.3"}});

  RunRequest given;
  given.stageParams.push_back({"SphereDetection", "minConfidence", "0.95"});
  std::vector<std::string> changes;
  run::applyDecisions(r, given, changes);
  CHECK(changes.empty());
}

TEST_CASE("a recorded web copy stands with its options and is withdrawn with them", "[stages][decisions]") {
  carrier::Carrier c = recorded();
  for (const char* model : {"hsh3", "hsh3"}) {
    carrier::Step& s = c.addStep("WebCopy", "1");
    s.setParam("model", model);
    s.setParam("quality", "80");
    s.setParam("tiles", "auto");  // the default: not a decision
    s.setParam("tileSize", "256");
  }
  const RunRequest standing = run::standingDecisions(c);
  REQUIRE(standing.publish);
  CHECK(*standing.publish);
  std::vector<std::string> web;
  for (const auto& p : standing.stageParams)
    if (p.component == "WebCopy") web.push_back(p.name + "=" + p.value);
  CHECK(web == std::vector<std::string>{"quality=80"});  // once, though two steps record it

  // Nothing said about it: it stays, and the plan has one step per basis with its quality.
  std::vector<std::string> changes;
  RunRequest kept = run::applyDecisions(standing, RunRequest{}, changes);
  CHECK(kept.publish.value_or(false));
  const auto planned = run::analysisStages(false, kept);
  int steps = 0;
  for (const auto& p : planned)
    if (p.component == "WebCopy") {
      ++steps;
      CHECK(p.params == std::vector<std::pair<std::string, std::string>>{{"model", "hsh3"}});
    }
  CHECK(steps == 1);

  // Withdrawn: its options go too, and options without a web copy are refused.
  RunRequest off;
  off.publish = false;
  changes.clear();
  const RunRequest withdrawn = run::applyDecisions(standing, off, changes);
  CHECK_FALSE(withdrawn.publish.value_or(false));
  for (const auto& p : withdrawn.stageParams) CHECK(p.component != "WebCopy");
  CHECK(changes == std::vector<std::string>{"no web copy any more"});
  RunRequest quality;
  quality.stageParams.push_back({"WebCopy", "quality", "50"});
  CHECK_THROWS_AS(run::applyDecisions(withdrawn, quality, changes), Error);
}

// Issue 52: an audit's threshold was kept as a standing decision, so that the same `audit PRIOR`
// later answered otherwise without saying why. It is that audit's only: a carrier whose Audit
// step records one (as every carrier did) loads, and the next run plans the default; the other
// Audit parameters stand as before.
TEST_CASE("an audit's threshold is no standing decision and a carrier recording one still loads", "[stages][decisions]") {
  carrier::Carrier c = recorded();
  carrier::Step& audit = c.addStep("Audit", "6");
  audit.setParam("angleThresholdDegrees", "15");
  audit.setParam("reproducedMarginDb", "3");
  const RunRequest standing = run::standingDecisions(c);
  for (const auto& p : standing.stageParams) CHECK(p.name != "angleThresholdDegrees");
  bool margin = false;
  for (const auto& p : standing.stageParams) margin = margin || (p.component == "Audit" && p.name == "reproducedMarginDb");
  CHECK(margin);

  // Given again, it goes to this run's step, and the history says it is for this run only.
  RunRequest given;
  given.stageParams.push_back({"Audit", "angleThresholdDegrees", "5"});
  std::vector<std::string> changes;
  const RunRequest r = run::applyDecisions(standing, given, changes);
  CHECK(std::count_if(r.stageParams.begin(), r.stageParams.end(),
                      [](const auto& p) { return p.name == "angleThresholdDegrees" && p.value == "5"; }) == 1);
  CHECK(changes == std::vector<std::string>{"Audit angleThresholdDegrees = 5 (this run only)"});
}
