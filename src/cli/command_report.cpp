// surrogate report PACKAGE|CAPTURE -o report.html: the self-contained HTML report.
#include <iostream>
#include <optional>

#include "capture/capture.h"
#include "capture/lock.h"
#include "carrier/summary.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/progress.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "core/json.h"
#include "report/report.h"
#include "verify/verify.h"

namespace surrogate::cli {

int runCommandReport(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"verify", false, false, "verify the package first and show the result of every check"},
      {"reexecute", false, false, "with --verify: also re-execute the recorded steps (slow)"},
      {"o", true, false, "the HTML file to write", "FILE.html", OptionGroup::Output},
      {"output", true, false, "same as -o", "FILE.html", OptionGroup::Output},
      {"max-image-side", true, false, "longest side of the embedded pictures in pixels (default 720)", "N", OptionGroup::Output},
      {"relight-side", true, false, "longest side of each model's interactive copy in pixels (default 1200)", "N", OptionGroup::Output},
      {"quiet", false, false, "no progress bar, and at most one summary line", "", OptionGroup::Output},
      {"verbose", false, false, "also list every check of --verify and every warning of the record", "", OptionGroup::Output},
      {"json", false, false, "print what the report shows as JSON", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate report PACKAGE|CAPTURE -o FILE.html [options]",
                 "Write a self-contained HTML report (one file, no network access) of a processed capture "
                 "folder or a package (bag directory, .tar or .zip, or an OCFL object or E-ARK SIP): light "
                 "directions and coverage gaps, "
                 "sphere detection, normals, albedo, previews, an interactive relighting view, the provenance "
                 "timeline and the camera; with --verify, the verifier's result per check. surrogate run "
                 "writes one to CAPTURE/finished-files/report.html.",
                 {{"surrogate report stela12.zip -o stela12-report.html",
                   "the report of a package, read without extracting it"},
                  {"surrogate report stela12.zip --verify -o checked.html",
                   "the same, with the verifier's result for every check"}},
                 commonExitCodes("the report is written, whatever the checks found (surrogate verify gives the verdict)",
                                 {{3, "a package archive truncated or damaged"}})}))
    return 0;
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out)
    throw Error(ErrorKind::Usage, "", "command line",
                "give the capture or package and the output: surrogate report CAPTURE -o report.html");
  checkOutputFile("-o", *out, "report.html");
  report::ReportOptions options;
  options.maxImageSide = args.intValue("max-image-side", options.maxImageSide);
  options.relightMaxSide = args.intValue("relight-side", options.relightMaxSide);
  if (options.maxImageSide < 16 || options.relightMaxSide < 16)
    throw Error(ErrorKind::Usage, "--max-image-side/--relight-side", "command line", "needs at least 16 pixels");

  const Verbosity verbosity = verbosityOf(args);
  ProgressBar bar(verbosity == Verbosity::Quiet || args.has("json"));
  // A capture is read under a reader's lock: a run committing meanwhile would show half of
  // one record and half of the next.
  std::optional<capture::CaptureLock> lock;
  const std::filesystem::path input = args.positional()[0];
  std::error_code ec;
  if (std::filesystem::is_directory(input / capture::kAssemblyDir, ec))
    lock.emplace(input, "report", capture::CaptureLock::Shared{});
  const auto source = report::openReportSource(args.positional()[0], bar.callback());
  if (args.has("reexecute") && !args.has("verify"))
    throw Error(ErrorKind::Usage, "--reexecute", "command line", "goes with --verify");
  if (args.has("verify")) {
    if (!source->isPackage())
      throw Error(ErrorKind::Usage, args.positional()[0], "command line",
                  "is a capture folder: --verify checks a package (surrogate pack makes one)");
    verify::VerifyOptions vo;
    vo.reexecute = args.has("reexecute");
    vo.progress = bar.callback();
    const verify::Report verified = verify::verifyPackage(args.positional()[0], vo);
    bar.finish();
    std::vector<report::VerificationCheck> checks;
    for (const verify::Check& c : verified.checks) {
      std::string detail = c.what;
      for (const std::string& w : c.where) detail += (detail.empty() ? "" : "; ") + w;
      checks.push_back({c.name, c.passed, detail});
    }
    options.verification = checks;
  }
  options.progress = bar.callback();
  const report::Report r = report::buildReport(source->carrier(), *source, options);
  bar.finish();
  writeFileAtomically(*out, r.html);
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("source").value(source->describe())
        .key("lights").value(r.lightsPlotted).key("pictures").value(r.picturesEmbedded)
        .key("relightable").value(r.relightable).key("coverageGaps").beginArray();
    for (const std::string& g : r.coverageGaps) j.value(g);
    j.endArray().key("bytes").value(static_cast<unsigned long long>(r.html.size())).key("verification");
    if (options.verification) {
      int failed = 0;
      for (const report::VerificationCheck& c : *options.verification) failed += !c.passed;
      j.beginObject().key("checks").value(static_cast<int>(options.verification->size()))
          .key("failed").value(failed).endObject();
    } else {
      j.null();
    }
    j.endObject();
    std::cout << j.str() << "\n";
  } else {
    std::cout << "wrote " << *out << " (" << r.lightsPlotted << " lights, " << r.picturesEmbedded
              << " pictures" << (r.relightable ? ", interactive relighting" : "") << ", "
              << r.html.size() / 1024 << " KiB)\n";
    if (verbosity == Verbosity::Quiet) return 0;
    for (const std::string& g : r.coverageGaps) std::cout << "  coverage: " << g << "\n";
    if (options.verification) {
      int failed = 0;
      for (const report::VerificationCheck& c : *options.verification) failed += !c.passed;
      std::cout << "  verification: " << options.verification->size() << " checks, " << failed
                << " failed (details in the report; surrogate verify gives the verdict as its exit code)\n";
      // Verbose: each check as the page shows it, names from the package escaped.
      if (verbosity == Verbosity::Verbose)
        for (const report::VerificationCheck& c : *options.verification)
          std::cout << "    " << (c.passed ? "ok   " : "FAIL ") << escapedText(c.name)
                    << (c.detail.empty() ? "" : ": " + escapedText(c.detail)) << "\n";
    }
    // Verbose: the record's warnings, every one (the page shows them in its provenance).
    if (verbosity == Verbosity::Verbose) {
      const carrier::CarrierSummary summary = carrier::describeCarrier(source->carrier());
      if (summary.warnings.empty()) std::cout << "  warnings: none in the record\n";
      else printWarnings(summary, 0, "");
    }
  }
  return 0;
}

}  // namespace surrogate::cli
