// surrogate pack CAPTURE -o OUT [options]
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "archive/eark_layout.h"
#include "archive/ocfl_layout.h"
#include "archive/package.h"
#include "capture/capture.h"
#include "capture/lock.h"
#include "capture/output_rule.h"
#include "carrier/carrier.h"
#include "pipeline/stage.h"
#include "run/plan.h"
#include "run/run_commit.h"
#include "stages/registry.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/pipeline_options.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "report/report.h"

namespace surrogate::cli {

namespace {

// Runs the pipeline as `surrogate run` does, starting from the decisions the carrier records
// (the options of this command, if any, add to them), under the lock `pack` holds.
void runPipeline(const std::string& capture, const Args& args, ProgressBar& bar) {
  run::RunRequest request = requestFrom(args);
  request.command = "pack";
  const pipeline::RunSettings settings = settingsFrom(args, bar);
  run::runCapture(capture, request, settings, /*takeLock=*/false);
  if (!args.has("no-report")) {
    report::ReportOptions options;
    options.progress = bar.callback();
    report::writeCaptureReport(capture, options);
  }
}

// A step the carrier records with another version than this build's stage (the verifier
// would find the package invalid): the capture is processed again with its recorded decisions.
std::string outdatedStep(const std::string& capture) {
  stages::registerBuiltinStages();
  const carrier::Carrier c = carrier::loadCarrier(std::filesystem::path(capture) / capture::kCarrierPath);
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
              what + ". An original (or prior work another tool made) is evidence: pack never records a "
              "new baseline for it. "
              "Restore the file from the card or a backup; if the change is deliberate, accept it "
              "with `surrogate run " + escapedText(capture) + " --accept-changed " + escapedText(path) + " --reason \"why\"`, then pack");
}

std::vector<OptionSpec> packOptions() {
  constexpr OptionGroup kOutput = OptionGroup::Output;
  std::vector<OptionSpec> specs = {
      {"o", true, false, "the package to write: a folder, NAME.tar or NAME.zip", "OUT", kOutput},
      {"output", true, false, "same as -o", "OUT", kOutput},
      {"layout", true, false,
       "bag (the default: a BagIt bag, folder, .tar or .zip); ocfl: OUT is an OCFL 1.1 object holding the "
       "bag, made or given a new version (v2, v3, ...) by each pack of the same capture; eark: OUT is a new "
       "folder holding an E-ARK SIP 2.2 (METS.xml, representations/rep1/, metadata/, schemas/, documentation/)",
       "bag|ocfl|eark", kOutput},
      {"force", false, false, "replace an existing .tar or .zip of the same name", "", kOutput},
      {"bag-info", true, true,
       "a holder's field for bag-info.txt only, e.g. External-Identifier=INV-7 or "
       "Contact-Email=archive@museum.org (not recorded in the carrier: verify lists it as added by the holder)",
       "LABEL=VALUE", kOutput},
      {"base-uri", true, false,
       "mint crm.rdf's node URIs under this base, e.g. https://repository.example/capture/stela12/ (ends in / "
       "or #; recorded in bag-info.txt as Surrogate-Base-URI; default: under the capture identifier)",
       "URI", kOutput},
      {"no-report", false, false, "when the pipeline runs, do not write finished-files/report.html", "", kOutput},
  };
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  for (const OptionSpec& o : runOptionsForAnotherCommand()) specs.push_back(o);
  return specs;
}

// The layout of the package (--layout): "bag", "ocfl" or "eark".
std::string layoutOf(const Args& args) {
  const std::string layout = args.value("layout", "bag");
  if (layout != "bag" && layout != "ocfl" && layout != "eark")
    throw Error(ErrorKind::Usage, "--layout " + layout, "command line",
                "is not a layout pack writes: give bag (a BagIt bag, the default), ocfl (an OCFL "
                "object) or eark (an E-ARK SIP)");
  return layout;
}

// The capture folder and the package to write, checked before any long work.
std::pair<std::string, std::string> captureAndOutput(const Args& args) {
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out || out->empty())
    throw Error(ErrorKind::Usage, "", "command line",
                "give the capture and the output: surrogate pack CAPTURE -o OUT (see --help)");
  const std::string capture = args.positional()[0];
  refuseCaptureSubfolder(capture, "pack");
  std::error_code ec;  // a symbolic-link loop is no folder either, not an internal error
  // A capture that is not there is missing input (exit 1), as for run and lights.
  if (!std::filesystem::exists(std::filesystem::symlink_status(capture, ec)))
    throwInputError(capture, "command line", "the capture folder does not exist");
  if (!std::filesystem::is_directory(capture, ec))
    throw Error(ErrorKind::Usage, capture, "command line",
                ec ? "cannot be read as a folder (" + ec.message() + "); give the capture folder"
                   : "is not a capture folder");
  if (layoutOf(args) == "ocfl") {
    // An existing object is added to, never replaced (archive::packOcfl checks what it is).
    if (args.has("force"))
      throw Error(ErrorKind::Usage, "--force", "command line",
                  "does not go with --layout ocfl: an OCFL object is never replaced, each pack adds a version");
    capture::checkOutputTarget(*out, "-o", capture::ExistingOutput::Replace, capture::OutputPlace::OutsideCaptures);
    archive::checkPackageName(*out);
    return {capture, *out};
  }
  if (layoutOf(args) == "eark") {
    if (args.has("force") || archive::bagFormatFor(*out) != archive::BagFormat::Directory)
      throw Error(ErrorKind::Usage, args.has("force") ? "--force" : *out, "command line",
                  "--layout eark writes a SIP into a new or empty folder: give a folder name, without --force");
    capture::checkOutputTarget(*out, "-o", capture::ExistingOutput::Replace, capture::OutputPlace::OutsideCaptures);
    archive::checkOutput(*out);
    return {capture, *out};
  }
  capture::checkOutputTarget(*out, "-o",
                             args.has("force") ? capture::ExistingOutput::Replace : capture::ExistingOutput::Refuse,
                             capture::OutputPlace::OutsideCaptures, "give --force to replace it, or choose another name");
  archive::checkOutput(*out, args.has("force"));
  return {capture, *out};
}

// The holder's fields (--bag-info LABEL=VALUE), their form checked before any long work
// (packCapture checks them against the carrier's own labels too). They go into bag-info.txt
// only, not into the carrier (archive::holderFieldProblem says why).
std::vector<std::pair<std::string, std::string>> holderFields(const Args& args) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& given : args.values("bag-info")) {
    const auto eq = given.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error(ErrorKind::Usage, "--bag-info " + given, "command line",
                  "needs the form LABEL=VALUE, e.g. --bag-info External-Identifier=INV-7");
    const std::string label = given.substr(0, eq), value = given.substr(eq + 1);
    if (const std::string why = archive::holderFieldProblem(label, value); !why.empty())
      throw Error(ErrorKind::Usage, "--bag-info " + label, "command line",
                  "\"" + label + "\" " + why);
    out.emplace_back(label, value);
  }
  return out;
}

// Whether the pipeline ran first, and why.
struct Processing {
  bool ran = false;
  std::string why;
};

// Runs the pipeline when the capture's record is incomplete, outdated or given new decisions;
// then refuses output files its carrier does not describe (a package holds only those).
Processing processIfNeeded(const std::string& capture, const Args& args, ProgressBar& bar) {
  Processing p;
  const archive::CarrierState state = archive::checkCarrier(capture);
  if (!state.inputProblem.empty()) refuseChangedInput(capture, state.inputProblem, state.inputPath);
  const std::string outdated = state.complete ? outdatedStep(capture) : "";
  if (!state.complete || !outdated.empty() || givesDecisions(args)) {
    p.why = !state.complete ? state.reason : !outdated.empty() ? outdated : "new decisions were given";
    runPipeline(capture, args, bar);
    p.ran = true;
  }
  const archive::CarrierState after = p.ran ? archive::checkCarrier(capture) : state;
  if (!after.unrecordedOutputs.empty()) {
    std::string list;
    for (const std::string& f : after.unrecordedOutputs) list += "\n  " + f;
    throw Error(ErrorKind::Input, capture, "packing",
                "these files in the capture's output folders are not described by its carrier "
                "(Surrogate did not write them, or a run that wrote them was not recorded), and a "
                "package holds only what the carrier describes; run `surrogate run " + capture +
                    "` to record them as prior work (files another tool made), or move them out of "
                    "the capture, then pack again:" + list);
  }
  return p;
}

// Packs; when a result no longer matches its carrier, processes the capture again once and
// packs again (an original that changed is refused: it is evidence).
// `pack` is archive::packCapture or archive::packOcfl, given the capture, the output and the options.
template <class Pack>
auto packOnce(const std::string& capture, const std::string& out, const Args& args, ProgressBar& bar,
              Processing& processing, Pack pack) {
  archive::PackOptions options;
  options.replace = args.has("force");
  options.bagInfo = holderFields(args);
  if (const auto base = args.value("base-uri")) options.baseUri = *base;
  options.progress = [&bar](std::uint64_t done, std::uint64_t total) {
    bar.update("packing", total ? static_cast<double>(done) / static_cast<double>(total) : 1.0);
  };
  try {
    return pack(capture, out, options);
  } catch (const archive::PayloadChanged& e) {
    const std::string path = e.bagPath().substr(5);  // without "data/"
    const carrier::Carrier recorded = carrier::loadCarrier(std::filesystem::path(capture) / capture::kCarrierPath);
    const carrier::FileRecord* f = recorded.findFileByPath(path);
    if (f && carrier::isEvidenceRole(f->role))
      refuseChangedInput(capture, path + " no longer matches the SHA-256 its carrier records", path);
    if (processing.ran) {
      throw Error(ErrorKind::Input, e.source(), "packing",
                  "changed while the capture was being processed and packed; make sure nothing "
                  "else writes to the capture, then pack again");
    }
    processing.why = path + " no longer matches the carrier";
    runPipeline(capture, args, bar);
    processing.ran = true;
    return pack(capture, out, options);
  }
}

// What every layout's output says: the capture, the package, whether the pipeline ran first
// and why, the holder's fields and the leftovers of killed packs removed first.
struct PackReport {
  const std::string& capture;
  const std::string& out;
  const Processing& processing;
  const std::vector<std::pair<std::string, std::string>>& holder;
  const std::vector<std::string>& removedLeftovers;
};

// The members every layout's JSON begins with; the caller adds its own and ends with
// endPackJson.
void beginPackJson(JsonWriter& j, const PackReport& p, const std::string& format) {
  j.beginObject().key("capture").value(p.capture).key("package").value(p.out).key("format").value(format)
      .key("pipelineRan").value(p.processing.ran);
  j.key("pipelineReason");
  if (p.processing.ran) j.value(p.processing.why);
  else j.null();
}

void endPackJson(JsonWriter& j, const PackReport& p) {
  j.key("holderFields").beginArray();
  for (const auto& [label, value] : p.holder)
    j.beginObject().key("label").value(label).key("value").value(value).endObject();
  j.endArray().key("removedLeftovers").beginArray();
  for (const std::string& t : p.removedLeftovers) j.value(t);
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}

// `text` (a note holding paths) as a sentence of its own, its first letter capitalised, and
// its names' tabs, line breaks, other control characters and bytes that are not UTF-8 shown
// escaped (core/text.h).
void printSentence(const std::string& text) {
  const std::string shown = escapedText(text);
  if (shown.empty()) return;
  std::cout << char(std::toupper(static_cast<unsigned char>(shown[0]))) << shown.substr(1) << ".\n";
}

// The sentences before every layout's summary: why the pipeline ran, what leftovers went.
void printPackPreamble(const PackReport& p) {
  if (p.processing.ran)
    // The cause first, as what was found before this pack (an earlier run's failed step is not
    // this pack's), then what this pack did about it.
    std::cout << "Processed " << escapedText(p.capture) << " before packing it, because " << escapedText(p.processing.why)
              << "; every step of this processing completed, with the decisions its carrier records (see `surrogate "
              << "info " << escapedText(p.capture) << "`).\n";
  for (const std::string& removed : p.removedLeftovers) printSentence(removed);
}

void printHolderFields(const PackReport& p) {
  if (p.holder.empty()) return;
  std::cout << "  holder's fields in bag-info.txt (not in the carrier):";
  for (std::size_t i = 0; i < p.holder.size(); ++i) std::cout << (i ? ", " : " ") << p.holder[i].first;
  std::cout << "\n";
}

void printJson(const PackReport& p, const archive::PackResult& r) {
  const double mb = static_cast<double>(r.bag.payloadBytes) / 1e6;
  JsonWriter j;
  beginPackJson(j, p, archive::bagFormatName(r.bag.format));
  j.key("packageId").value(r.packageId).key("captureId").value(r.captureId);
  j.key("previousPackageId");
  if (r.previousPackageId.empty()) j.null();
  else j.value(r.previousPackageId);
  j.key("packagingTime").value(r.packagingTime)
      .key("payloadFiles").value(static_cast<unsigned long long>(r.bag.payloadFiles))
      .key("payloadBytes").value(static_cast<unsigned long long>(r.bag.payloadBytes))
      .key("payloadOxum").value(std::to_string(r.bag.payloadBytes) + "." +
                                std::to_string(r.bag.payloadFiles))
      .key("seconds").value(r.bag.seconds)
      .key("megabytesPerSecond").value(r.bag.seconds > 0 ? mb / r.bag.seconds : 0.0);
  j.key("tagFiles").beginArray();
  for (const std::string& t : r.bag.tagFiles) j.value(t);
  j.endArray();
  endPackJson(j, p);
}

void printSummary(const PackReport& p, const archive::PackResult& r, Verbosity verbosity) {
  if (verbosity == Verbosity::Quiet) {
    std::cout << "Packed " << escapedText(p.capture) << " into " << escapedText(p.out) << " (package id " << r.packageId << ").\n";
    return;
  }
  printPackPreamble(p);
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.1f MB in %.2f s", static_cast<double>(r.bag.payloadBytes) / 1e6,
                r.bag.seconds);
  std::cout << "Packed " << escapedText(p.capture) << " into " << escapedText(p.out) << " (BagIt 1.0, "
            << archive::bagFormatName(r.bag.format) << ").\n"
            << "  payload: " << r.bag.payloadFiles << " files, " << rate << "\n"
            << "  package id: " << r.packageId << "\n"
            << "  capture id: " << r.captureId << "\n"
            << (r.previousPackageId.empty() ? std::string()
                                            : "  revises the package " + r.previousPackageId +
                                                  " (made of this capture before its record changed)\n")
            << "  metadata: metadata/crm.rdf (CIDOC-CRM), metadata/mets.xml (METS+PREMIS), "
               "data/ro-crate-metadata.json (RO-Crate: the payload folder described as a crate)\n";
  printHolderFields(p);
  if (verbosity == Verbosity::Verbose)
    for (const std::string& t : r.bag.tagFiles) std::cout << "  tag file: " << t << "\n";
}

// --layout ocfl: the object, the version written (or none: the head holds this bag already),
// what it holds anew and what it takes from earlier versions.
void printOcflJson(const PackReport& p, const archive::OcflResult& r) {
  JsonWriter j;
  beginPackJson(j, p, "ocfl");
  j.key("objectId").value(r.objectId).key("version").value(r.version)
      .key("created").value(r.created).key("unchanged").value(r.unchanged)
      .key("newFiles").value(static_cast<unsigned long long>(r.newFiles))
      .key("newBytes").value(static_cast<unsigned long long>(r.newBytes))
      .key("reusedFiles").value(static_cast<unsigned long long>(r.reusedFiles))
      .key("packageId").value(r.pack.packageId).key("packagingTime").value(r.pack.packagingTime)
      .key("payloadFiles").value(static_cast<unsigned long long>(r.pack.bag.payloadFiles))
      .key("payloadBytes").value(static_cast<unsigned long long>(r.pack.bag.payloadBytes));
  j.key("notes").beginArray();
  for (const std::string& n : r.notes) j.value(n);
  j.endArray();
  endPackJson(j, p);
}

void printOcflSummary(const PackReport& p, const archive::OcflResult& r, Verbosity verbosity) {
  if (verbosity == Verbosity::Quiet) {
    std::cout << (r.unchanged ? "Unchanged: " : "Packed " + escapedText(p.capture) + " into ") << escapedText(p.out) << " version "
              << r.version << " (package id " << r.pack.packageId << ").\n";
    return;
  }
  printPackPreamble(p);
  for (const std::string& n : r.notes) printSentence(n);
  if (r.unchanged) {
    std::cout << escapedText(p.out) << " already holds this package as its head version " << r.version
              << " (the same bytes): no version added.\n";
    return;
  }
  std::cout << (r.created ? "Made the OCFL 1.1 object " : "Added a version to the OCFL object ") << escapedText(p.out)
            << ": " << r.version << ", the BagIt package of " << escapedText(p.capture) << ".\n"
            << "  object id: " << r.objectId << " (the capture identifier: every package of the capture is a version)\n"
            << "  new content: " << r.newFiles << " files, " << r.newBytes << " bytes"
            << (r.reusedFiles ? ", " + std::to_string(r.reusedFiles) + " unchanged files kept from earlier versions" : "")
            << "\n  package id: " << r.pack.packageId << "\n";
  printHolderFields(p);
}

// --layout eark: the SIP written and the bag it holds.
void printEarkJson(const PackReport& p, const archive::EarkResult& r) {
  JsonWriter j;
  beginPackJson(j, p, "eark");
  j.key("objectId").value(r.objectId).key("files").value(static_cast<unsigned long long>(r.files))
      .key("packageId").value(r.pack.packageId).key("packagingTime").value(r.pack.packagingTime)
      .key("payloadFiles").value(static_cast<unsigned long long>(r.pack.bag.payloadFiles))
      .key("payloadBytes").value(static_cast<unsigned long long>(r.pack.bag.payloadBytes));
  endPackJson(j, p);
}

void printEarkSummary(const PackReport& p, const archive::EarkResult& r, Verbosity verbosity) {
  if (verbosity == Verbosity::Quiet) {
    std::cout << "Packed " << escapedText(p.capture) << " into " << escapedText(p.out) << " (E-ARK SIP; package id " << r.pack.packageId << ").\n";
    return;
  }
  printPackPreamble(p);
  std::cout << "Packed " << escapedText(p.capture) << " into " << escapedText(p.out) << " (E-ARK SIP 2.2, " << r.files << " files).\n"
            << "  METS: " << escapedText(p.out) << "/METS.xml, representation " << escapedText(p.out) << "/representations/rep1/METS.xml\n"
            << "  payload: " << r.pack.bag.payloadFiles << " files in representations/rep1/data/\n"
            << "  package id: " << r.pack.packageId << "\n";
  printHolderFields(p);
}

}  // namespace

int runCommandPack(int argc, char** argv) {
  const std::vector<OptionSpec> specs = packOptions();
  Args args(argc, argv, 1, specs);  // Args takes -o as well as --o
  if (helpShown(args, specs,
                {"surrogate pack CAPTURE -o OUT [options]",
                 "Write the archival package of a capture: a BagIt 1.0 bag (a folder, or a .tar or .zip by "
                 "OUT's name; with --layout ocfl, a new version of the OCFL object in folder OUT; with --layout "
                 "eark, an E-ARK SIP in folder OUT) holding the untouched originals, the carrier, the results, "
                 "SHA-256 and SHA-512 manifests, README.txt, and metadata/ with CIDOC-CRM (crm.rdf), "
                 "METS+PREMIS (mets.xml) and the stylesheets and schemas that derive them. Runs the pipeline "
                 "first (with the options of `surrogate run`, listed last) when the capture has no complete "
                 "carrier or its files changed. SOURCE_DATE_EPOCH, when set, fixes every time in the package, "
                 "so that two packs of the same capture are byte-identical. --meta records metadata in the "
                 "carrier (the capture's record, checked by verify); --bag-info writes a holder's field into "
                 "bag-info.txt only.",
                 {{"surrogate pack stela12 -o stela12.zip",
                   "bag the capture stela12 into one zip file (processing it first if its record is not complete)"},
                  {"surrogate pack stela12 --layout ocfl -o repository/stela12",
                   "add the package as a new version of an OCFL object (made on the first pack)"}},
                 {{0, "packed"},
                  {1, "bad input: an unreadable file, or one that changed while it was packed; an OUT whose "
                      "name no package can have (not UTF-8, a control character, a backslash); or " +
                          std::string(kWriteRefused)},
                  {2, "bad usage: an unknown option, a missing or malformed value; with --layout ocfl, an "
                      "existing object that fails verify's OCFL checks (nothing is written)"},
                  {3, kChangedOriginal},
                  {5, kInternalError}}}))
    return 0;
  const auto [capture, out] = captureAndOutput(args);
  (void)holderFields(args);  // a malformed --bag-info is refused before any work
  if (const auto base = args.value("base-uri"))  // and a base URI crm.rdf cannot use
    if (const std::string why = archive::baseUriProblem(*base); !why.empty())
      throw Error(ErrorKind::Usage, "--base-uri " + *base, "command line", why);
  // One process at a time on the capture, for the whole pack: a run meanwhile would change
  // what is being bagged.
  capture::CaptureLock lock(capture, "pack");
  run::recoverRun(capture);
  const Verbosity verbosity = verbosityOf(args);
  ProgressBar bar(args.has("quiet") || args.has("json"));
  Processing processing = processIfNeeded(capture, args, bar);
  const auto holder = holderFields(args);
  const bool json = args.has("json");
  if (layoutOf(args) == "ocfl") {
    const archive::OcflResult r = packOnce(capture, out, args, bar, processing, archive::packOcfl);
    bar.finish();
    const PackReport p{capture, out, processing, holder, r.pack.bag.removedLeftovers};
    if (json) printOcflJson(p, r);
    else printOcflSummary(p, r, verbosity);
    return 0;
  }
  if (layoutOf(args) == "eark") {
    const archive::EarkResult r = packOnce(capture, out, args, bar, processing, archive::packEark);
    bar.finish();
    const PackReport p{capture, out, processing, holder, r.pack.bag.removedLeftovers};
    if (json) printEarkJson(p, r);
    else printEarkSummary(p, r, verbosity);
    return 0;
  }
  const archive::PackResult r = packOnce(capture, out, args, bar, processing, archive::packCapture);
  bar.finish();
  const PackReport p{capture, out, processing, holder, r.bag.removedLeftovers};
  if (json) printJson(p, r);
  else printSummary(p, r, verbosity);
  return 0;
}

}  // namespace surrogate::cli
