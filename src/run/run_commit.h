// Making a run's staged results the capture's state, all or nothing.
//
// A run writes its outputs and carrier under CAPTURE/.surrogate/staging/ (the same relative
// paths as in the capture). Only when every step succeeded does commitRun() move them into
// place: it first writes a journal (CAPTURE/.surrogate/commit), then moves aside the results of
// the previous record that the new one no longer has (into superseded-files/RUN/), renames each
// staged output over the old one, renames the staged carrier last, and removes the journal. A
// process killed in the middle leaves the journal; the next command on the capture calls
// recoverRun() under the capture's lock and finishes the commit, so the capture is always
// either the old state or the new one, never a mix.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::run {

// CAPTURE/.surrogate/staging: where a run in progress writes.
std::filesystem::path stagingRoot(const std::filesystem::path& capture);

// Results `previous` records (assembly and result files) that `next` does not
// produce, with where commitRun() will move them: superseded-files/<runId>/<path>.
struct SupersededFile {
  std::string path;   // relative to the capture
  std::string movedTo;
};
std::vector<SupersededFile> supersededFiles(const std::filesystem::path& capture,
                                            const carrier::Carrier* previous,
                                            const carrier::Carrier& next, const std::string& runId);

// Moves the staged run into the capture (see above); `next` is the staged carrier, already
// saved in the staging folder.
void commitRun(const std::filesystem::path& capture, const carrier::Carrier* previous,
               const carrier::Carrier& next);

// Under the capture's lock, before anything else: finishes a commit that a killed process left
// (journal present), or removes the staging folder of a run that never reached its commit;
// and removes the temporary files of atomic writes a killed command left in assembly-files/ and
// finished-files/, and in .surrogate/ (".NAME.part-PID-N": its report, written after the commit,
// waits there until complete).
// Returns a sentence for the run history when it found an interrupted run, else nothing.
std::optional<std::string> recoverRun(const std::filesystem::path& capture);

// What recoverRun will find when the next command takes the capture's lock, read without the
// lock and without changing anything (for `surrogate info`); nothing when no command was cut
// short in a commit or before it.
struct PendingRecovery {
  enum class Kind {
    FinishCommit,    // a journal and the staged carrier: the commit will be finished, its run recorded
    ClearJournal,    // a journal alone: the commit had moved everything; the journal will be removed
    DiscardStaging,  // a staging folder without a journal: a run killed before its commit, discarded
  };
  Kind kind;
  std::optional<carrier::RunRecord> run;  // FinishCommit: the staged carrier's last run, when it reads
  std::string stagedProblem;  // FinishCommit: why the staged carrier cannot be read (recovery will stop on it)
};
std::optional<PendingRecovery> pendingRecovery(const std::filesystem::path& capture);
// The kind alone, from which of the journal, the staged carrier and the staging folder are
// there (nothing read): the one decision recoverRun acts on and pendingRecovery describes.
std::optional<PendingRecovery::Kind> pendingKind(const std::filesystem::path& capture);

}  // namespace surrogate::run
