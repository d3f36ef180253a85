// CaptureIngest: scans the capture folder, records every file (hash, format, camera metadata,
// XMP) in the carrier, pairs originals with exports, applies the excluded-image interventions,
// and chooses which images the pipeline decodes.
//
// Parameters:  source = auto | original | export
// Interventions: exclude-image (target: shot name or file path; reason mandatory)
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class IngestStage : public pipeline::DescribedStage<IngestStage> {
 public:
  static constexpr const char* kComponent = "CaptureIngest";
  static pipeline::StageInfo info();  // in ingest_stage.cpp, with the version history
  void run(const carrier::Step& step, pipeline::Context& context,
           carrier::Result& result) override;
};

}  // namespace surrogate::stages
