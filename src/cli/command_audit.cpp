// surrogate audit CAPTURE [--json] [--threshold DEG]: the audit of the prior work another tool
// left in the capture, as the carrier records it (stages/audit_stage.h). When the carrier has no
// Audit result yet, or one made with another threshold, the capture is run again with it
// (recorded in the carrier like a run, under the capture's lock).
#include <cmath>
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
#include "stages/audit_stage.h"
#include "stages/plan.h"
#include "stages/prior_work.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

using capture::kCarrierPath;

// The recorded Audit result and whether it was made with `threshold` (unset: any).
const carrier::Result* usableResult(const carrier::Carrier& c, const std::optional<double>& threshold) {
  const carrier::Result* r = audit::auditResult(c);
  if (!r || !threshold) return r;
  const carrier::Step* step = c.findStep(r->step);
  pipeline::Parameters params;
  if (step)
    for (const carrier::Param& p : step->params) params.emplace_back(p.name, p.value);
  const stages::AuditStageOptions recorded = stages::AuditStageOptions::fromParameters(params);
  return recorded.angleThresholdDegrees == *threshold ? r : nullptr;
}

std::optional<double> thresholdOption(const Args& args) {
  if (!args.has("threshold")) return std::nullopt;
  const double v = args.doubleValue("threshold", 2);
  if (!(v > 0 && v < 180))
    throw Error(ErrorKind::Usage, "--threshold " + args.value("threshold", ""), "command line",
                "give the angle in degrees, more than 0 and less than 180 (e.g. --threshold 2)");
  return v;
}

void printNoPriorWork(const fs::path& capture, bool json) {
  if (json) {
    JsonWriter j;
    j.beginObject().key("capture").value(capture.string()).key("priorWork").value(false).endObject();
    std::cout << j.str() << "\n";
  } else {
    std::cout << capture.string() << ": no prior work to audit (no .lp, .ptm or .rti that Surrogate "
                                     "did not write in assembly-files/ or finished-files/)\n";
  }
}

void printAudit(const fs::path& capture, const carrier::Carrier& c, const carrier::Result& r, bool ran, bool json) {
  const audit::AuditReport report = audit::recordedAudit(c, r);
  if (json) {
    JsonWriter j;
    j.beginObject().key("capture").value(capture.string()).key("priorWork").value(true)
        .key("step").value(r.step).key("ran").value(ran).key("audit");
    audit::writeAuditJson(j, report);
    j.endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << "audit of the prior work in " << capture.string() << " (step " << r.step
            << (ran ? ", just run" : ", as recorded") << "; threshold "
            << fixedDecimals(report.thresholdDegrees, 1) << " degrees)\n";
  for (const std::string& line : audit::auditLines(report)) std::cout << line << "\n";
}

}  // namespace

int runCommandAudit(int argc, char** argv) {
  std::vector<OptionSpec> specs = {
      {"threshold", true, false, "name the images whose prior light differs by more than this (default 2)", "DEG"}};
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs, "surrogate audit CAPTURE [--json] [--threshold DEG] [options]",
                "Audit the prior work another tool (RTIBuilder, relight, a dome's software) left in "
                "CAPTURE's assembly-files/ and finished-files/: each prior .lp against Surrogate's "
                "lights, each prior .ptm or .rti against the photographs beside Surrogate's own fit, "
                "and a verdict. Prints the audit the carrier records; runs the capture again (recorded "
                "like a run) when there is none yet or it was made with another threshold. Run "
                "`surrogate run CAPTURE` first."))
    return 0;
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line", "give the capture folder: surrogate audit CAPTURE");
  const fs::path capture = args.positional()[0];
  const std::optional<double> threshold = thresholdOption(args);
  const bool json = args.has("json");
  capture::requireCaptureFolder(capture);
  if (!fs::exists(capture / kCarrierPath))
    throw Error(ErrorKind::Usage, capture.string(), "audit",
                "has not been processed yet: run `surrogate run " + capture.string() +
                    "` first; the audit compares the prior work with Surrogate's lights and fit of it");
  carrier::Carrier c = carrier::loadCarrier(capture / kCarrierPath);
  if (!audit::auditResult(c) &&
      stages::priorWorkToAudit(capture, &c, stages::plannedOutputs(c)).empty()) {
    printNoPriorWork(capture, json);
    return 0;
  }
  if (const carrier::Result* r = usableResult(c, threshold)) {
    printAudit(capture, c, *r, false, json);
    return 0;
  }
  stages::RunRequest request;
  request.command = "audit";
  for (int i = 1; i < argc; ++i) request.arguments.push_back(argv[i]);
  if (threshold)
    request.stageParams.push_back({stages::AuditStage::kComponent, "angleThresholdDegrees", formatNumber(*threshold)});
  ProgressBar bar(args.has("quiet") || json);
  c = stages::runCapture(capture, request, settingsFrom(args, bar));
  bar.finish();
  const carrier::Result* r = audit::auditResult(c);
  if (!r) {
    printNoPriorWork(capture, json);
    return 0;
  }
  printAudit(capture, c, *r, true, json);
  return 0;
}

}  // namespace surrogate::cli
