// Pipeline stages and their registry.
//
// A stage is a registered component with a name and a version. The runner gives it its
// `Step` from the carrier's process list (parameters and interventions), the shared
// `Context`, and an empty `Result` to fill: what it read, computed and wrote. Stages talk
// only through the carrier, plus the context's cache of pixel data derived from the files the
// carrier lists (decoding the same files again would give the same pixels).
//
//   class SphereDetectionStage : public Stage {
//     std::string component() const override { return "SphereDetection"; }
//     std::string version() const override { return "1"; }
//     void run(const carrier::Step& step, Context& ctx, carrier::Result& out) override;
//   };
//   StageRegistry::instance().add("SphereDetection",
//                                 [] { return std::make_unique<SphereDetectionStage>(); });
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::pipeline {

class Context;

class Stage {
 public:
  virtual ~Stage() = default;
  virtual std::string component() const = 0;
  // Bumped whenever the stage's results for the same inputs and parameters change.
  virtual std::string version() const = 0;
  virtual void run(const carrier::Step& step, Context& context, carrier::Result& result) = 0;
};

class StageRegistry {
 public:
  using Factory = std::function<std::unique_ptr<Stage>()>;
  static StageRegistry& instance();
  void add(const std::string& component, Factory factory);
  // Throws Error(Input) when the carrier names a component this build does not have.
  std::unique_ptr<Stage> create(const std::string& component) const;
  bool has(const std::string& component) const;
  std::vector<std::string> components() const;

 private:
  std::vector<std::pair<std::string, Factory>> factories_;
};

}  // namespace surrogate::pipeline
