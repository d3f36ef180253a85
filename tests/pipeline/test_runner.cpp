#include <catch2/catch.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <vector>
#include <string>

#include "pipeline/context.h"
#include "pipeline/runner.h"
#include "pipeline/stage.h"
#include "core/text.h"

using namespace surrogate;
using namespace surrogate::pipeline;
namespace fs = std::filesystem;

namespace {

// Doubles the "value" parameter and passes it on through the blackboard.
class DoublingStage : public Stage {
 public:
  std::string component() const override { return "TestDoubling"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, Context& ctx, carrier::Result& result) override {
    double v = std::stod(step.param("value", "1"));
    if (ctx.has("last")) v += *ctx.get<double>("last");
    result.add("value").set("name", "doubled").set("value", formatNumber(2 * v));
    ctx.put("last", std::make_shared<double>(2 * v));
  }
};

class FailingStage : public Stage {
 public:
  std::string component() const override { return "TestFailing"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, Context&, carrier::Result&) override {
    throwInputError("IMG_0001.jpg", "test", "is broken");
  }
};

// Reports the start of two parts of its work and a milestone of the second, not their ends;
// with the "fail" parameter, stops after the first part's start.
class ReportingStage : public Stage {
 public:
  std::string component() const override { return "TestReporting"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, Context& ctx, carrier::Result&) override {
    ctx.progress("Reading", 0);
    if (step.hasParam("fail")) throwInputError("IMG_0001.jpg", "test", "is broken");
    ctx.progress("Measuring", 0);
    ctx.progress("Measuring", 0.5);
  }
};

// A value that says when it is freed.
struct Tracked {
  explicit Tracked(bool* freed) : freed(freed) {}
  ~Tracked() { *freed = true; }
  bool* freed;
};

// Puts a Tracked under "tracked" (parameter "put"), or reads it and records whether it was
// there; declares that it reads "tracked" only when its "reads" parameter is "yes".
bool gTrackedFreed = false;
class TrackingStage : public Stage {
 public:
  std::string component() const override { return "TestTracking"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, Context& ctx, carrier::Result& result) override {
    result.add("value").set("name", "freedBefore").set("value", gTrackedFreed ? "yes" : "no");
    if (step.hasParam("put")) ctx.put("tracked", std::make_shared<Tracked>(&gTrackedFreed));
    else if (step.param("reads", "") == "yes") ctx.get<Tracked>("tracked");
  }
};

void registerTestStages() {
  static bool done = false;
  if (done) return;
  done = true;
  StageRegistry::instance().add("TestDoubling", [] { return std::make_unique<DoublingStage>(); });
  StageRegistry::instance().add("TestFailing", [] { return std::make_unique<FailingStage>(); });
  StageRegistry::instance().add("TestReporting", [] { return std::make_unique<ReportingStage>(); });
  StageInfo tracking("TestTracking", "1", "puts or reads a tracked value", PlanSlot::NotPlanned);
  tracking.reads = [](const carrier::Step& step) {
    return step.param("reads", "") == "yes" ? std::vector<std::string>{"tracked"} : std::vector<std::string>{};
  };
  StageRegistry::instance().add(tracking, [] { return std::make_unique<TrackingStage>(); });
}

}  // namespace

TEST_CASE("the runner executes the process list in order, steps sharing the blackboard") {
  registerTestStages();
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestDoubling", "1").setParam("value", "3");
  c.addStep("TestDoubling", "1").setParam("value", "1");
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  runProcess(ctx, {});
  REQUIRE(c.data.size() == 2);
  CHECK(c.findResult("s1")->items[0].number("value") == 6);
  CHECK(c.findResult("s2")->items[0].number("value") == 14);  // (1 + 6) * 2
  CHECK(c.findResult("s2")->status == "completed");
  int timings = 0;
  for (const carrier::LogEntry& e : c.log) timings += e.level == "timing";
  CHECK(timings == 2);
}

TEST_CASE("a failing step is recorded as failed in the saved carrier, and the error propagates") {
  registerTestStages();
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-runner";
  fs::remove_all(dir);
  fs::create_directories(dir);
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestDoubling", "1");
  c.addStep("TestFailing", "1");
  c.addStep("TestDoubling", "1");
  Context ctx(dir, c, RunSettings{});
  CHECK_THROWS_AS(runProcess(ctx, dir / "carrier.xml"), Error);
  const carrier::Carrier saved = carrier::loadCarrier(dir / "carrier.xml");
  REQUIRE(saved.data.size() == 2);
  CHECK(saved.data[1].status == "failed");
  CHECK(saved.findResult("s3") == nullptr);
  CHECK(saved.log.back().level == "error");
  CHECK(saved.log.back().text.find("IMG_0001.jpg") != std::string::npos);
  fs::remove_all(dir);
}

// Records, when it runs, the steps the carrier on disk holds results for: the saves after earlier
// steps are written on a thread of their own (runner.cpp, CarrierSaver).
class DiskReadingStage : public Stage {
 public:
  std::string component() const override { return "TestDiskReading"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, Context&, carrier::Result& result) override {
    const fs::path file = step.param("carrier", "");
    const std::size_t onDisk = fs::exists(file) ? carrier::loadCarrier(file).data.size() : 0;
    result.add("value").set("name", "onDisk").set("value", std::to_string(onDisk));
  }
};

void registerDiskReading() {
  static const bool registered = [] {
    StageRegistry::instance().add("TestDiskReading", [] { return std::make_unique<DiskReadingStage>(); });
    return true;
  }();
  (void)registered;
}

TEST_CASE("the carrier saved after each step is on disk, whole and last, when the runner returns") {
  registerTestStages();
  registerDiskReading();
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-runner-saves";
  fs::remove_all(dir);
  fs::create_directories(dir);
  carrier::Carrier c = carrier::newCarrier("runner", {});
  for (int k = 0; k < 12; ++k) c.addStep("TestDiskReading", "1").setParam("carrier", (dir / "carrier.xml").string());
  Context ctx(dir, c, RunSettings{});
  runProcess(ctx, dir / "carrier.xml");
  const carrier::Carrier saved = carrier::loadCarrier(dir / "carrier.xml");
  REQUIRE(saved.data.size() == 12);
  CHECK(toXml(saved) == toXml(c));
  // Each step saw a carrier the run saved: of the steps before it, all but at most the last.
  for (int k = 0; k < 12; ++k) {
    const double seen = c.data[static_cast<std::size_t>(k)].items[0].number("value");
    CHECK(seen <= k);
    CHECK(seen >= k - 1);
  }
  // No temporary file left beside it.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  CHECK(files == 1);
  fs::remove_all(dir);
}

TEST_CASE("told to save only a failure, the runner writes no carrier for a run that succeeds, and the failed step's") {
  registerTestStages();
  registerDiskReading();
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-runner-failure-only";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "carrier.xml";
  carrier::Carrier ok = carrier::newCarrier("runner", {});
  for (int k = 0; k < 3; ++k) ok.addStep("TestDiskReading", "1").setParam("carrier", file.string());
  Context okCtx(dir, ok, RunSettings{});
  runProcess(okCtx, file, static_cast<std::size_t>(-1), Saves::FailureOnly);
  CHECK_FALSE(fs::exists(file));  // the caller saves it
  REQUIRE(ok.data.size() == 3);
  for (const carrier::Result& r : ok.data) CHECK(r.items[0].number("value") == 0);  // none on disk meanwhile

  carrier::Carrier failing = carrier::newCarrier("runner", {});
  failing.addStep("TestDoubling", "1");
  failing.addStep("TestFailing", "1");
  failing.addStep("TestDoubling", "1");
  Context failingCtx(dir, failing, RunSettings{});
  CHECK_THROWS_AS(runProcess(failingCtx, file, static_cast<std::size_t>(-1), Saves::FailureOnly), Error);
  const carrier::Carrier saved = carrier::loadCarrier(file);
  REQUIRE(saved.data.size() == 2);
  CHECK(saved.data[0].status == "completed");
  CHECK(saved.data[1].status == "failed");
  CHECK(saved.findResult("s3") == nullptr);
  fs::remove_all(dir);
}

// Leaves a task for later that writes "done" into its own result once run, and records a
// placeholder now; with "holding", it names the shared value the task reads.
class DeferringStage : public Stage {
 public:
  std::string component() const override { return "TestDeferring"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, Context& ctx, carrier::Result& result) override {
    result.add("value").set("name", "deferred").set("value", "");
    auto done = std::make_shared<std::string>();
    ctx.put("held", std::make_shared<int>(1));
    ctx.defer({[done] { *done = "done"; }},
              [&carrier = ctx.carrier, id = step.id, done] {
                for (carrier::Result& r : carrier.data)
                  if (r.step == id) r.items.at(0).set("value", *done);
              },
              {"held"});
  }
};

// Records whether the deferring step's result is filled in yet, as the carrier in memory holds it.
class PeekingStage : public Stage {
 public:
  std::string component() const override { return "TestPeeking"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, Context& ctx, carrier::Result& result) override {
    const carrier::Result* r = ctx.carrier.findResult("s1");
    result.add("value").set("name", "seen").set("value", r ? *r->items.at(0).get("value") : "none");
    if (ctx.has("held")) ctx.get<int>("held");
  }
};

TEST_CASE("work a step defers is recorded before every save, before its data is let go, and at the end") {
  registerTestStages();
  static const bool registered = [] {
    StageRegistry::instance().add("TestDeferring", [] { return std::make_unique<DeferringStage>(); });
    StageInfo peeking("TestPeeking", "1", "reads what it is told to", PlanSlot::NotPlanned);
    peeking.reads = [](const carrier::Step& step) {
      return step.param("reads", "") == "yes" ? std::vector<std::string>{"held"} : std::vector<std::string>{};
    };
    StageRegistry::instance().add(peeking, [] { return std::make_unique<PeekingStage>(); });
    return true;
  }();
  (void)registered;
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-runner-deferred";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto process = [](carrier::Carrier& c) {
    c.addStep("TestDeferring", "1");
    c.addStep("TestPeeking", "1").setParam("reads", "yes");
    c.addStep("TestPeeking", "1").setParam("reads", "yes");
    c.addStep("TestPeeking", "1");
  };
  SECTION("saved after each step: recorded before the first save") {
    carrier::Carrier c = carrier::newCarrier("runner", {});
    process(c);
    Context ctx(dir, c, RunSettings{});
    runProcess(ctx, dir / "carrier.xml");
    CHECK(*c.data[1].items[0].get("value") == "done");
    CHECK(*carrier::loadCarrier(dir / "carrier.xml").data[0].items[0].get("value") == "done");
  }
  SECTION("saved only on failure: left running until its data is let go (after step 3)") {
    carrier::Carrier c = carrier::newCarrier("runner", {});
    process(c);
    RunSettings settings;
    settings.threads = 2;
    Context ctx(dir, c, settings);
    runProcess(ctx, {}, static_cast<std::size_t>(-1), Saves::FailureOnly);
    CHECK(*c.data[1].items[0].get("value") == "");      // step 2: not yet
    CHECK(*c.data[2].items[0].get("value") == "");      // step 3 still reads "held"
    CHECK(*c.data[3].items[0].get("value") == "done");  // let go of after step 3: recorded
    CHECK(*c.data[0].items[0].get("value") == "done");
  }
  SECTION("a step that fails after it: recorded in the failure's save") {
    carrier::Carrier c = carrier::newCarrier("runner", {});
    c.addStep("TestDeferring", "1");
    c.addStep("TestFailing", "1");
    Context ctx(dir, c, RunSettings{});
    CHECK_THROWS_AS(runProcess(ctx, dir / "carrier.xml", static_cast<std::size_t>(-1), Saves::FailureOnly), Error);
    CHECK(*carrier::loadCarrier(dir / "carrier.xml").data[0].items[0].get("value") == "done");
  }
  fs::remove_all(dir);
}

TEST_CASE("a carrier that cannot be saved stops the run with the save's error") {
  registerTestStages();
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-runner-unsaved";
  fs::remove_all(dir);
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestDoubling", "1");
  c.addStep("TestDoubling", "1");
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  // The folder does not exist: the first save fails, on the saving thread.
  CHECK_THROWS_AS(runProcess(ctx, dir / "carrier.xml"), Error);
  CHECK_FALSE(fs::exists(dir / "carrier.xml"));
}

TEST_CASE("an unknown component in a carrier is refused by name") {
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("NoSuchStage", "1");
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  try {
    runProcess(ctx, {});
    FAIL("ran an unknown stage");
  } catch (const Error& e) {
    CHECK(e.message().find("NoSuchStage") != std::string::npos);
  }
}

TEST_CASE("a shared value read as another type is an Error naming its key, not a bad_any_cast") {
  carrier::Carrier c = carrier::newCarrier("runner", {});
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  ctx.put("lights", std::make_shared<double>(1.0));
  CHECK(*ctx.get<double>("lights") == 1.0);
  try {
    ctx.get<std::string>("lights");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK(e.file() == "lights");
    CHECK_THAT(e.message(), Catch::Contains("\"lights\""));
  }
  try {
    ctx.get<double>("spheres");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK_THAT(e.message(), Catch::Contains("\"spheres\""));
  }
}

namespace {

// Throws what a raw std::stod would, as a stage with a bug might.
class RawThrowingStage : public Stage {
 public:
  std::string component() const override { return "TestRawThrow"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, Context&, carrier::Result&) override { (void)std::stod("not a number"); }
};

// Its parameter "value" must be a number: the check every stage's options struct gives.
struct NumberOptions {
  Parameters toParameters() const { return {{"value", "1"}}; }
  static NumberOptions fromParameters(const Parameters& p) {
    for (const auto& [name, value] : p)
      if (name != "value" || value.empty() || value.find_first_not_of("0123456789") != std::string::npos)
        throw Error(ErrorKind::Input, name + "=" + value, "test", "is not a whole number");
    return {};
  }
};
class CheckedStage : public DescribedStage<CheckedStage> {
 public:
  static StageInfo info() { return withOptions<NumberOptions>({"TestChecked", "1", "checked", PlanSlot::NotPlanned}); }
  void run(const carrier::Step&, Context&, carrier::Result&) override {}
};

}  // namespace

TEST_CASE("a stage failing with another exception than Error is recorded as failed, as an internal Error") {
  static const bool once = (StageRegistry::instance().add("TestRawThrow", [] { return std::make_unique<RawThrowingStage>(); }), true);
  (void)once;
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestRawThrow", "1");
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  try {
    runProcess(ctx, {});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK(e.step() == "TestRawThrow");
  }
  REQUIRE(c.data.size() == 1);
  CHECK(c.data[0].status == "failed");
  CHECK(c.log.back().level == "error");
}

TEST_CASE("the runner checks a step's parameters with its stage's options before running it") {
  static const bool once = (StageRegistry::instance().add<CheckedStage>(), true);
  (void)once;
  const StageInfo* info = StageRegistry::instance().info("TestChecked");
  REQUIRE(info);
  CHECK(info->defaults == Parameters{{"value", "1"}});
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestChecked", "1").setParam("value", "1e9x");
  Context ctx(fs::temp_directory_path(), c, RunSettings{});
  try {
    runProcess(ctx, {});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == "value=1e9x");
  }
  REQUIRE(c.data.size() == 1);
  CHECK(c.data[0].status == "failed");
}

TEST_CASE("the runner ends each part of a step's progress at 100 percent, once the step goes on or completes") {
  registerTestStages();
  carrier::Carrier c = carrier::newCarrier("runner", {});
  c.addStep("TestReporting", "1");
  c.addStep("TestReporting", "1").setParam("fail", "yes");
  std::vector<std::pair<std::string, double>> seen;
  RunSettings settings;
  settings.progress = [&seen](const std::string& label, double f) { seen.emplace_back(label, f); };
  Context ctx(fs::temp_directory_path(), c, settings);
  CHECK_THROWS_AS(runProcess(ctx, {}), Error);
  const std::vector<std::pair<std::string, double>> expected = {
      {"Reading", 0}, {"Reading", 1}, {"Measuring", 0}, {"Measuring", 0.5}, {"Measuring", 1},
      {"Reading", 0}};  // the failed step's part is not said to be done
  CHECK(seen == expected);
  CHECK(ctx.settings.progress);  // the caller's callback is back in place after the failure
}

TEST_CASE("the runner lets go of shared data after the last step that reads it, and not before") {
  registerTestStages();
  // Runs the steps (component, parameter, value) in order; returns, per step, whether the
  // tracked value had been freed before it ran.
  const auto run = [](const std::vector<std::array<std::string, 3>>& steps, carrier::Carrier* c,
                      std::unique_ptr<Context>* ctx) {
    *c = carrier::newCarrier("release", {});
    for (const auto& [component, name, value] : steps) c->addStep(component, "1").setParam(name, value);
    gTrackedFreed = false;
    *ctx = std::make_unique<Context>(fs::temp_directory_path(), *c, RunSettings{});
    runProcess(**ctx, {});
    std::vector<std::string> freed;
    for (const carrier::Step& step : c->process)
      if (step.component == "TestTracking") freed.push_back(c->findResult(step.id)->items[0].get("value").value_or(""));
    return freed;
  };
  carrier::Carrier c;
  std::unique_ptr<Context> ctx;
  // put, read, read, then a step that reads nothing: freed after the last read, before the
  // step after it runs.
  CHECK(run({{{"TestTracking", "put", "1"}, {"TestTracking", "reads", "yes"}, {"TestTracking", "reads", "yes"},
              {"TestTracking", "reads", "no"}}},
            &c, &ctx) == std::vector<std::string>{"no", "no", "no", "yes"});
  CHECK_FALSE(ctx->has("tracked"));
  // A stage reading what it did not declare meets a plain internal error, not a wrong one.
  try {
    ctx->get<Tracked>("tracked");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK_THAT(e.what(), Catch::Contains("StageInfo::reads"));
  }
  // A later step of a stage that does not say what it reads keeps everything until it has run.
  CHECK(run({{{"TestTracking", "put", "1"}, {"TestTracking", "reads", "no"}, {"TestDoubling", "value", "1"},
              {"TestTracking", "reads", "no"}}},
            &c, &ctx) == std::vector<std::string>{"no", "no", "yes"});
}
