// surrogate verify PACKAGE [--reexecute] [--json]
#include <iostream>

#include "batch/batch.h"
#include "batch/ledger.h"
#include "batch/resume.h"
#include "batch/work_list.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "verify/verify.h"

namespace surrogate::cli {

namespace {

const char* verdict(int code) {
  switch (code) {
    case 0: return "sound";
    case 2: return "invalid package";
    case 3: return "fixity failure";
    case 4: return "not reproduced";
    default: return "error";
  }
}

// The two parts of the verdict, as words.
std::string bagitVerdict(const verify::Report& r) { return r.bagitValid() ? "valid" : "invalid"; }

std::string packageVerdict(const verify::Report& r) {
  if (r.surrogatePackage) return r.packageSound() ? "sound" : "not sound";
  return r.kind.empty() ? "not checked" : "not a Surrogate package";
}

// The failed checks of one part.
std::vector<std::string> failedChecks(const verify::Report& r, bool bagit) {
  std::vector<std::string> out;
  for (const verify::Check& c : r.checks)
    if (!c.passed && c.aboutBagIt() == bagit) out.push_back(c.name);
  return out;
}

void printJson(const verify::Report& report) {
  JsonWriter j;
  j.beginObject().key("package").value(report.package).key("kind").value(report.kind)
      .key("sound").value(report.sound()).key("exitCode").value(report.exitCode())
      .key("verdict").value(verdict(report.exitCode()))
      .key("reexecuted").value(report.reexecuted);
  j.key("bagit").beginObject().key("valid").value(report.bagitValid())
      .key("verdict").value(bagitVerdict(report)).key("failedChecks").beginArray();
  for (const std::string& name : failedChecks(report, true)) j.value(name);
  j.endArray().endObject();
  j.key("surrogatePackage").beginObject().key("is").value(report.surrogatePackage).key("sound");
  if (report.surrogatePackage) j.value(report.packageSound());
  else j.null();
  j.key("verdict").value(packageVerdict(report)).key("failedChecks").beginArray();
  for (const std::string& name : failedChecks(report, false)) j.value(name);
  j.endArray().endObject();
  j.key("warnings").beginArray();
  for (const std::string& w : report.warnings) j.value(w);
  j.endArray();
  j.key("softwareDifferences").beginArray();
  for (const std::string& s : report.softwareDifferences) j.value(s);
  j.endArray().key("holderFields").beginArray();
  for (const auto& [label, value] : report.holderFields)
    j.beginObject().key("label").value(label).key("value").value(value)
        .key("addedBy").value("holder").endObject();
  j.endArray().key("checks").beginArray();
  for (const verify::Check& c : report.checks) {
    j.beginObject().key("name").value(c.name).key("passed").value(c.passed)
        .key("severity").value(static_cast<int>(c.severity)).key("what").value(c.what);
    j.key("where").beginArray();
    for (const std::string& w : c.where) j.value(w);
    j.endArray().endObject();
  }
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}

// What a failure of `c` means, for --verbose.
std::string failureMeaning(const verify::Check& c) {
  const int code = static_cast<int>(c.severity);
  return std::string("a failure here: ") + verdict(code) + " (exit " + std::to_string(code) + ")";
}

// --quiet: the failed checks and the verdict line only; --verbose: each check with what its
// failure means.
void printText(const verify::Report& report, bool quiet, bool verbose = false) {
  if (!quiet)
    std::cout << "Verifying " << escapedText(report.package)
              << (report.kind.empty() ? "" : " (" + report.kind + ")") << "\n";
  std::size_t width = 0;
  for (const verify::Check& c : report.checks) width = std::max(width, c.name.size());
  for (const verify::Check& c : report.checks) {
    if (quiet && c.passed) continue;
    std::string name = c.name;
    name.resize(width, ' ');
    // Paths from a manifest are the package's text, whatever it holds: escaped (core/text.h).
    std::cout << (c.passed ? "  ok    " : "  FAIL  ") << name << "  " << escapedText(c.what, true) << "\n";
    for (const std::string& w : c.where) std::cout << "          " << escapedText(w, true) << "\n";
    if (verbose) std::cout << "          " << failureMeaning(c) << "\n";
  }
  if (!quiet && !report.holderFields.empty()) {
    std::cout << "bag-info.txt fields added by the holder (not written by Surrogate, not checked "
                 "against the carrier; the tag manifests cover them):\n";
    for (const auto& [label, value] : report.holderFields)
      std::cout << "  " << escapedText(label + ": " + value, true) << "  (added by the holder)\n";
  }
  if (!quiet && !report.softwareDifferences.empty()) {
    std::cout << "Software versions differ from the carrier's:\n";
    for (const std::string& s : report.softwareDifferences) std::cout << "  " << s << "\n";
  }
  if (!quiet && !report.warnings.empty()) {
    std::cout << "Warnings:\n";
    for (const std::string& w : report.warnings) std::cout << "  " << escapedText(w, true) << "\n";
  }
  // The two-part verdict: the bag, then what a Surrogate package adds.
  if (quiet) {
    const int code = report.exitCode();
    std::cout << (code == 0 ? (report.surrogatePackage ? "SOUND" : "VALID BAG") : report.surrogatePackage ? "NOT SOUND" : "NOT VALID")
              << ": " << escapedText(report.package) << " (" << report.checks.size() - report.failures() << " of "
              << report.checks.size() << " checks passed" << (report.reexecuted ? ", re-executed" : "")
              << (report.warnings.empty() ? "" : "; " + std::to_string(report.warnings.size()) + " warnings") << ")\n";
    return;
  }
  std::size_t bagitChecks = 0, ownChecks = 0;
  for (const verify::Check& c : report.checks) (c.aboutBagIt() ? bagitChecks : ownChecks) += 1;
  const std::size_t bagitFailed = failedChecks(report, true).size();
  const std::size_t ownFailed = failedChecks(report, false).size();
  std::cout << "BagIt: " << bagitVerdict(report);
  if (bagitFailed) std::cout << " (" << bagitFailed << " of " << bagitChecks << " checks failed)";
  std::cout << "\nSurrogate package: " << packageVerdict(report);
  if (!report.surrogatePackage)
    std::cout << (report.kind.empty() ? " (the package could not be read)"
                                      : " (made by another tool: its BagIt verdict is the whole verdict)");
  else if (ownFailed)
    std::cout << " (" << ownFailed << " of " << ownChecks << " checks failed)";
  else if (bagitFailed)
    std::cout << " (a package that is not a valid bag is not sound)";
  std::cout << "\n";
  const int code = report.exitCode();
  if (code == 0 && report.surrogatePackage)
    std::cout << "SOUND: all " << report.checks.size() << " checks passed"
              << (report.reexecuted ? ", including re-execution" : "") << ".\n";
  else if (code == 0)
    std::cout << "VALID BAG: all " << report.checks.size() << " checks passed; it is not a "
              << "Surrogate package, so there is no more to check.\n";
  else
    std::cout << (report.surrogatePackage ? "NOT SOUND (" : "NOT VALID (") << verdict(code)
              << ", exit " << code << "): " << report.failures() << " of "
              << report.checks.size() << " checks failed.\n";
}

// verify --batch LIST -o LEDGER: the packages of the list, each verified by `surrogate verify`
// in a process of its own (batch/batch.h), a ledger line each; --sample N of those not yet
// verified.
int verifyBatch(const Args& args) {
  const auto ledger = outputOption(args);
  if (!ledger || ledger->empty() || !args.positional().empty())
    throw Error(ErrorKind::Usage, "--batch", "command line",
                "give the list and the ledger only: surrogate verify --batch LIST -o LEDGER (see --help)");
  batch::checkLedgerTarget(*ledger, *args.value("batch"));  // appending is writing: the output rule
  std::vector<batch::WorkItem> items = batch::readWorkList(*args.value("batch"));
  for (batch::WorkItem& item : items) item.isPackage = true;  // verify takes each as a package
  batch::BatchOptions o;
  o.ledger = *ledger;
  o.steps = {"verify"};
  o.reexecute = args.has("reexecute");
  o.jobs = args.intValue("jobs", 1);
  if (o.jobs < 1) throw Error(ErrorKind::Usage, "--jobs", "command line", "give 1 or more jobs");
  o.threadsPerJob = args.intValue("threads", 0);
  if (args.has("strict") || args.has("tolerance"))
    throw Error(ErrorKind::Usage, args.has("strict") ? "--strict" : "--tolerance", "command line",
                "is not taken with --batch (each package is verified with the defaults)");
  if (args.has("sample")) {
    const int n = args.intValue("sample", 0);
    const int seed = args.intValue("seed", 1);
    if (n < 1) throw Error(ErrorKind::Usage, "--sample", "command line", "give the number of packages to verify, 1 or more");
    std::vector<std::string> paths;
    for (const batch::WorkItem& item : items) paths.push_back(item.path);
    const std::vector<std::size_t> open = batch::notYetVerified(paths, batch::readLedger(*ledger), o.reexecute);
    std::vector<batch::WorkItem> drawn;
    for (std::size_t k : batch::drawSample(open.size(), static_cast<std::size_t>(n), static_cast<std::uint64_t>(seed)))
      drawn.push_back(items[open[k]]);
    if (!args.has("quiet") && !args.has("json"))
      std::cout << "Sample of " << drawn.size() << " package(s), drawn with seed " << seed << " from the "
                << open.size() << " of " << items.size() << " the ledger does not record as verified.\n";
    items = std::move(drawn);
  } else if (args.has("seed")) {
    throw Error(ErrorKind::Usage, "--seed", "command line", "goes with --sample N");
  }
  const bool quiet = args.has("quiet") || args.has("json");
  if (const std::string note = batch::listFolderNote(*args.value("batch"), items); !quiet && !note.empty())
    std::cout << note << "\n";
  std::size_t sound = 0;
  std::vector<std::pair<std::string, std::string>> failures;
  ProgressBar bar(quiet);
  o.jobFinished = [&](const batch::JobReport& r) {
    const batch::StepOutcome* s = r.steps.empty() ? nullptr : &r.steps.back();
    if (r.succeeded) ++sound;
    else failures.emplace_back(r.item.path, s ? s->message : "");
    if (quiet) return;
    bar.finish();
    std::cout << (r.succeeded ? "  ok    " : "  FAIL  ") << escapedText(r.item.path) << "  "
              << escapedText(!s ? "" : s->outcome == "skipped" ? "sound (verified before, unchanged since)"
                                     : r.succeeded ? "sound" : s->message, true)
              << std::endl;
  };
  o.progress = [&](std::size_t done, std::size_t total) {
    bar.update("verifying: " + std::to_string(done) + " of " + std::to_string(total) + " packages",
               total ? static_cast<double>(done) / static_cast<double>(total) : 1.0);
  };
  const batch::BatchResult r = items.empty() ? batch::BatchResult{} : batch::runBatch(items, o);
  bar.finish();
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("ledger").value(*ledger).key("packages").value(static_cast<unsigned long long>(r.items))
        .key("sound").value(static_cast<unsigned long long>(sound)).key("exitCode").value(r.exitCode);
    j.key("failures").beginArray();
    for (const auto& [package, message] : failures)
      j.beginObject().key("package").value(package).key("message").value(message).endObject();
    j.endArray().endObject();
    std::cout << j.str() << "\n";
  } else {  // --quiet too: the verdict line
    std::cout << r.items << " package(s): " << sound << " sound, " << failures.size() << " not; ledger "
              << escapedText(*ledger) << "\n";
  }
  return r.exitCode;
}

}  // namespace

int runCommandVerify(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"reexecute", false, false,
       "also run the recorded steps again on the bagged originals and compare the results"},
      {"tolerance", true, false,
       "relative tolerance for recorded numbers when re-executing (default 0: exactly equal)", "REL"},
      {"threads", true, false, "threads for re-execution, 1 or more (default or 0: all cores)", "N"},
      {"strict", false, false,
       "count files the operating system leaves (.DS_Store, Thumbs.db, ._*) and no manifest lists as fixity "
       "failures (default: warnings, with the command to remove them)"},
      {"quiet", false, false, "no progress bar; print only the failed checks and the verdict line", "",
       OptionGroup::Output},
      {"verbose", false, false, "also say under each check what its failure means (invalid package, fixity "
                                "failure, not reproduced) and its exit code", "", OptionGroup::Output},
      {"json", false, false, "print the report as JSON", "", OptionGroup::Output},
      {"batch", true, false,
       "verify every package of LIST (a text file, or - for standard input, one package a line), each in a "
       "process of its own, writing the ledger -o (as surrogate batch --do verify)",
       "LIST", OptionGroup::Input},
      {"jobs", true, false, "with --batch: packages verified at a time (default 1)", "N"},
      {"sample", true, false,
       "with --batch: verify only N packages, drawn from those the ledger does not record as verified", "N"},
      {"seed", true, false, "with --sample: the draw's seed, so that a draw can be repeated (default 1)", "S"},
      {"o", true, false, "with --batch: the ledger, one JSON line per package and attempt", "LEDGER",
       OptionGroup::Output},
      {"output", true, false, "same as -o", "LEDGER", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate verify PACKAGE [--reexecute] [options]",
                 "Check that an archival package (a bag directory, .tar or .zip, or an OCFL object or E-ARK "
                 "SIP holding a bag: pack --layout ocfl or eark) is sound: BagIt fixity and completeness, every "
                 "file `surrogate pack` writes present (a package cut short is never sound), the bundled "
                 "stylesheets, schemas and tables identical to this Surrogate's, bag-info.txt against the "
                 "carrier (fields Surrogate did not write are listed as added by the holder), the carrier "
                 "against its schema, the files it lists and the steps this build can run, METS/PREMIS and "
                 "CIDOC-CRM metadata against what the bundled stylesheets derive from the carrier; with "
                 "--reexecute, the recorded steps are run again on the bagged originals in a temporary folder "
                 "($TMPDIR) and every recorded result is compared. Archives are read without extracting; unsafe "
                 "entries (.., absolute paths, links, devices, duplicates, decompression bombs) refuse the "
                 "package. A bag that another tool made is verified as a bag (RFC 8493 and its drafts "
                 "0.93-0.97: manifests in any digest OpenSSL offers, md5 and sha1 with a warning, md5sum's '*' "
                 "marker, 0.97 repeats and repeated Bagging-Date with a warning, tag files in the encoding "
                 "bagit.txt names, fetch.txt) and its exit code is its BagIt verdict. Files an operating system "
                 "leaves (.DS_Store, ._*, Thumbs.db) that no manifest lists are set aside with a warning and the "
                 "command to remove them (--strict: fixity failures). The verdict has two parts: \"BagIt: "
                 "valid/invalid\" and \"Surrogate package: sound/not sound/not a Surrogate package\".",
                 {{"surrogate verify stela12.zip --reexecute",
                   "fixity, completeness, schemas and metadata of a package, and every recorded step run again on "
                   "the bagged originals and compared"},
                  {"surrogate verify --batch packages.txt -o fixity-2026.jsonl --sample 1000 --seed 2026",
                   "this year's fixity audit of 1000 packages of a list not yet checked, one ledger line each"}},
                 {{0, "sound (a bag that is not a Surrogate package: valid)"},
                  {1, "the package cannot be read (missing file); with --batch, " + std::string(kWriteRefused) +
                          " for the ledger"},
                  {2, "invalid or refused package (including steps that cannot run, resources of another version, "
                      "bag-info.txt that disagrees with the carrier), or bad usage"},
                  {3, "fixity failure: a file changed, is missing or unlisted, the package is incomplete, or the "
                      "archive is truncated or has data after its end"},
                  {4, "re-execution did not reproduce the recorded results"},
                  {5, kInternalError}}}))
    return 0;
  const Verbosity verbosity = verbosityOf(args);
  if (args.has("batch") && verbosity == Verbosity::Verbose)
    throw Error(ErrorKind::Usage, "--verbose", "command line",
                "is not taken with --batch (each package's checks are in the ledger); verify one package to see them");
  if (args.has("batch")) return verifyBatch(args);
  for (const char* name : {"o", "output", "jobs", "sample", "seed"})
    if (args.has(name))
      throw Error(ErrorKind::Usage, std::string("--") + name, "command line", "goes with --batch LIST only");
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line",
                "give exactly one package: surrogate verify PACKAGE [--reexecute] (see --help)");
  refuseCaptureForPackage(args.positional()[0], "verify");
  verify::VerifyOptions options;
  options.reexecute = args.has("reexecute");
  options.strict = args.has("strict");
  options.tolerance = args.doubleValue("tolerance", 0.0);
  if (!(options.tolerance >= 0 && options.tolerance < 1))
    throw Error(ErrorKind::Usage, "--tolerance", "command line",
                "give a relative tolerance between 0 and 1, e.g. 1e-9");
  options.threads = args.intValue("threads", 0);
  if (options.threads < 0)
    throw Error(ErrorKind::Usage, "--threads", "command line",
                "give a number of threads, 1 or more (0 or none: all cores), not " +
                    std::to_string(options.threads));
  ProgressBar bar(args.has("quiet") || args.has("json"));
  options.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  const verify::Report report = verify::verifyPackage(args.positional()[0], options);
  bar.finish();
  if (args.has("json")) printJson(report);
  else printText(report, verbosity == Verbosity::Quiet, verbosity == Verbosity::Verbose);
  return report.exitCode();
}

}  // namespace surrogate::cli
