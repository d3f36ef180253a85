// surrogate pack CAPTURE -o OUT [options]
#include <cctype>
#include <iostream>

#include "archive/package.h"
#include "capture/capture.h"
#include "capture/lock.h"
#include "carrier/carrier.h"
#include "pipeline/stage.h"
#include "stages/run_commit.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/pipeline_options.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "report/report.h"
#include "stages/plan.h"

namespace surrogate::cli {

namespace {

// Runs the pipeline as `surrogate run` does, starting from the decisions the carrier records
// (the options of this command, if any, add to them), under the lock `pack` holds.
void runPipeline(const std::string& capture, const Args& args, ProgressBar& bar) {
  stages::RunRequest request = requestFrom(args);
  request.command = "pack";
  pipeline::RunSettings settings = settingsFrom(args);
  settings.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  stages::runCapture(capture, request, settings, /*takeLock=*/false);
  if (!args.has("no-report")) report::writeCaptureReport(capture);
}

// A step the carrier records with another version than this build's stage (the verifier
// would find the package invalid): the capture is processed again with its recorded decisions.
std::string outdatedStep(const std::string& capture) {
  stages::registerBuiltinStages();
  const carrier::Carrier c = carrier::loadCarrier(std::filesystem::path(capture) / "assembly-files/carrier.xml");
  for (const carrier::Step& s : c.process) {
    const std::string now = pipeline::StageRegistry::instance().create(s.component)->version();
    if (now != s.version)
      return "step " + s.id + " (" + s.component + ") was recorded by version " + s.version +
             " of the stage; this Surrogate has version " + now;
  }
  return "";
}

// Whether the command line gives a decision (an option `surrogate run` records).
bool givesDecisions(const Args& args) {
  for (const OptionSpec& o : pipelineOptions(true))
    if (args.has(o.name)) return true;
  return false;
}

[[noreturn]] void refuseChangedInput(const std::string& capture, const std::string& what,
                                     const std::string& path) {
  throw Error(ErrorKind::Fixity, capture, "packing",
              what + ". An original is evidence: pack never records a new baseline for it. "
              "Restore the file from the card or a backup; if the change is deliberate, accept it "
              "with `surrogate run " + capture + " --accept-changed " + path + " --reason \"why\"`, then pack");
}

}  // namespace

int runCommandPack(int argc, char** argv) {
  std::vector<OptionSpec> specs = pipelineOptions(true);
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  specs.push_back({"o", true, false, "the package to write: a folder, NAME.tar or NAME.zip", "OUT"});
  specs.push_back({"output", true, false, "same as -o", "OUT"});
  specs.push_back({"no-report", false, false,
                   "when the pipeline runs, do not write finished-files/report.html"});
  std::vector<char*> rewritten(argv, argv + argc);  // the short "-o" as well as "--o"
  std::string longO = "--o";
  for (char*& a : rewritten)
    if (std::string(a) == "-o") a = longO.data();
  Args args(argc, rewritten.data(), 1, specs);
  if (args.helpRequested()) {
    std::cout << usageHeader(
                     "surrogate pack CAPTURE -o OUT [options]",
                     "Write the archival package of a capture: a BagIt 1.0 bag (a folder, or a "
                     ".tar or .zip by OUT's name) holding the untouched originals, the carrier, "
                     "the results, SHA-256 and SHA-512 manifests, and metadata/ with CIDOC-CRM "
                     "(crm.rdf), METS+PREMIS (mets.xml) and the stylesheets and schemas that "
                     "derive them. Runs the pipeline first (with the options below, as `surrogate "
                     "run`) when the capture has no complete carrier or its files changed. "
                     "SOURCE_DATE_EPOCH, when set, fixes every time in the package, so that two "
                     "packs of the same capture are byte-identical.\n\nexit codes: 0 packed, 1 bad "
                     "input (unreadable or changing file), 2 usage, 5 could not write (disk full, "
                     "permissions)")
              << Args::describe(specs);
    return 0;
  }
  const auto out = args.has("o") ? args.value("o") : args.value("output");
  if (args.positional().size() != 1 || !out || out->empty())
    throw Error(ErrorKind::Usage, "", "command line",
                "give the capture and the output: surrogate pack CAPTURE -o OUT (see --help)");
  const std::string capture = args.positional()[0];
  std::error_code ec;  // a symbolic-link loop is no folder either, not an internal error
  if (!std::filesystem::is_directory(capture, ec))
    throw Error(ErrorKind::Usage, capture, "command line",
                ec ? "cannot be read as a folder (" + ec.message() + "); give the capture folder"
                   : "is not a capture folder");

  archive::checkOutput(*out);  // before any long work
  capture::refuseOutputInside(capture, *out, "-o", /*anywhere=*/true);

  // One process at a time on the capture, for the whole pack: a run meanwhile would change
  // what is being bagged.
  capture::CaptureLock lock(capture, "pack");
  stages::recoverRun(capture);
  ProgressBar bar(args.has("quiet") || args.has("json"));
  bool ran = false;
  std::string why;
  const archive::CarrierState state = archive::checkCarrier(capture);
  if (!state.inputProblem.empty()) refuseChangedInput(capture, state.inputProblem, state.inputPath);
  const std::string outdated = state.complete ? outdatedStep(capture) : "";
  if (!state.complete || !outdated.empty() || givesDecisions(args)) {
    why = !state.complete ? state.reason : !outdated.empty() ? outdated : "new decisions were given";
    runPipeline(capture, args, bar);
    ran = true;
  }
  const archive::CarrierState after = ran ? archive::checkCarrier(capture) : state;
  if (!after.unrecordedOutputs.empty()) {
    std::string list;
    for (const std::string& f : after.unrecordedOutputs) list += "\n  " + f;
    throw Error(ErrorKind::Input, capture, "packing",
                "these files in the capture's output folders are not described by its carrier "
                "(Surrogate did not write them, or a run that wrote them was not recorded), and a "
                "package holds only what the carrier describes; move them out of the capture, "
                "then pack again:" + list);
  }
  archive::PackOptions options;
  options.progress = [&bar](std::uint64_t done, std::uint64_t total) {
    bar.update("packing", total ? static_cast<double>(done) / static_cast<double>(total) : 1.0);
  };
  archive::PackResult r;
  try {
    r = archive::packCapture(capture, *out, options);
  } catch (const archive::PayloadChanged& e) {
    const carrier::Carrier recorded = carrier::loadCarrier(std::filesystem::path(capture) / "assembly-files/carrier.xml");
    const carrier::FileRecord* f = recorded.findFileByPath(e.bagPath().substr(5));
    if (f && carrier::isEvidenceRole(f->role))
      refuseChangedInput(capture, e.bagPath().substr(5) + " no longer matches the SHA-256 its carrier records",
                         e.bagPath().substr(5));
    if (ran) {
      throw Error(ErrorKind::Input, e.source(), "packing",
                  "changed while the capture was being processed and packed; make sure nothing "
                  "else writes to the capture, then pack again");
    }
    why = e.bagPath().substr(5) + " no longer matches the carrier";
    runPipeline(capture, args, bar);
    ran = true;
    r = archive::packCapture(capture, *out, options);
  }
  bar.finish();

  const double mb = static_cast<double>(r.bag.payloadBytes) / 1e6;
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("capture").value(capture).key("package").value(*out)
        .key("format").value(archive::bagFormatName(r.bag.format))
        .key("pipelineRan").value(ran);
    j.key("pipelineReason");
    if (ran) j.value(why);
    else j.null();
    j.key("packageId").value(r.packageId).key("packagingTime").value(r.packagingTime)
        .key("payloadFiles").value(static_cast<unsigned long long>(r.bag.payloadFiles))
        .key("payloadBytes").value(static_cast<unsigned long long>(r.bag.payloadBytes))
        .key("payloadOxum").value(std::to_string(r.bag.payloadBytes) + "." +
                                  std::to_string(r.bag.payloadFiles))
        .key("seconds").value(r.bag.seconds)
        .key("megabytesPerSecond").value(r.bag.seconds > 0 ? mb / r.bag.seconds : 0.0);
    j.key("tagFiles").beginArray();
    for (const std::string& t : r.bag.tagFiles) j.value(t);
    j.endArray().key("removedLeftovers").beginArray();
    for (const std::string& t : r.bag.removedLeftovers) j.value(t);
    j.endArray().endObject();
    std::cout << j.str() << "\n";
  } else {
    if (ran)
      std::cout << "Processed " << capture << " first (" << why << "), with the decisions its "
                << "carrier records (see `surrogate info " << capture << "`).\n";
    for (const std::string& removed : r.bag.removedLeftovers)
      std::cout << char(std::toupper(static_cast<unsigned char>(removed[0]))) << removed.substr(1) << ".\n";
    char rate[64];
    std::snprintf(rate, sizeof rate, "%.1f MB in %.2f s", mb, r.bag.seconds);
    std::cout << "Packed " << capture << " into " << *out << " (BagIt 1.0, "
              << archive::bagFormatName(r.bag.format) << ").\n"
              << "  payload: " << r.bag.payloadFiles << " files, " << rate << "\n"
              << "  package id: " << r.packageId << "\n"
              << "  metadata: metadata/crm.rdf (CIDOC-CRM), metadata/mets.xml (METS+PREMIS)\n";
  }
  return 0;
}

}  // namespace surrogate::cli
