// The values of the pipeline options (run, lights, pack) checked before any work, as far as
// they can be without the capture: every value is UTF-8 text without control characters
// (every option is recorded in the carrier, an XML document); --sphere, --highlight and
// --sphere-roi are numbers a frame can have (the rules of stages/request_checks.h, whose
// checkRequestAgainstFrame adds the frame once the capture's images are known); lens and
// sphere measures are finite, above 0 and of a sane size; --meta keys are labels `pack` can
// write into bag-info.txt (archive::bagInfoLabelProblem). A bad value is Error(Usage) naming
// the option and the value: "--sphere 339,57,-5: the radius R is -5; it must be above 0 ...".
#pragma once

#include "cli/args.h"

namespace surrogate::cli {

void checkPipelineOptionValues(const Args& args);

// Lens and sphere measures in millimetres that any real capture falls within.
inline constexpr double kMinFocalLengthMm = 0.5, kMaxFocalLengthMm = 10000;
inline constexpr double kMinPixelPitchMm = 0.0001, kMaxPixelPitchMm = 1;
inline constexpr double kMinSphereDiameterMm = 0.5, kMaxSphereDiameterMm = 10000;

}  // namespace surrogate::cli
