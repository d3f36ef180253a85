// The Audit stage: prior work another tool left in the capture (RTIBuilder's .lp, a .ptm or
// .rti; recorded by the ingest with role "prior", stages/prior_work.h) against Surrogate's
// lights and the photographs (src/audit, docs/hrti-math.md "Auditing a prior RTI"). Planned by
// `surrogate run` after the fits, only when the capture holds a prior light file or result.
// Its figures are the step's result (audit/recorded.h); it writes a difference image of each
// prior model at its worst image to assembly-files/audit/<model stem>-difference.png, and one at
// each photograph named by `differenceImages` (<model stem>-difference-<photograph stem>.png).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "audit/recorded.h"
#include "carrier/carrier.h"
#include "pipeline/stage.h"

namespace surrogate::stages {

// The parameters of Audit (audit::AuditOptions). Names and defaults are a record: never change
// them.
struct AuditStageOptions {
  // Images whose prior light differs from Surrogate's by more than this are named (degrees).
  double angleThresholdDegrees = 2.0;
  // The prior counts as reproduced when its PSNR is at most this far below Surrogate's fit of
  // the same basis with the prior's lights (dB).
  double reproducedMarginDb = 1.0;
  // Photographs (file names, or shot names: the file name without its extension) at which a
  // difference image of each prior model is made besides the one at its worst image; recorded
  // comma-separated. Each costs one rendering and one PNG file.
  std::vector<std::string> differenceImages;

  pipeline::Parameters toParameters() const;
  // Error(Input) naming the parameter for an unknown name, a value that is not a number, a
  // threshold outside (0, 180), a negative margin, or an empty name in differenceImages.
  static AuditStageOptions fromParameters(const pipeline::Parameters& parameters);
};

// The stack indices of `names` (AuditStageOptions::differenceImages) among `photographs` (the
// photographs' capture-relative paths, in stack order), each matched by file name, else by shot
// name, each photograph once; Error(Usage) naming the first that is none of them, with a few
// that are.
std::vector<int> photographsNamed(const std::vector<std::string>& names, const std::vector<std::string>& photographs);

class AuditStage : public pipeline::DescribedStage<AuditStage> {
 public:
  static constexpr const char* kComponent = audit::kAuditComponent;
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

// The prior light files and results (kinds lp and rti) among the files of the capture's
// assembly-files/ and finished-files/, by the rule of stages/prior_work.h (`previous`: the
// capture's carrier or null; `planned`: the outputs of the run about to be planned).
std::vector<std::string> priorWorkToAudit(const std::filesystem::path& capture,
                                          const carrier::Carrier* previous,
                                          const std::vector<std::string>& planned);

}  // namespace surrogate::stages
