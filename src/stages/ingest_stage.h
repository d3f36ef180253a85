// CaptureIngest: scans the capture folder, records every file (hash, format, camera metadata,
// XMP) in the carrier, pairs originals with exports, applies the excluded-image interventions,
// and chooses which images the pipeline decodes.
//
// Parameters:  source = auto | original | export
// Interventions: exclude-image (target: shot name or file path; reason mandatory)
#pragma once

#include <string>

#include "capture/capture.h"
#include "pipeline/stage.h"

namespace surrogate::stages {

// The capture as `run` scanned it just before its steps, under this key of the context (put
// only when the output folders are still as that scan listed them: recoverRun may have finished
// an interrupted commit since). The ingest takes it instead of reading every name and image
// header again when it was scanned with the step's "lp"; without it (a re-execution), it scans.
constexpr const char* kScannedCapture = "capture.scanned";
struct ScannedCapture {
  capture::CaptureLayout layout;
  std::string lp;  // the dome .lp it was scanned with ("" for none)
};

class IngestStage : public pipeline::DescribedStage<IngestStage> {
 public:
  static constexpr const char* kComponent = "CaptureIngest";
  static pipeline::StageInfo info();  // in ingest_stage.cpp, with the version history
  void run(const carrier::Step& step, pipeline::Context& context,
           carrier::Result& result) override;
};

}  // namespace surrogate::stages
