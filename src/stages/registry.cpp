// Every stage this build of Surrogate has: one line each. Within a slot of the plan
// (pipeline::PlanSlot), `surrogate run` plans stages in the order registered here.
#include <mutex>

#include "pipeline/stage.h"
#include "stages/audit_stage.h"
#include "stages/colour_chart_stage.h"
#include "stages/crop_stage.h"
#include "stages/decode_stage.h"
#include "stages/derived_maps_stage.h"
#include "stages/highlight_detection_stage.h"
#include "stages/ingest_stage.h"
#include "stages/learned_fit_stage.h"
#include "stages/light_directions_stage.h"
#include "stages/lights_from_file_stage.h"
#include "stages/registry.h"
#include "stages/resize_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/sphere_detection_stage.h"
#include "stages/web_copy_stage.h"
#include "stages/white_balance_stage.h"

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
    r.add<ColourChartStage>();
    r.add<WhiteBalanceStage>();
    r.add<CropStage>();
    r.add<ResizeStage>();
    r.add<RtiFitStage>();
    r.add<LearnedFitStage>();
    r.add<DerivedMapsStage>();
    r.add<WebCopyStage>();
    r.add<AuditStage>();
  });
}

}  // namespace surrogate::stages
