// The Audit stage: prior work another tool left in the capture (RTIBuilder's .lp, a .ptm or
// .rti; recorded by the ingest with role "prior", stages/prior_work.h) against Surrogate's
// lights and the photographs (src/audit, docs/hrti-math.md "Auditing a prior RTI"). Planned by
// `surrogate run` after the fits, only when the capture holds a prior light file or result.
// Its figures are the step's result (audit/recorded.h); it writes one difference image per
// prior model to assembly-files/audit/.
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

  pipeline::Parameters toParameters() const;
  // Error(Input) naming the parameter for an unknown name, a value that is not a number, a
  // threshold outside (0, 180) or a negative margin.
  static AuditStageOptions fromParameters(const pipeline::Parameters& parameters);
};

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
