// LearnedFit: fits a learned basis (fit/learned.h: relight's RBF or bilinear model) to the
// decoded images and the light directions and writes it as the web layout it is read in,
// finished-files/<basis>/ (info.json and plane_N.jpg, whole or not at all), every file recorded
// with its digests so that a package bags them and `verify --reexecute` makes them again. A
// stage of its own in the EachModel slot rather than a kind of RtiFit: its output is a folder,
// not a file, and its parameters are not fit::FitOptions', so the consumers of RtiFit steps
// (web copy, audit, the verifier's checks) need not tell two kinds of step apart.
//
// Records as results the kernel width and ridge chosen by leaving each photograph out, the PSNR
// at the captured lights, the leave-one-out PSNR and the explained variance; with holdout K > 0
// also the PSNR and SSIM at K lights left out of a second fit, beside the blend of the three
// nearest photographs (stages/held_out_quality.h). Puts the model as a viewer shows it (its
// planes through their JPEG compression) under modelKey(basis), a fit::Relightable.
//
//   surrogate run stela12 --basis ptm-lrgb --basis bln --planes 27 --holdout 6
//   // steps: RtiFit basis=ptm-lrgb, LearnedFit basis=bln planes=27 resolution=8 quality=90:40 holdout=6
#pragma once

#include <string>

#include "fit/learned.h"
#include "pipeline/stage.h"

namespace surrogate::stages {

// The defaults of a learned fit, one place for `surrogate fit` and `surrogate run`: the fit's
// own (fit::LearnedOptions) and the planes' JPEG quality. Recorded in every LearnedFit step, so
// changing them changes only later plans, never a recorded step.
inline const int kLearnedPlanes = fit::LearnedOptions().planes;          // coefficients per texel
inline const int kLearnedResolution = fit::LearnedOptions().resolution;  // bln: the grid's side
// JPEG quality of the first plane and of the last, in equal steps between (publish::
// PublishOptions::lastQuality): on the NeuralRTI test set 90:40 gave 24.21 dB at 875 KB at
// lights left out and 26.91 dB at the captured lights, a uniform 75 24.18 dB at 964 KB and 26.86.
inline constexpr int kLearnedQuality = 90;
inline constexpr int kLearnedLastQuality = 40;

// The parameters of LearnedFit. Names and defaults are a record: never change them.
struct LearnedFitOptions {
  std::string basis = "bln";  // rbf or bln
  int planes = kLearnedPlanes;
  int resolution = kLearnedResolution;  // recorded for rbf too, which does not use it
  int quality = kLearnedQuality;          // recorded as "Q" (every plane) or "Q:LAST"
  int lastQuality = kLearnedLastQuality;
  int holdout = 0;  // photographs left out of a second fit to measure it at unseen lights; 0: none

  pipeline::Parameters toParameters() const;
  // Error(Input) naming the parameter for an unknown name, a basis that is not learned, or a
  // number out of range (planes a multiple of 3 in 3..120, resolution 4..32, quality Q or Q:LAST
  // each 1..100,
  // holdout 0..1000; the holdout's bound by the photographs is checked when the step runs).
  static LearnedFitOptions fromParameters(const pipeline::Parameters& parameters);
  // The fit's own options (kind, planes, resolution).
  fit::LearnedOptions fitOptions() const;
};

// Where LearnedFit writes the layout of `basis`: finished-files/<basis>.
std::string learnedFolder(const std::string& basis);

class LearnedFitStage : public pipeline::DescribedStage<LearnedFitStage> {
 public:
  static constexpr const char* kComponent = "LearnedFit";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
