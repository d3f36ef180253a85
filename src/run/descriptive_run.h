// A run that changes only the capture's descriptive metadata (title, creators, rights, licence,
// --meta): recorded as a run in the history without running any step again.
//
// Every step of a plan but WebCopy reads only the capture's files and its own parameters and
// interventions, never the header (src/stages): a title changes no result. WebCopy's pages show
// the description, so a capture with a web copy processes as usual. When the new plan's process list is
// the recorded one, the build is the one that made the results (software list), the record is
// complete and every file it records is on disk with the recorded bytes, and no file of the
// capture is new, the results stand as they are: runCapture (run/plan.h) then commits a carrier
// that is the previous one with the new header fields and run record, through the same
// all-or-nothing commit as any run (run/run_commit.h), and writes no result file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "capture/capture.h"
#include "carrier/carrier.h"

namespace surrogate::run {

// Whether `planned` (planRun's carrier for the new request) differs from `previous` (the
// capture's carrier) only in the descriptive fields of the header, with every processing input
// and result as recorded: same steps (components, versions, parameters, interventions with
// their who and when), same software versions, every step's result completed, the same set of
// files in the capture (`layout`, and `outputFolderFiles` listed after any interrupted commit
// was finished) as the carrier records, each with the recorded size and SHA-256 (read in
// parallel on `threads`). False as soon as anything differs: the run then processes as usual.
bool onlyDescriptiveChange(const std::filesystem::path& capture, const capture::CaptureLayout& layout,
                           const std::vector<std::string>& outputFolderFiles, const carrier::Carrier& previous,
                           const carrier::Carrier& planned, int threads);

// How the note of a descriptive-only run begins, and whether `record` is one: the CLI says so
// rather than "Processed".
inline constexpr const char* kDescriptiveRunNote = "descriptive metadata only";
bool isDescriptiveRun(const carrier::RunRecord& record);

// Commits the descriptive-only run: `previous` with `planned`'s title, creators, metadata,
// rights and licence, a new modified time and `record` (completed, with a note saying that no
// step ran) appended to its history; files, process, data and log as they were. Written to the
// staging folder and moved into place by commitRun, so that a process killed at any point
// leaves the old carrier or the new one. Returns the new carrier.
carrier::Carrier commitDescriptiveRun(const std::filesystem::path& capture, const carrier::Carrier& previous,
                                      const carrier::Carrier& planned, carrier::RunRecord record);

}  // namespace surrogate::run
