// surrogate audit PRIOR [-o WORK] [--json] [--threshold DEG] [run options]: audits the prior
// work another tool left in PRIOR (a capture folder as RTIBuilder leaves it, or a package) in
// a work folder of its own (evidence/evidence.h), never writing into PRIOR; prints the verdict
// first, and exits 0 when the prior work is reproduced, 4 when it is not, 1 when it cannot be
// read.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "audit/audit.h"
#include "audit/recorded.h"
#include "capture/capture.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/pipeline_options.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "evidence/evidence.h"
#include "report/report.h"
#include "stages/audit_stage.h"
#include "run/plan.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kReproduced = 0;
constexpr int kNotReproduced = static_cast<int>(ErrorKind::NotReproduced);
constexpr int kUnreadable = static_cast<int>(ErrorKind::Input);

// The recorded Audit result, when it was made with the threshold of this audit (`threshold`, or
// the default when none is given: a threshold given to an earlier audit was that audit's only)
// and the difference images of `at` (unset: any).
const carrier::Result* usableResult(const carrier::Carrier& c, const std::optional<double>& threshold,
                                    const std::optional<std::string>& at) {
  const carrier::Result* r = audit::auditResult(c);
  if (!r) return r;
  const carrier::Step* step = c.findStep(r->step);
  if (!step) return nullptr;
  const double wanted = threshold.value_or(stages::AuditStageOptions{}.angleThresholdDegrees);
  if (step->param("angleThresholdDegrees", formatNumber(stages::AuditStageOptions{}.angleThresholdDegrees)) !=
      formatNumber(wanted))
    return nullptr;
  if (at && step->param("differenceImages") != *at) return nullptr;
  return r;
}

// --at NAME, repeatable: the photographs to make difference images at, as the Audit step's
// differenceImages parameter (comma-separated).
std::optional<std::string> atOption(const Args& args) {
  if (!args.has("at")) return std::nullopt;
  std::string joined;
  for (const std::string& name : args.values("at")) {
    if (name.empty() || name.find(',') != std::string::npos)
      throw Error(ErrorKind::Usage, "--at " + name, "command line",
                  "give one photograph's file or shot name per --at (e.g. --at IMG_0003.jpg --at IMG_0007)");
    joined += (joined.empty() ? "" : ",") + name;
  }
  return joined;
}

std::optional<double> thresholdOption(const Args& args) {
  if (!args.has("threshold")) return std::nullopt;
  const double v = args.doubleValue("threshold", 2);
  if (!(v > 0 && v < 180))
    throw Error(ErrorKind::Usage, "--threshold " + args.value("threshold", ""), "command line",
                "give the angle in degrees, more than 0 and less than 180 (e.g. --threshold 2)");
  return v;
}

// Whether the command line asks for a decision about the processing (--sphere, --exclude, ...),
// which only a run can apply.
bool decisionsGiven(const Args& args) {
  for (const OptionSpec& o : pipelineOptions(true))
    if (args.has(o.name)) return true;
  return false;
}

struct Outcome {
  fs::path prior, work;
  const evidence::WorkFolder* folder = nullptr;
  bool ran = false;
  std::string step;
  std::optional<fs::path> report;
};

void printJson(const Outcome& o, const audit::AuditReport& report, int exitCode) {
  JsonWriter j;
  j.beginObject().key("reproduced").value(exitCode == kReproduced).key("exitCode").value(exitCode);
  j.key("verdict");
  audit::writeSummaryJson(j, audit::summarise(report));
  j.key("prior").value(escapedText(o.prior.string())).key("work").value(escapedText(o.work.string()));
  j.key("copiedFiles");
  if (o.folder->copied) j.value(static_cast<int>(o.folder->copied->files.size()));
  else j.null();
  j.key("step").value(o.step).key("ran").value(o.ran).key("report");
  if (o.report) j.value(escapedText(o.report->string()));
  else j.null();
  j.key("audit");
  audit::writeAuditJson(j, report);
  j.endObject();
  std::cout << j.str() << "\n";
}

// The most lines of the per-image listing printed without --verbose.
constexpr std::size_t kAuditLines = 20;

void printText(const Outcome& o, const audit::AuditReport& report, int exitCode, Verbosity verbosity) {
  const char* verdict =
      exitCode == kReproduced ? "reproduced" : exitCode == kNotReproduced ? "not reproduced" : "cannot tell";
  if (verbosity == Verbosity::Quiet) {
    // The threshold this audit judged at, and the farthest light that differs, judged in words.
    std::cout << "audit of " << escapedText(o.prior.string()) << ": " << verdict << " (exit " << exitCode
              << "; threshold " << fixedDecimals(report.thresholdDegrees, 1) << " deg)";
    for (const audit::LightComparison& l : report.lights)
      if (!l.aboveThreshold.empty()) {
        const auto worst = std::max_element(l.aboveThreshold.begin(), l.aboveThreshold.end(),
                                            [](const auto& a, const auto& b) { return a.degrees < b.degrees; });
        std::cout << "; " << audit::lightJudgement(*worst, l.thresholdDegrees);
        break;
      }
    if (!report.notAudited.empty())
      std::cout << "; " << escapedText(report.notAudited.front().file.generic_string()) << " cannot be read ("
                << report.notAudited.front().reason << ")"
                << (report.notAudited.size() > 1 ? " and " + std::to_string(report.notAudited.size() - 1) + " more" : "");
    if (o.report) std::cout << "; report: " << escapedText(o.report->string());
    std::cout << "\n";
    return;
  }
  for (const std::string& line : audit::summaryLines(audit::summarise(report))) std::cout << line << "\n";
  for (const std::string& line : audit::logSummaryLines(report)) std::cout << line << "\n";
  for (const auto& n : report.notAudited)
    std::cout << "CANNOT TELL     " << n.file.generic_string() << ": cannot be read (" << n.reason << ")\n";
  std::cout << "\naudit of " << escapedText(o.prior.string()) << " in the work folder " << escapedText(o.work.string());
  if (o.folder->copied)
    std::cout << " (" << o.folder->copied->files.size() << " files copied; nothing written into "
              << escapedText(o.prior.string()) << ")";
  else if (o.folder->reused)
    std::cout << " (" << (o.work == o.prior ? "audited again in place" : "made by an earlier audit; the files audited are unchanged") << ")";
  std::cout << "\n  exit " << exitCode << ": " << verdict << "; step " << o.step << (o.ran ? ", just run" : ", as recorded") << "; threshold "
            << fixedDecimals(report.thresholdDegrees, 1) << " degrees\n";
  if (o.report) std::cout << "  report: " << escapedText(o.report->string()) << "\n";
  std::cout << "  pack it with its evidence: surrogate pack " << escapedText(o.work.string()) << " -o "
            << escapedText(o.work.string()) << ".zip\n\n";
  const std::vector<std::string> lines = audit::auditLines(report);
  const std::size_t shown = verbosity == Verbosity::Verbose ? lines.size() : std::min(lines.size(), kAuditLines);
  for (std::size_t i = 0; i < shown; ++i) std::cout << lines[i] << "\n";
  if (shown < lines.size())
    std::cout << "and " << (lines.size() - shown) << " more lines (--verbose prints them; the report shows all)\n";
}

// Runs the work folder with the request; a failure says where the audit works and how to go on.
carrier::Carrier runWorkFolder(const Outcome& o, const run::RunRequest& request, const pipeline::RunSettings& settings) {
  try {
    return run::runCapture(o.work, request, settings);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Input) throw;
    throw Error(e.kind(), e.file(), e.step(),
                e.message() + " (the audit works in " + escapedText(o.work.string()) +
                    "; give the correction, e.g. --sphere X,Y,R or --exclude NAME --reason \"...\", to `surrogate audit " +
                    escapedText(o.prior.string()) + "` again)");
  }
}

}  // namespace

int runCommandAudit(int argc, char** argv) {
  constexpr OptionGroup kOutput = OptionGroup::Output;
  std::vector<OptionSpec> specs = {
      {"o", true, false, "the work folder (default: beside PRIOR, named PRIOR-audit)", "WORK", kOutput},
      {"output", true, false, "same as -o", "WORK", kOutput},
      {"threshold", true, false,
       "name the images whose prior light differs by more than this and than the lights' combined uncertainty, "
       "for this audit only (default 2)",
       "DEG"},
      {"at", true, true, "also make a difference image at this photograph (file or shot name)", "PHOTO", kOutput}};
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  for (const OptionSpec& o : runOptionsForAnotherCommand()) specs.push_back(o);
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate audit PRIOR [-o WORK] [--json] [--threshold DEG] [options]",
                 "Audit the work another tool (RTIBuilder, relight, a dome's software) left in PRIOR, a "
                 "capture folder with its .lp and .ptm/.rti in assembly-files/ and finished-files/, or a "
                 "package of one: each prior .lp against Surrogate's lights, each prior .ptm or .rti "
                 "against the photographs beside Surrogate's refits, and a verdict in four parts (lights, "
                 "model, tone, integrity). Nothing is written into PRIOR, which may be read-only: its files "
                 "are copied into the work folder WORK, a capture of its own whose carrier records where "
                 "each came from, run there, and reported in WORK/finished-files/report.html; "
                 "`surrogate pack WORK` bags the audit with the evidence it examined. Run again, it reuses "
                 "WORK while PRIOR is unchanged. The options of `surrogate run` (--sphere, --exclude, ...) "
                 "correct the audit's own processing.",
                 {{"surrogate audit coin-rtibuilder",
                   "audit the RTIBuilder project folder coin-rtibuilder; the work goes to coin-rtibuilder-audit"},
                  {"surrogate audit coin.zip -o coin-audit --threshold 5",
                   "audit a package, naming only the lights that differ by more than 5 degrees"}},
                 {{0, "the prior work is reproduced"},
                  {1, "the prior work cannot be read (a file of it left out, named: this before 4), or there is none; or " +
                          std::string(kWriteRefused) + " in the work folder"},
                  {2, "bad usage: an unknown option, a missing or malformed value, a work folder inside PRIOR or "
                      "one that is something else; or a PRIOR file that is not a package (.zip, .tar)"},
                  {3, "a package whose files differ from its record, or an archive truncated or damaged"},
                  {4, "not reproduced: the verdict says which part and why"},
                  {5, kInternalError}}}))
    return 0;
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line", "give the folder or package to audit: surrogate audit PRIOR");
  const std::optional<double> threshold = thresholdOption(args);
  const std::optional<std::string> at = atOption(args);
  const bool json = args.has("json");
  (void)verbosityOf(args);  // --quiet with --verbose is refused before any work
  const std::optional<std::string> out = outputOption(args);

  Outcome o;
  o.prior = fs::absolute(args.positional()[0]).lexically_normal();
  if (o.prior.filename().empty() && o.prior != o.prior.root_path()) o.prior = o.prior.parent_path();  // "stela12/"
  ProgressBar bar(args.has("quiet") || json);
  const evidence::WorkFolder folder =
      evidence::prepareWorkFolder(o.prior, out ? std::optional<fs::path>(*out) : std::nullopt, bar.callback());
  bar.finish();
  o.folder = &folder;
  o.work = folder.folder;

  std::optional<carrier::Carrier> c;
  const fs::path carrierPath = o.work / capture::kCarrierPath;
  if (folder.reused && !decisionsGiven(args) && fs::exists(carrierPath)) {
    c = carrier::loadCarrier(carrierPath);
    if (!usableResult(*c, threshold, at)) c.reset();
  }
  if (!c) {
    run::RunRequest request = requestFrom(args);
    request.command = "audit";
    request.arguments.clear();
    for (int i = 1; i < argc; ++i) request.arguments.push_back(argv[i]);
    if (threshold)
      request.stageParams.push_back({stages::AuditStage::kComponent, "angleThresholdDegrees", formatNumber(*threshold)});
    if (at) request.stageParams.push_back({stages::AuditStage::kComponent, "differenceImages", *at});
    if (folder.copied) request.audited = folder.copied;
    pipeline::RunSettings settings = settingsFrom(args, bar);
    c = runWorkFolder(o, request, settings);
    bar.finish();
    o.ran = true;
    report::ReportOptions reportOptions;
    reportOptions.threads = settings.threads;
    reportOptions.progress = bar.callback();
    report::writeCaptureReport(o.work, reportOptions);
    bar.finish();
  }
  if (fs::exists(o.work / capture::kReportPath)) o.report = o.work / capture::kReportPath;

  const carrier::Result* r = audit::auditResult(*c);
  if (!r)
    throwInputError(o.prior.string(), "audit",
                    "holds no prior work Surrogate could audit: its run planned no Audit step (see " +
                        carrierPath.string() + ")");
  o.step = r->step;
  const audit::AuditReport report = audit::recordedAudit(*c, *r);
  const int exitCode = audit::auditExitCode(report);
  if (json) printJson(o, report, exitCode);
  else printText(o, report, exitCode, verbosityOf(args));
  return exitCode;
}

}  // namespace surrogate::cli
