// The values of a run checked against the frame they apply to, before any processing: a circle
// given by hand (--sphere), a sphere search region (--sphere-roi), a highlight given by hand
// (--highlight), a crop rectangle or grey region (--crop, --wb-region), each by the rules of
// stages/frame_checks.h. The command line checks what needs no frame (cli/option_checks.h)
// with the same rules; the stages check again.
//
//   run::checkRequestAgainstFrame(request, 400, 300);  // Error(Usage) naming the option
#pragma once

#include "capture/capture.h"
#include "run/plan.h"

namespace surrogate::run {

// Checks the request's values against a width x height frame (the capture's images), before
// any processing: the circles and highlights given by hand, the sphere search regions, a
// user crop rectangle, a white-balance grey region and the size a resize gives (at least
// kMinResizeSide pixels per side, stages/preprocess.h). A highlight given for a sphere whose
// circle is given by hand must lie on that circle, and name one of those spheres. Throws
// Error(Usage) naming the option and its value ("--sphere 900,57,45"), saying what is wrong
// and what the frame allows.
void checkRequestAgainstFrame(const RunRequest& request, int width, int height);

// Checks the names the request gives for the capture's images, before any processing and
// before the run is recorded: each image `--exclude` or `--highlight IMAGE:SPHERE=X,Y` names
// must be a shot of `layout` (by the rule of capture::findShotStem: a shot's name, a file name
// or a path). Throws Error(Usage)
// naming the option and the value, with the nearest name when one is close: the file whose
// name differs only in case ("IMG_0003.jpg" for img_0003), else a shot within a small edit
// distance. Decisions standing from earlier runs are not checked again here (the ingest and
// highlight steps do).
void checkRequestNames(const RunRequest& request, const capture::CaptureLayout& layout);

}  // namespace surrogate::run
