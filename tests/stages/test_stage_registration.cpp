// A stage describes itself in one place (pipeline::StageInfo): a stage added here, by one
// registration line, is planned, recorded and run like the built-in ones; and a bad parameter
// value in a recorded step is an Error the runner records as the step's failure.
#include <catch2/catch.hpp>

#include <filesystem>

#include "carrier/carrier.h"
#include "core/error.h"
#include "pipeline/context.h"
#include "pipeline/runner.h"
#include "pipeline/stage.h"
#include "run/plan.h"
#include "stages/registry.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

// The options of the no-op stage: one text parameter, recorded like any other.
struct NoOpOptions {
  std::string note = "nothing";  // written back into the result, so a test sees it arrive

  pipeline::Parameters toParameters() const { return {{"note", note}}; }
  static NoOpOptions fromParameters(const pipeline::Parameters& parameters) {
    NoOpOptions o;
    for (const auto& [name, value] : parameters) {
      if (name != "note") throw Error(ErrorKind::Input, name + "=" + value, "no-op", "is not a parameter of TestNoOp");
      o.note = value;
    }
    return o;
  }
};

class NoOpStage : public pipeline::DescribedStage<NoOpStage> {
 public:
  static pipeline::StageInfo info() {
    return pipeline::withOptions<NoOpOptions>(
        {"TestNoOp", "1", "Does nothing: a test of stage registration", pipeline::PlanSlot::AfterModels});
  }
  void run(const carrier::Step& step, pipeline::Context&, carrier::Result& result) override {
    pipeline::Parameters params;
    for (const carrier::Param& p : step.params) params.emplace_back(p.name, p.value);
    result.add("value").set("name", "note").set("value", NoOpOptions::fromParameters(params).note);
  }
};

void registerNoOp() {
  stages::registerBuiltinStages();
  static const bool once = (pipeline::StageRegistry::instance().add<NoOpStage>(), true);
  (void)once;
}

// A carrier of one step of `component` with the parameters given, run without a capture.
carrier::Carrier runOneStep(const std::string& component, const pipeline::Parameters& params,
                            const fs::path& carrierPath = {}) {
  carrier::Carrier c = carrier::newCarrier("one step", {});
  carrier::Step& s = c.addStep(component, pipeline::StageRegistry::instance().create(component)->version());
  for (const auto& [name, value] : params) s.setParam(name, value);
  pipeline::Context ctx(fs::temp_directory_path(), c, pipeline::RunSettings{});
  pipeline::runProcess(ctx, carrierPath);
  return c;
}

}  // namespace

TEST_CASE("a stage registered by one line is planned in its slot with its description and defaults", "[stages][registry]") {
  registerNoOp();
  run::RunRequest request;
  request.stageParams.push_back({"TestNoOp", "note", "given"});
  const carrier::Carrier c = run::planRun(SURROGATE_SOURCE_DIR, request);
  REQUIRE(c.process.size() >= 2);
  const carrier::Step& last = c.process.back();  // AfterModels: after DerivedMaps
  CHECK(last.component == "TestNoOp");
  CHECK(c.process[c.process.size() - 2].component == "DerivedMaps");
  CHECK(last.version == "1");
  CHECK(last.description == "Does nothing: a test of stage registration");
  CHECK(last.param("note") == "given");
  // A parameter equal to its default is no decision; another one stands for the next run.
  const run::RunRequest standing = run::standingDecisions(c);
  bool stands = false;
  for (const auto& p : standing.stageParams) stands = stands || (p.component == "TestNoOp" && p.value == "given");
  CHECK(stands);
}

TEST_CASE("a stage registered by one line runs from a carrier with its recorded parameters", "[stages][registry]") {
  registerNoOp();
  const carrier::Carrier c = runOneStep("TestNoOp", {{"note", "recorded"}});
  REQUIRE(c.data.size() == 1);
  CHECK(c.data[0].status == "completed");
  CHECK(c.data[0].items[0].get("value") == std::string("recorded"));
}

TEST_CASE("built-in stages keep their recorded names, versions and default parameters", "[stages][registry]") {
  stages::registerBuiltinStages();
  const auto& r = pipeline::StageRegistry::instance();
  // What existing carriers record: changing any of these makes old packages fail verification.
  const std::vector<std::pair<std::string, std::string>> versions = {
      {"CaptureIngest", "3"}, {"ImageDecode", "3"}, {"SphereDetection", "9"}, {"HighlightDetection", "12"},
      {"LightDirections", "7"}, {"LightsFromFile", "4"}, {"WhiteBalance", "1"}, {"Crop", "1"},
      {"Resize", "1"}, {"RtiFit", "8"}, {"LearnedFit", "1"}, {"DerivedMaps", "5"}, {"WebCopy", "4"}, {"Audit", "7"},
      {"ColourCorrection", "1"}};
  for (const auto& [component, version] : versions) {
    INFO(component);
    REQUIRE(r.info(component));
    CHECK(r.info(component)->version == version);
    CHECK(r.create(component)->version() == version);
    CHECK(r.runsAsRecorded(component, version));
  }
  // Older versions still run as they ran: HighlightDetection 11 (cv::phaseCorrelate) and RtiFit 7
  // (its errors in double precision).
  for (const pipeline::StageInfo* info : r.stages())
    CHECK(info->alsoRuns == (info->component == "HighlightDetection" ? std::vector<std::string>{"11"}
                             : info->component == "RtiFit"           ? std::vector<std::string>{"7"}
                                                                     : std::vector<std::string>{}));
  CHECK(r.runsAsRecorded("HighlightDetection", "11"));
  CHECK(r.runsAsRecorded("RtiFit", "7"));
  CHECK_FALSE(r.runsAsRecorded("RtiFit", "6"));
  CHECK_FALSE(r.runsAsRecorded("HighlightDetection", "10"));
  CHECK_FALSE(r.runsAsRecorded("SphereDetection", "8"));
  CHECK_FALSE(r.runsAsRecorded("NoSuchStage", "1"));
  CHECK(r.info("ColourCorrection")->defaults ==
        pipeline::Parameters{{"chart", "auto"}, {"corners", ""}, {"reference", "colorchecker-classic-2014"},
                             {"model", "matrix"}});
  CHECK(r.info("LightDirections")->defaults ==
        pipeline::Parameters{{"model", "orthographic"}, {"focalLengthMm", "0"}, {"pixelPitchMm", "0"},
                             {"sphereDiameterMm", "0"}, {"lightDistance", "auto"}});
  CHECK(r.info("DerivedMaps")->defaults == pipeline::Parameters{{"model", "ptm-lrgb"}});
  CHECK(r.info("RtiFit")->defaults == pipeline::Parameters{{"basis", "ptm-lrgb"}});
  CHECK(r.info("LearnedFit")->defaults == pipeline::Parameters{{"basis", "bln"}, {"planes", "45"}, {"resolution", "8"},
                                                              {"quality", "90:40"}, {"holdout", "0"}});
  CHECK(r.info("Audit")->defaults == pipeline::Parameters{{"angleThresholdDegrees", "2"},
                                                         {"reproducedMarginDb", "1"},
                                                         {"differenceImages", ""}});
  // The audit's threshold is that audit's alone, never a standing decision (issue 52).
  CHECK(r.info("Audit")->perCommand == std::vector<std::string>{"angleThresholdDegrees"});
  CHECK(r.info("Crop")->defaults.empty());
  CHECK(r.info("Resize")->defaults.empty());
  CHECK(r.info("LightsFromFile")->defaults == pipeline::Parameters{{"lightDistance", "auto"}});
}

TEST_CASE("a bad parameter value in a recorded step is a failed step naming it, not a crash", "[stages][registry]") {
  stages::registerBuiltinStages();
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-bad-parameter";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const struct {
    const char* component;
    pipeline::Parameters params;
    const char* named;
  } cases[] = {
      {"LightDirections", {{"focalLengthMm", "fifty"}}, "focalLengthMm=fifty"},
      {"LightDirections", {{"pixelPitchMm", "nan"}}, "pixelPitchMm=nan"},
      {"LightDirections", {{"sphereDiameterMm", "-3"}}, "sphereDiameterMm=-3"},
      {"LightDirections", {{"focalLength", "50"}}, "focalLength=50"},
      {"LightDirections", {{"model", "fisheye"}}, "fisheye"},
      {"DerivedMaps", {{"model", "hsh9"}}, "model=hsh9"},
      {"LearnedFit", {{"basis", "bln"}, {"planes", "44"}}, "planes=44"},
      {"RtiFit", {{"basis", "hsh2"}, {"output", "../elsewhere.rti"}}, "../elsewhere.rti"},
      {"Crop", {{"method", "user"}, {"rectangle", "1,2,x,4"}}, "rectangle=1,2,x,4"},
      {"LightsFromFile", {{"file", "dome.lp"}}, "file=dome.lp"},
  };
  for (const auto& t : cases) {
    INFO(t.component << " " << t.named);
    try {
      runOneStep(t.component, t.params, dir / "carrier.xml");
      FAIL("no error");
    } catch (const Error& e) {
      CHECK_THAT(std::string(e.what()), Catch::Contains(t.named));
      CHECK(e.kind() != ErrorKind::Internal);
    }
    const carrier::Carrier saved = carrier::loadCarrier(dir / "carrier.xml");
    REQUIRE(saved.data.size() == 1);
    CHECK(saved.data[0].status == "failed");
    CHECK(saved.log.back().level == "error");
    CHECK_THAT(saved.log.back().text, Catch::Contains(t.named));
  }
  fs::remove_all(dir);
}

TEST_CASE("every built-in stage says what shared data it reads, so the runner can let go of the photographs", "[stages][registry]") {
  stages::registerBuiltinStages();
  for (const pipeline::StageInfo* info : pipeline::StageRegistry::instance().stages()) {
    if (info->component.rfind("Test", 0) == 0) continue;  // stages registered by tests
    INFO(info->component);
    CHECK(static_cast<bool>(info->reads));
  }
}
