// Every stage this build of Surrogate has: one line each. Within a slot of the plan
// (pipeline::PlanSlot), `surrogate run` plans stages in the order registered here.
#include <mutex>

#include "pipeline/stage.h"
#include "stages/audit_stage.h"
#include "stages/decode_stage.h"
#include "stages/fit_stages.h"
#include "stages/ingest_stage.h"
#include "stages/light_stages.h"
#include "stages/plan.h"
#include "stages/preprocess_stages.h"
#include "stages/web_copy_stage.h"

namespace surrogate::stages {

void registerBuiltinStages() {
  static std::once_flag once;
  std::call_once(once, [] {
    auto& r = pipeline::StageRegistry::instance();
    r.add<IngestStage>();
    r.add<DecodeStage>();
    r.add<SphereDetectionStage>();
    r.add<HighlightDetectionStage>();
    r.add<LightDirectionsStage>();
    r.add<LightsFromFileStage>();
    r.add<WhiteBalanceStage>();
    r.add<CropStage>();
    r.add<ResizeStage>();
    r.add<RtiFitStage>();
    r.add<DerivedMapsStage>();
    r.add<WebCopyStage>();
    r.add<AuditStage>();
  });
}

}  // namespace surrogate::stages
