#include "pipeline/runner.h"

#include <chrono>
#include <cstdio>
#include <exception>

#include "carrier/carrier.h"
#include "pipeline/stage.h"

namespace surrogate::pipeline {

namespace fs = std::filesystem;

fs::path Context::pathOf(const std::string& fileId) const {
  const carrier::FileRecord* f = carrier.findFile(fileId);
  if (!f) throwInputError("carrier", "pipeline", "refers to file id " + fileId + ", which it does not list");
  const bool output = f->role == "assembly" || f->role == "result";
  return (output ? outputRoot : capture) / f->path;
}

namespace {

// The step's parameters read by its stage's options struct before it runs: a bad value (not a
// number, out of range, an unknown name) is an Error naming it, recorded as the step's failure.
void checkParameters(const carrier::Step& step) {
  const StageInfo* info = StageRegistry::instance().info(step.component);
  if (!info || !info->check) return;
  Parameters params;
  for (const carrier::Param& p : step.params) params.emplace_back(p.name, p.value);
  info->check(params);
}

}  // namespace

void runProcess(Context& context, const fs::path& carrierPath, std::size_t steps) {
  carrier::Carrier& c = context.carrier;
  auto save = [&] {
    if (carrierPath.empty()) return;
    c.header.modified = carrier::timestampNow();
    carrier::saveCarrier(c, carrierPath);
  };
  // Copy the list: a stage may append files, never steps, but the reference must stay valid.
  std::vector<carrier::Step> list = c.process;
  if (steps < list.size()) list.resize(steps);
  for (const carrier::Step& step : list) {
    std::unique_ptr<Stage> stage = StageRegistry::instance().create(step.component);
    c.clearResult(step.id);
    carrier::Result result;
    result.step = step.id;
    result.started = carrier::timestampNow();
    const auto t0 = std::chrono::steady_clock::now();
    auto fail = [&](const Error& e) {
      result.status = "failed";
      result.ended = carrier::timestampNow();
      result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      c.data.push_back(result);
      c.addLog("error", step.id, e.what());
      save();
    };
    try {
      checkParameters(step);
      stage->run(step, context, result);
    } catch (const Error& e) {
      fail(e);
      throw;
    } catch (const std::exception& e) {
      // Stages throw only Error; anything else is a bug, recorded as the step's failure all the
      // same, so that no carrier looks complete after it.
      const Error internal(ErrorKind::Internal, "carrier", step.component,
                           std::string("step ") + step.id + " failed unexpectedly (" + e.what() +
                               "); this is a bug in Surrogate, please report it");
      fail(internal);
      throw internal;
    }
    result.ended = carrier::timestampNow();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    c.data.push_back(std::move(result));
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3f", c.data.back().seconds);
    c.addLog("timing", step.id, step.component + " completed in " + seconds + " s");
    save();
  }
}

}  // namespace surrogate::pipeline
