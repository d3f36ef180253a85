#include "run/run_commit.h"

#include <cstdlib>
#include <set>
#include <vector>

#include "capture/capture.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace surrogate::run {

namespace fs = std::filesystem;

namespace {

using capture::kCarrierPath;
using capture::kReportPath;

fs::path journalPath(const fs::path& capture) { return capture / capture::kWorkDir / "commit"; }

bool isOutput(const carrier::FileRecord& f) { return f.role == "assembly" || f.role == "result"; }

// rename(2), creating the target's folder; a missing source means an earlier, interrupted
// commit already moved it.
void moveInto(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(from, ec))) return;
  fs::create_directories(to.parent_path());
  fs::rename(from, to, ec);
  if (ec)
    throw Error(ErrorKind::Internal, to.string(), "commit",
                "could not move the run's result into place (" + ec.message() +
                    "); run the command again to finish");
}

// The commit itself, from the journal's point on: idempotent, so recovery can repeat it.
// `next` is the carrier staged in the staging folder.
void finishCommit(const fs::path& capture, const carrier::Carrier* previous, const carrier::Carrier& next) {
  const fs::path staging = stagingRoot(capture);
  const std::string runId = next.header.runs.empty() ? "r0" : next.header.runs.back().id;
  for (const SupersededFile& s : supersededFiles(capture, previous, next, runId))
    moveInto(capture / s.path, capture / s.movedTo);
  for (const carrier::FileRecord& f : next.files)
    if (isOutput(f) && f.path != kCarrierPath) moveInto(staging / f.path, capture / f.path);
  // Fault injection for the test of this guarantee (tests/e2e/test_workflow_e2e.cpp): with
  // SURROGATE_FAULT_INJECTION=commit the process dies here, between the results and the
  // carrier, as a kill -9 or a power cut could make it; the next command must finish the commit.
  if (const char* fault = std::getenv("SURROGATE_FAULT_INJECTION"); fault && std::string(fault) == "commit")
    std::_Exit(137);
  // The report is a view of the carrier it was made from: it goes with the old carrier (the
  // command writes a new one after the commit).
  std::error_code ec;
  fs::remove(capture / kReportPath, ec);
  moveInto(staging / kCarrierPath, capture / kCarrierPath);
  fs::remove(journalPath(capture));
  fs::remove_all(staging);
}

// The temporary files of atomic writes (".NAME.part-PID-N", core/atomic_file.h) that a killed
// command left in the output folders or in the work folder: a run killed while it wrote its
// report after the commit leaves ".surrogate/.report.html.part-...". Under the capture's lock no
// other command is writing there, so each one is a leftover. Returns their capture-relative
// paths.
std::vector<std::string> removeInterruptedWrites(const fs::path& capture) {
  std::vector<fs::path> leftovers;
  for (const char* dir : {capture::kAssemblyDir, capture::kFinishedDir, capture::kWorkDir}) {
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(capture / dir, ec))) continue;
    for (auto it = fs::recursive_directory_iterator(capture / dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
      if (!it->is_directory(ec) && capture::isInterruptedWrite(it->path().filename().string()))
        leftovers.push_back(it->path());
  }
  std::vector<std::string> removed;
  for (const fs::path& p : leftovers) {
    std::error_code ec;
    if (fs::remove(p, ec)) removed.push_back(p.lexically_relative(capture).generic_string());
  }
  return removed;
}

}  // namespace

fs::path stagingRoot(const fs::path& capture) { return capture / capture::kWorkDir / "staging"; }

std::vector<SupersededFile> supersededFiles(const fs::path& capture, const carrier::Carrier* previous,
                                            const carrier::Carrier& next, const std::string& runId) {
  std::set<std::string> produced;
  for (const carrier::FileRecord& f : next.files)
    if (isOutput(f)) produced.insert(f.path);
  std::vector<std::string> old;
  if (previous)
    for (const carrier::FileRecord& f : previous->files)
      if (isOutput(f) && !produced.count(f.path)) old.push_back(f.path);
  std::vector<SupersededFile> out;
  for (const std::string& path : old) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(capture / path, ec))) continue;
    out.push_back({path, std::string(capture::kSupersededDir) + "/" + runId + "/" + path});
  }
  return out;
}

void commitRun(const fs::path& capture, const carrier::Carrier* previous, const carrier::Carrier& next) {
  // `next` was saved in the staging folder just before: what reading it back would give, without
  // parsing the carrier again (a few milliseconds at the end of every run, on one thread).
  writeFileAtomically(journalPath(capture), "commit of the staged run in .surrogate/staging\n");
  finishCommit(capture, previous, next);
}

std::optional<PendingRecovery::Kind> pendingKind(const fs::path& capture) {
  std::error_code ec;
  if (fs::exists(journalPath(capture), ec))
    return fs::exists(stagingRoot(capture) / kCarrierPath, ec) ? PendingRecovery::Kind::FinishCommit
                                                               : PendingRecovery::Kind::ClearJournal;
  if (fs::exists(stagingRoot(capture), ec)) return PendingRecovery::Kind::DiscardStaging;
  return std::nullopt;
}

std::optional<std::string> recoverRun(const fs::path& capture) {
  const std::vector<std::string> leftovers = removeInterruptedWrites(capture);
  const fs::path staging = stagingRoot(capture);
  std::error_code ec;
  if (const std::optional<PendingRecovery::Kind> kind = pendingKind(capture)) {
    switch (*kind) {
      case PendingRecovery::Kind::FinishCommit: {
        std::optional<carrier::Carrier> previous;
        if (fs::exists(capture / kCarrierPath, ec)) previous = carrier::loadCarrier(capture / kCarrierPath);
        // When the staged carrier is still there, the old carrier is still in place too (it is
        // renamed last): the superseded files are computed against it as in the first attempt.
        finishCommit(capture, previous ? &*previous : nullptr,
                     carrier::loadCarrier(staging / kCarrierPath));
        return std::nullopt;  // the interrupted run completed: its record is the carrier now
      }
      case PendingRecovery::Kind::ClearJournal:
        fs::remove(journalPath(capture));
        fs::remove_all(staging, ec);
        return std::nullopt;
      case PendingRecovery::Kind::DiscardStaging:
        fs::remove_all(staging, ec);
        return "an earlier command on this capture was interrupted before it finished (killed or "
               "crashed); its partial results were discarded";
    }
  }
  if (!leftovers.empty())
    return "an earlier command on this capture was interrupted while it wrote " + leftovers.front() +
           (leftovers.size() > 1 ? " and " + std::to_string(leftovers.size() - 1) + " more" : std::string()) +
           "; the partial file was removed";
  return std::nullopt;
}

std::optional<PendingRecovery> pendingRecovery(const fs::path& capture) {
  const std::optional<PendingRecovery::Kind> kind = pendingKind(capture);
  if (!kind) return std::nullopt;
  PendingRecovery p{*kind, {}, {}};
  if (*kind == PendingRecovery::Kind::FinishCommit) {
    try {
      const carrier::Carrier staged = carrier::loadCarrier(stagingRoot(capture) / kCarrierPath);
      if (!staged.header.runs.empty()) p.run = staged.header.runs.back();
    } catch (const Error& e) {
      p.stagedProblem = e.message();  // recoverRun will stop on it too
    }
  }
  return p;
}

}  // namespace surrogate::run
