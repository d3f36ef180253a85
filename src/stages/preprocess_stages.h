// The pre-processing stages: recorded steps that change the photographs the fit reads, never
// the files (the originals stay untouched) and never the light estimation (sphere and
// highlight detection always read the full, decoded frame). `surrogate run` plans them after
// the light stages and before RtiFit, in this order: WhiteBalance, Crop, Resize; a carrier may
// order them otherwise, and re-execution follows the carrier. Each replaces the "rgb-stack"
// the fit reads with a view computed on demand (see stack_views.h): no copy, bounded memory,
// identical values at any thread count.
//
//   WhiteBalance  per-channel gains in linear light: as shot (none beyond the decoder's), from
//                 a grey region (median over the stack of the region's per-image means, G = 1),
//                 or given multipliers; then the fit's input encoding (srgb or linear).
//                 Records the gains, per-image region means and the output space.
//   Crop          a rectangle given by the user, or the largest one clear of the spheres the
//                 SphereDetection step recorded (with a margin). Records the rectangle and how
//                 it was chosen.
//   Resize        a scale factor or a target size, area averaging in linear light with exact
//                 integer weights. Records the input and output sizes and the filter.
//
// Parameters: see preprocess.h (CropOptions, ResizeOptions, WhiteBalanceOptions). Each stage's
// info() (version, description, place in the plan) is next to its run() in preprocess_stages.cpp.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class WhiteBalanceStage : public pipeline::DescribedStage<WhiteBalanceStage> {
 public:
  static constexpr const char* kComponent = "WhiteBalance";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class CropStage : public pipeline::DescribedStage<CropStage> {
 public:
  static constexpr const char* kComponent = "Crop";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class ResizeStage : public pipeline::DescribedStage<ResizeStage> {
 public:
  static constexpr const char* kComponent = "Resize";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
