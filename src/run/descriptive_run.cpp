#include "run/descriptive_run.h"

#include <atomic>
#include <set>
#include <system_error>

#include "core/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "run/run_commit.h"
#include "stages/web_copy_stage.h"

namespace surrogate::run {

namespace fs = std::filesystem;

namespace {

bool sameIntervention(const carrier::Intervention& a, const carrier::Intervention& b) {
  return a.kind == b.kind && a.target == b.target && a.value == b.value && a.who == b.who && a.time == b.time &&
         a.reason == b.reason;
}

bool sameStep(const carrier::Step& a, const carrier::Step& b) {
  if (a.id != b.id || a.component != b.component || a.version != b.version || a.algorithm != b.algorithm ||
      a.params.size() != b.params.size() || a.interventions.size() != b.interventions.size())
    return false;
  for (std::size_t n = 0; n < a.params.size(); ++n)
    if (a.params[n].name != b.params[n].name || a.params[n].value != b.params[n].value) return false;
  for (std::size_t n = 0; n < a.interventions.size(); ++n)
    if (!sameIntervention(a.interventions[n], b.interventions[n])) return false;
  return true;
}

bool sameSoftware(const std::vector<carrier::Software>& a, const std::vector<carrier::Software>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t n = 0; n < a.size(); ++n)
    if (a[n].name != b[n].name || a[n].version != b[n].version || a[n].role != b[n].role) return false;
  return true;
}

bool sameCreators(const std::vector<carrier::Creator>& a, const std::vector<carrier::Creator>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t n = 0; n < a.size(); ++n)
    if (a[n].name != b[n].name || a[n].role != b[n].role) return false;
  return true;
}

bool sameDescription(const carrier::Header& a, const carrier::Header& b) {
  return a.title == b.title && sameCreators(a.creators, b.creators) && a.meta == b.meta && a.rights == b.rights &&
         a.license == b.license;
}

// The capture's files as scanCapture sees them (inputs, other files, the output folders), less
// the carrier and the report, which no record describes.
std::set<std::string> filesOnDisk(const capture::CaptureLayout& layout, const std::vector<std::string>& outputFolderFiles) {
  std::set<std::string> out;
  for (const capture::Shot& shot : layout.shots)
    for (const std::optional<capture::ImageFile>& f : {shot.original, shot.exported})
      if (f) out.insert(f->relativePath);
  if (layout.lp) out.insert(*layout.lp);
  out.insert(layout.sidecars.begin(), layout.sidecars.end());
  out.insert(layout.others.begin(), layout.others.end());
  out.insert(outputFolderFiles.begin(), outputFolderFiles.end());
  out.erase(capture::kCarrierPath);
  out.erase(capture::kReportPath);
  return out;
}

}  // namespace

bool onlyDescriptiveChange(const fs::path& capture, const capture::CaptureLayout& layout,
                           const std::vector<std::string>& outputFolderFiles, const carrier::Carrier& previous,
                           const carrier::Carrier& planned, int threads) {
  // Something descriptive changed, and nothing else a run records: a run that changes nothing
  // processes again, as it always has (the way to make fresh results on purpose).
  if (sameDescription(previous.header, planned.header)) return false;
  if (previous.header.audited.has_value() != planned.header.audited.has_value()) return false;
  if (!sameSoftware(previous.header.software, planned.header.software)) return false;
  if (previous.process.empty() || previous.process.size() != planned.process.size()) return false;
  // The web copy's pages show the title, creators, rights and licence (WebCopy 4): its step
  // must run again for them to say the new description, and verify re-executes it from the
  // header. Such a capture processes as usual.
  for (const carrier::Step& s : previous.process)
    if (s.component == stages::WebCopyStage::kComponent) return false;
  for (std::size_t n = 0; n < previous.process.size(); ++n)
    if (!sameStep(previous.process[n], planned.process[n])) return false;
  // The record is complete: every step ran and succeeded (not a lights-only record, not one
  // whose last processing failed), and no result stands for a step the plan does not have.
  if (previous.data.size() != previous.process.size()) return false;
  for (const carrier::Step& s : previous.process) {
    const carrier::Result* r = previous.findResult(s.id);
    if (!r || r->status != "completed") return false;
  }
  // The same files: none new (a photograph added, a stray result), none gone.
  std::set<std::string> recorded;
  for (const carrier::FileRecord& f : previous.files)
    if (f.path != capture::kCarrierPath && f.path != capture::kReportPath) recorded.insert(f.path);
  if (recorded != filesOnDisk(layout, outputFolderFiles)) return false;
  // Each with the bytes recorded: sizes first (cheap), then SHA-256, in parallel.
  for (const carrier::FileRecord& f : previous.files) {
    std::error_code ec;
    const fs::path p = capture / fs::u8path(f.path);
    if (!fs::is_regular_file(fs::symlink_status(p, ec)) || fs::file_size(p, ec) != f.size || ec) return false;
  }
  std::atomic<bool> same{true};
  parallelFor(previous.files.size(), 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e && same; ++i) {
      const carrier::FileRecord& f = previous.files[i];
      try {
        if (digestFile(capture / fs::u8path(f.path)).sha256 != f.sha256) same = false;
      } catch (const Error&) {
        same = false;  // unreadable now: the full run names the file and the cause
      }
    }
  });
  return same;
}

carrier::Carrier commitDescriptiveRun(const fs::path& capture, const carrier::Carrier& previous,
                                      const carrier::Carrier& planned, carrier::RunRecord record) {
  carrier::Carrier next = previous;
  next.header.title = planned.header.title;
  next.header.creators = planned.header.creators;
  next.header.meta = planned.header.meta;
  next.header.rights = planned.header.rights;
  next.header.license = planned.header.license;
  record.notes.push_back(std::string(kDescriptiveRunNote) +
                         ": no processing step ran again; the results and "
                         "their records stand as the previous run left them (every recorded file "
                         "checked against its SHA-256)");
  record.ended = carrier::timestampNow();
  record.outcome = "completed";
  next.header.runs.push_back(std::move(record));
  next.header.modified = carrier::timestampNow();
  const fs::path staging = stagingRoot(capture);
  fs::remove_all(staging);
  fs::create_directories(staging / capture::kAssemblyDir);
  carrier::saveCarrier(next, staging / capture::kCarrierPath);
  commitRun(capture, &previous, next);
  return next;
}

bool isDescriptiveRun(const carrier::RunRecord& record) {
  for (const std::string& note : record.notes)
    if (note.rfind(kDescriptiveRunNote, 0) == 0) return true;
  return false;
}

}  // namespace surrogate::run
