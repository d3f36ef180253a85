// RtiFit: fits one model (PTM LRGB, PTM RGB, HSH order 2 or 3) to the decoded images and the
// light directions, streaming over row bands; writes it to finished-files/ (.ptm or .rti) and
// records the fit quality: RMSE and PSNR of the stored model re-rendered at every captured
// light, per image and overall. Puts the model under modelKey(basis) for DerivedMaps and WebCopy.
#pragma once

#include <string>

#include "fit/fit.h"
#include "pipeline/stage.h"

namespace surrogate::stages {

// Blackboard key of a fitted model, by basis name ("model:ptm-lrgb").
std::string modelKey(const std::string& basis);
// Where RtiFit writes a basis unless told otherwise: finished-files/ptm-lrgb.ptm, .../hsh2.rti.
std::string defaultFitOutput(const std::string& basis);

// The parameters of RtiFit: the fit's (fit::FitOptions: basis), where the model goes, and how
// many photographs a second fit leaves out to measure the model at unseen lights.
struct RtiFitOptions {
  fit::FitOptions fit;
  std::string output;  // relative to the capture; empty: defaultFitOutput(basis)
  int holdout = 0;     // 0: not measured (stages/held_out_record.h)

  pipeline::Parameters toParameters() const;  // basis, then output when given, holdout when > 0
  // Error(Input) for an unknown basis or name, or an output outside assembly-files/ and
  // finished-files/ (checkedOutputPath).
  static RtiFitOptions fromParameters(const pipeline::Parameters& parameters);
  static RtiFitOptions forBasis(const std::string& basis);  // with its default output
};

class RtiFitStage : public pipeline::DescribedStage<RtiFitStage> {
 public:
  static constexpr const char* kComponent = "RtiFit";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
