// The fitting stages:
//
//   RtiFit       fits one model (PTM LRGB, PTM RGB, HSH order 2 or 3) to the decoded images
//                and the light directions, streaming over row bands; writes it to
//                finished-files/ (.ptm or .rti) and records the fit quality: RMSE and PSNR of
//                the stored model re-rendered at every captured light, per image and overall.
//   DerivedMaps  from a fitted model: surface normals (16-bit PNG), albedo, and relit
//                previews at a few fixed lights.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

// Blackboard key of a fitted model, by basis name ("model:ptm-lrgb").
std::string modelKey(const std::string& basis);
// Where RtiFit writes a basis unless told otherwise: finished-files/ptm-lrgb.ptm, .../hsh2.rti.
std::string defaultFitOutput(const std::string& basis);

class RtiFitStage : public pipeline::Stage {
 public:
  std::string component() const override { return "RtiFit"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

class DerivedMapsStage : public pipeline::Stage {
 public:
  std::string component() const override { return "DerivedMaps"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
