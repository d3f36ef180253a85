// The values of the pipeline options (run, lights, pack) checked before any work, as far as
// they can be without the capture: every value is UTF-8 text without control characters
// (every option is recorded in the carrier, an XML document); --sphere, --highlight and
// --sphere-roi are numbers a frame can have (the rules of stages/frame_checks.h, to which
// run::checkRequestAgainstFrame adds the frame once the capture's images are known); lens and
// sphere measures are finite, above 0 and of a sane size; --meta keys are labels `pack` can
// write into bag-info.txt (archive::bagInfoLabelProblem). A bad value is Error(Usage) naming
// the option and the value: "--sphere 339,57,-5: the radius R is -5; it must be above 0 ...".
#pragma once

#include <filesystem>

#include "cli/args.h"

namespace surrogate::cli {

void checkPipelineOptionValues(const Args& args);

// --threads N: a whole number from 0 (all cores, the default) to kMaxThreads; anything else is
// Error(Usage) naming the option and the value.
inline constexpr int kMaxThreads = 1024;
int threadsOption(const Args& args);

// An output file the user names (`-o OUT`), checked before any work: not an existing folder,
// in a folder that exists (Error(Usage) naming `option` and the path, saying what to do;
// `example` is a file name the message suggests, "relit.png"), and allowed by the output rule
// of capture/output_rule.h (an earlier output at the same path may be replaced; a package, an
// archive, a bag's file or a file of several names may not).
void checkOutputFile(const std::string& option, const std::filesystem::path& output,
                     const std::string& example);

// A folder inside a capture given where the capture is meant (`run CAPTURE/original-captures`):
// Error(Usage) naming the folder and saying to give its parent ("surrogate `command` PARENT").
// The folders recognised are original-captures/, raw-images/, jpeg-exports/, assembly-files/
// and finished-files/, when the folder given is not itself a capture (has none of them).
void refuseCaptureSubfolder(const std::filesystem::path& folder, const std::string& command);

// A capture folder given to a command that wants a package (`verify CAPTURE`): Error(Usage)
// saying to pack it first. A folder is a capture when it has no bagit.txt and has
// original-captures/, raw-images/, jpeg-exports/ or assembly-files/carrier.xml.
void refuseCaptureForPackage(const std::filesystem::path& path, const std::string& command);

// Lens and sphere measures in millimetres that any real capture falls within.
inline constexpr double kMinFocalLengthMm = 0.5, kMaxFocalLengthMm = 10000;
inline constexpr double kMinPixelPitchMm = 0.0001, kMaxPixelPitchMm = 1;
inline constexpr double kMinSphereDiameterMm = 0.5, kMaxSphereDiameterMm = 10000;

}  // namespace surrogate::cli
