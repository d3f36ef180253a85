// surrogate run CAPTURE [options]
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "capture/capture.h"
#include "capture/lock.h"
#include "cli/args.h"
#include "cli/pipeline_options.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "report/report.h"
#include "stages/ingest_stage.h"
#include "run/descriptive_run.h"
#include "run/plan.h"

namespace surrogate::cli {

namespace {
// Copies of what the run's steps write, by carrier path, made as each file is written, for the
// report that follows: display copies of the pictures (report::ReportOptions::displayed) and
// interactive copies of the fitted models (relightCopies), so that the report does not decode
// the pictures or read and parse the models again (at 36 x 3000x2000, 126 MB of models). Steps
// may write from several threads.
template <class Copy>
class CopiesByPath {
 public:
  void put(const std::string& path, Copy copy) {
    const std::lock_guard<std::mutex> lock(mutex_);
    (*copies_)[path] = std::move(copy);  // a file written again: its last content
  }

  std::shared_ptr<const std::map<std::string, Copy>> all() const { return copies_; }

 private:
  std::mutex mutex_;
  std::shared_ptr<std::map<std::string, Copy>> copies_ = std::make_shared<std::map<std::string, Copy>>();
};

// The models the run's carrier will list, for each one's share of the report's bytes: those
// --basis names, else those the capture's carrier lists now (the run keeps them), else the
// default two. A wrong guess costs time only: the report then reads the models from their
// files, and the page is the same.
std::size_t expectedModels(const std::string& capture, const run::RunRequest& request) {
  if (request.bases) return request.bases->size();
  const std::filesystem::path recorded = std::filesystem::path(capture) / capture::kCarrierPath;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(recorded, ec)) return 2;
  try {
    const std::size_t listed = report::relightModelCount(carrier::loadCarrier(recorded));
    return listed > 0 ? listed : 2;
  } catch (const Error&) {
    return 2;  // the run itself says what is wrong with the carrier
  }
}
}  // namespace

int runCommandRun(int argc, char** argv) {
  std::vector<OptionSpec> specs = pipelineOptions(true);
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  specs.push_back({"no-report", false, false,
                   "do not write finished-files/report.html (the HTML report, a view of the carrier); "
                   "a previous one is removed, since it no longer matches the carrier", "", OptionGroup::Output});
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate run CAPTURE [options]",
                 "Run the HRTI pipeline on a capture folder: ingest (hash, EXIF/XMP), decode, and every "
                 "processing stage, recording all of it in CAPTURE/assembly-files/carrier.xml; results go to "
                 "CAPTURE/finished-files/, with report.html. The originals are never changed. Each run starts "
                 "from the decisions recorded before; a run that changes only the description runs no step.",
                 {{"surrogate run stela12 --title \"Stela 12\" --creator \"Ana Silva:photographer\"",
                   "process the capture folder stela12, naming it and its photographer"},
                  {"surrogate run stela12 --exclude IMG_0007.CR2 --reason \"flash misfired\"",
                   "leave one photograph out from now on, saying why (recorded, with who and when)"}},
                 commonExitCodes("processed (warnings, if any, are printed and kept in the carrier)", {{3, kChangedOriginal}})}))
    return 0;
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line",
                "give exactly one capture folder: surrogate run CAPTURE (see --help)");
  const std::string capture = args.positional()[0];
  refuseCaptureSubfolder(capture, "run");
  const run::RunRequest request = requestFrom(args);

  ProgressBar bar(args.has("quiet") || args.has("json"));
  pipeline::RunSettings settings = settingsFrom(args, bar);
  report::ReportOptions reportOptions;
  CopiesByPath<report::DisplayPicture> displayed;
  CopiesByPath<report::RelightCopy> relightCopies;
  std::size_t modelBytes = 0;  // each model's share of the page's bytes, once the lock is held
  if (!args.has("no-report")) {
    const int pictureSide = reportOptions.maxImageSide, modelSide = reportOptions.relightMaxSide;
    settings.pictureWritten = [&displayed, pictureSide](const std::string& path, const Image& picture) {
      displayed.put(path, report::displayPicture(picture, pictureSide));
    };
    const auto copyModel = [&relightCopies, &modelBytes, modelSide](const std::string& path, const auto& model) {
      relightCopies.put(path, {report::relightJson(model, modelSide, modelBytes), modelSide, modelBytes});
    };
    settings.ptmWritten = copyModel;  // PTM and HSH alike
    settings.hshWritten = copyModel;
  }
  // A folder that is not a capture is refused before anything is written in it, lock included.
  capture::requireCaptureFolder(capture);
  // The lock covers the report too: it is written from the carrier this run committed.
  capture::CaptureLock lock(capture, "run");
  modelBytes = report::relightShare(reportOptions.relightModelsBytes, expectedModels(capture, request));
  const carrier::Carrier c = run::runCapture(capture, request, settings, /*takeLock=*/false);
  bar.finish();
  // The report is a derived view of the carrier, not a recorded step (it holds the time it was
  // made): written after the run, never listed in the carrier.
  std::optional<report::Report> rep;
  if (!args.has("no-report")) {
    reportOptions.threads = settings.threads;
    reportOptions.progress = bar.callback();
    reportOptions.displayed = displayed.all();
    reportOptions.relightCopies = relightCopies.all();
    rep = report::writeCaptureReport(capture, reportOptions);
    bar.finish();
  } else std::filesystem::remove(std::filesystem::path(capture) / capture::kReportPath);
  const std::string reportPath = capture + "/" + capture::kReportPath;

  const std::string carrierPath = capture + "/" + capture::kCarrierPath;
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("capture").value(capture).key("carrier").value(carrierPath);
    j.key("steps").beginArray();
    for (const carrier::Step& s : c.process) {
      const carrier::Result* r = c.findResult(s.id);
      j.beginObject().key("id").value(s.id).key("component").value(s.component)
          .key("status").value(r ? r->status : "not run")
          .key("seconds").value(r ? r->seconds : 0.0).endObject();
    }
    j.endArray().key("outputs").beginArray();
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "assembly" || f.role == "result") j.value(f.path);
    j.endArray().key("report");
    if (rep) j.value(reportPath);
    else j.null();
    // This run in the carrier's history, and what it changed in the standing decisions.
    if (!c.header.runs.empty()) {
      j.key("run").value(c.header.runs.back().id).key("changes").beginArray();
      for (const std::string& n : c.header.runs.back().notes) j.value(n);
      j.endArray();
    }
    // Every warning, as `info --json` lists them (carrier::describeCarrier).
    j.key("warnings").beginArray();
    for (const carrier::WarningSummary& w : carrier::describeCarrier(c).warnings)
      j.beginObject().key("step").value(w.step).key("component").value(w.component).key("time").value(w.time)
          .key("text").value(w.text).endObject();
    j.endArray();
    j.endObject();
    std::cout << j.str() << "\n";
  } else {
    const Verbosity verbosity = verbosityOf(args);
    const carrier::CarrierSummary summary = carrier::describeCarrier(c);
    const bool descriptive = !c.header.runs.empty() && run::isDescriptiveRun(c.header.runs.back());
    if (verbosity == Verbosity::Quiet) {
      // One line: what happened, how many warnings, where the report is.
      std::cout << (descriptive ? "Recorded the new description of " + capture + " (no processing step ran again)"
                                : "Processed " + capture + " (" + std::to_string(c.process.size()) + " steps)");
      if (!summary.warnings.empty())
        std::cout << ", " << summary.warnings.size() << (summary.warnings.size() == 1 ? " warning" : " warnings")
                  << " (surrogate info " << escapedText(capture) << " lists them)";
      if (rep) std::cout << "; report: " << reportPath;
      std::cout << "\n";
      return 0;
    }
    if (descriptive)
      std::cout << "Recorded the new description of " << capture << " (no processing step ran again).\n";
    else
      std::cout << "Processed " << capture << " (" << c.process.size() << " steps).\n";
    for (const carrier::Step& s : c.process)
      if (s.component == stages::IngestStage::kComponent && s.hasParam("lp"))
        std::cout << "  lights: from " << s.param("lp") << " (dome capture: no sphere or highlight detection)\n";
    if (!c.header.runs.empty()) {
      const carrier::RunRecord& r = c.header.runs.back();
      std::cout << "  run " << r.id << " of the capture's record; "
                << (!r.notes.empty() ? "changes:" : r.id == "r1" ? "no decisions given" : "the recorded decisions stand, unchanged")
                << "\n";
      for (const std::string& n : r.notes) std::cout << "    " << n << "\n";
    }
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "other" && f.path.find('/') == std::string::npos && f.format == "LP")
        std::cout << "  note: " << f.path << " is not used for the lights; for a dome capture, run with --lp " << f.path << "\n";
    std::cout << "  carrier (provenance): " << carrierPath << "\n";
    std::vector<ListedFile> written;
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "assembly" || f.role == "result") written.push_back({f.role, capture, f.path});
    printFileList(written, verbosity);
    // Files another tool left in the output folders: recorded, never touched.
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "prior")
        std::cout << "  prior work (kept as found): " << capture << "/" << f.path << " (" << f.priorKind
                  << (f.madeBy.empty() ? "" : "; " + f.madeBy) << ")\n";
    if (rep) {
      std::cout << "  report (open in a browser): " << reportPath << "\n";
      for (const std::string& g : rep->coverageGaps) std::cout << "  coverage: " << g << "\n";
    }
    // Each warning's text where the user looks, at most a screenful (issue 43); info lists all,
    // and so does --verbose.
    printWarnings(summary, verbosity == Verbosity::Verbose ? 0 : kWarningLines,
                  "surrogate info " + escapedText(capture) + " lists them all");
  }
  return 0;
}

}  // namespace surrogate::cli
