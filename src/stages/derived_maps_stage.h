// DerivedMaps: from a model an earlier RtiFit or LearnedFit step fitted (a learned one as a
// viewer shows it): surface normals (16-bit PNG),
// albedo, and relit previews at a few fixed lights, in finished-files/.
#pragma once

#include <string>

#include "pipeline/stage.h"

namespace surrogate::stages {

// The parameters of DerivedMaps: which fitted model the maps come from.
struct DerivedMapsOptions {
  std::string model = "ptm-lrgb";  // a basis name fitted by an earlier RtiFit or LearnedFit step

  pipeline::Parameters toParameters() const;
  // Error(Input) for an unknown basis or name.
  static DerivedMapsOptions fromParameters(const pipeline::Parameters& parameters);
};

class DerivedMapsStage : public pipeline::DescribedStage<DerivedMapsStage> {
 public:
  static constexpr const char* kComponent = "DerivedMaps";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
