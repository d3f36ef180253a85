// Pipeline stages and their registry.
//
// A stage is a registered component with a name and a version. The runner gives it its
// `Step` from the carrier's process list (parameters and interventions), the shared
// `Context`, and an empty `Result` to fill: what it read, computed and wrote. Stages talk
// only through the carrier, plus the context's cache of pixel data derived from the files the
// carrier lists (decoding the same files again would give the same pixels).
//
// A stage describes itself in one place, its class: `info()` gives its name, version,
// description, place in the plan and default parameters (from its options struct), and the
// check of a recorded step's parameters. One line registers it:
//
//   class SphereDetectionStage : public DescribedStage<SphereDetectionStage> {
//    public:
//     static StageInfo info() {
//       return withOptions<hrti::SphereDetectionOptions>(
//           {"SphereDetection", "1", "Find the reflective spheres: ...", PlanSlot::LightsFromSpheres});
//     }
//     void run(const carrier::Step& step, Context& ctx, carrier::Result& out) override;
//   };
//   registry.add<SphereDetectionStage>();
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::pipeline {

class Context;

// A step's parameters as name/value pairs, in the carrier's order.
using Parameters = std::vector<std::pair<std::string, std::string>>;

// Where `surrogate run` puts a stage in the process list it plans (run/plan.h). Within a
// slot, stages come in registration order.
enum class PlanSlot {
  Ingest,             // first: reads the capture folder
  Decode,             // second: decodes the images
  LightsFromSpheres,  // light estimation, for a capture without a dome .lp
  LightsFromFile,     // light directions, for a capture with a dome .lp
  Colour,             // after the lights, before pre-processing: colour from a chart
  Preprocessing,      // only when the request asks for it, in the order asked
  EachModel,          // once per model fitted (`forModel` gives the parameters)
  AfterModels,        // once after the fits, for the first model (`forModel`, if set)
  Publish,            // once per model fitted (`forModel`), only when the request asks for the
                      // web copy (run/plan.h: RunRequest::publish)
  PriorWork,          // last, only when the capture holds prior work to audit (stages/audit_stage.h)
  NotPlanned,         // never planned by `surrogate run` (a carrier may still name it)
};

// What a stage says about itself: everything the registry, the planner and the carrier need.
struct StageInfo {
  StageInfo() = default;
  StageInfo(std::string component, std::string version, std::string description, PlanSlot slot)
      : component(std::move(component)), version(std::move(version)),
        description(std::move(description)), slot(slot) {}

  std::string component;    // the carrier's step/@component: recorded, so never renamed
  std::string version;      // bumped whenever results change for the same inputs and parameters
  // Older versions this build still runs as they ran, so that their records re-execute
  // (`surrogate verify --reexecute`) with the results they recorded; the stage reads the step's
  // version to choose. Empty: only `version`.
  std::vector<std::string> alsoRuns;
  std::string description;  // one sentence for the carrier's <description>
  PlanSlot slot = PlanSlot::NotPlanned;
  // Recorded when the user gives none, so the carrier holds every value used: the options
  // struct's defaults (its toParameters()).
  Parameters defaults;
  // Throws Error naming the parameter when recorded parameters cannot be read (the options
  // struct's fromParameters()). Empty: the stage takes no parameters.
  std::function<void(const Parameters&)> check;
  // EachModel and AfterModels: the parameters of the step for the model `basis` ("hsh2").
  std::function<Parameters(const std::string& basis)> forModel;
  // EachModel and Publish: whether the stage has a step for the model `basis` (RtiFit fits
  // the PTM and HSH bases, LearnedFit the learned ones). Empty: every model.
  std::function<bool(const std::string& basis)> takesModel;
  // The files a step of this stage writes (capture-relative paths), known from the step before
  // it runs; a '*' stands for any text (one overview per sphere found). `surrogate run`
  // refuses a plan that would write over prior work (stages/prior_work.h). Empty: no file.
  std::function<std::vector<std::string>(const carrier::Step& step)> outputs;
  // The shared data a step of this stage reads (Context::get keys), known from the step before
  // it runs. The runner lets go of what no later step reads (runner.h), so that the decoded
  // photographs do not outlive the last step that needs them. Empty: the stage may read
  // anything, and nothing is let go while a step of it is still to come.
  std::function<std::vector<std::string>(const carrier::Step& step)> reads;
  // Parameters that a command gives for the step it plans only (`surrogate audit --threshold`):
  // recorded in that step like any parameter, so that re-execution repeats it, but never a
  // standing decision (run::standingDecisions leaves them out): a later run plans the default.
  std::vector<std::string> perCommand;
};

// A `reads` for a stage that always reads the same keys.
std::function<std::vector<std::string>(const carrier::Step&)> alwaysReads(std::vector<std::string> keys);

// `info` with the defaults and check of an options struct that has toParameters() and
// fromParameters(const Parameters&).
template <class Options>
StageInfo withOptions(StageInfo info) {
  info.defaults = Options().toParameters();
  info.check = [](const Parameters& p) { Options::fromParameters(p); };
  return info;
}

// The options of a stage that takes no parameters: fromParameters refuses any (Error(Input)).
struct NoOptions {
  Parameters toParameters() const { return {}; }
  static NoOptions fromParameters(const Parameters& parameters);
};

// `info` with the check of an options struct, and no defaults: the plan gives every parameter.
template <class Options>
StageInfo checkedBy(StageInfo info) {
  info.check = [](const Parameters& p) { Options::fromParameters(p); };
  return info;
}

class Stage {
 public:
  virtual ~Stage() = default;
  virtual std::string component() const = 0;
  // Bumped whenever the stage's results for the same inputs and parameters change.
  virtual std::string version() const = 0;
  virtual void run(const carrier::Step& step, Context& context, carrier::Result& result) = 0;
};

// A stage whose component and version come from its static `info()`.
template <class Self>
class DescribedStage : public Stage {
 public:
  std::string component() const override { return Self::info().component; }
  std::string version() const override { return Self::info().version; }
};

class StageRegistry {
 public:
  using Factory = std::function<std::unique_ptr<Stage>()>;
  static StageRegistry& instance();

  // Registers a stage class with a static info() (a DescribedStage).
  template <class S>
  void add() {
    add(S::info(), [] { return std::make_unique<S>(); });
  }
  void add(StageInfo info, Factory factory);
  // A stage known only by its factory (no description, defaults or place in the plan).
  void add(const std::string& component, Factory factory);

  // Throws Error(Input) when the carrier names a component this build does not have.
  std::unique_ptr<Stage> create(const std::string& component) const;
  bool has(const std::string& component) const;
  // The description of `component`, or null when this build does not have it.
  const StageInfo* info(const std::string& component) const;
  // Whether this build runs `version` of `component` as that version ran: its current version
  // or one of StageInfo::alsoRuns.
  bool runsAsRecorded(const std::string& component, const std::string& version) const;
  // Every registered stage, in registration order.
  std::vector<const StageInfo*> stages() const;
  std::vector<std::string> components() const;

 private:
  struct Entry {
    StageInfo info;
    Factory factory;
  };
  std::vector<Entry> entries_;
};

}  // namespace surrogate::pipeline
