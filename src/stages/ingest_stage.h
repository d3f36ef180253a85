// CaptureIngest: scans the capture folder, records every file (hash, format, camera metadata,
// XMP) in the carrier, pairs originals with exports, applies the excluded-image interventions,
// and chooses which images the pipeline decodes.
//
// Parameters:  source = auto | original | export
// Interventions: exclude-image (target: shot name or file path; reason mandatory)
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class IngestStage : public pipeline::Stage {
 public:
  std::string component() const override { return "CaptureIngest"; }
  // 2: other files of the capture recorded (role "other"), system files left out, links
  // refused, the dome .lp chosen by the "lp" parameter, recorded originals compared.
  std::string version() const override { return "2"; }
  void run(const carrier::Step& step, pipeline::Context& context,
           carrier::Result& result) override;
};

}  // namespace surrogate::stages
