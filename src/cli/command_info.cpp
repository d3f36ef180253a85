// surrogate info FILE: which kind of file it is (a package, carrier, capture folder, image,
// .xmp sidecar, .ptm, .rti, .lp, RTIBuilder log or web layout), then that concern's summary
// printed as text or JSON (info_carrier.cpp, info_folders.cpp, info_images.cpp).
#include <filesystem>
#include <iostream>
#include <sstream>
#include <system_error>

#include "audit/rtibuilder_log.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/info_print.h"
#include "cli/version_text.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/summary.h"
#include "verify/held_bag.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// Whether `path` is a package: a folder with bagit.txt, an OCFL object or an E-ARK SIP, or a
// .tar or .zip file.
bool isPackage(const fs::path& path, const fs::file_status& st) {
  std::error_code ec;
  if (fs::is_directory(st))
    return fs::exists(path / "bagit.txt", ec) || verify::holdsBagInLayout(path);
  const std::string ext = lowerCase(path.extension().string());
  return fs::is_regular_file(st) && (ext == ".tar" || ext == ".zip");
}

// The folder `surrogate publish` writes for one model: an info.json, and none of a capture's
// folders (a capture is described as one even if someone left an info.json in it).
bool isWebLayoutFolder(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path / "info.json", ec) && !fs::exists(path / capture::kAssemblyDir, ec) &&
         !fs::exists(path / "original-captures", ec) && !fs::exists(path / capture::kExportsDir, ec);
}

// Sends std::cout to `sink` (nullptr: nowhere, for --quiet) while it lives, when `active`: restored
// on an exception too, and the failure state that writing with no buffer sets cleared.
class CoutTo {
 public:
  explicit CoutTo(std::streambuf* sink, bool active = true)
      : saved_(active ? std::cout.rdbuf(sink) : nullptr), active_(active) {}
  ~CoutTo() {
    if (active_) {
      std::cout.rdbuf(saved_);
      std::cout.clear();
    }
  }
  CoutTo(const CoutTo&) = delete;
  CoutTo& operator=(const CoutTo&) = delete;

 private:
  std::streambuf* saved_;
  bool active_;
};

// --verbose: every file the carrier records, as a fixity list a person can compare by eye.
void printRecordedFiles(const carrier::Carrier& c) {
  std::cout << "  recorded files (role, size, SHA-256):\n";
  for (const carrier::FileRecord& f : c.files)
    std::cout << "    " << escapedText(f.path) << "  " << f.role << ", " << f.size << " bytes, " << f.sha256 << "\n";
}

// What info prints for `path`, by its kind.
void describe(const fs::path& path, const fs::file_status& st, const std::string& ext, bool json) {
  std::error_code ec;
  if (isPackage(path, st)) {
    printPackage(path, json);
  } else if (fs::is_directory(st) && isWebLayoutFolder(path)) {
    printWebLayout(path / "info.json", json);
  } else if (fs::is_directory(st)) {
    if (fs::exists(path / capture::kAssemblyDir / "carrier.xml", ec) && !json) {
      printCapture(path, false);
      printCarrier(path / capture::kAssemblyDir / "carrier.xml", false);  // JSON: nested by printCapture
    } else {
      printCapture(path, json);
    }
  } else if (path.filename() == "info.json") {
    printWebLayout(path, json);
  } else if (ext == ".xml" && audit::looksLikeRtiBuilderLog(path)) {
    const audit::RtiBuilderLog log = audit::readRtiBuilderLog(path);
    std::cout << (json ? log.toJson() : log.toText()) << "\n";
  } else if (ext == ".xml") {
    printCarrier(path, json);
  } else if (ext == ".xmp") {
    printXmpSidecar(path, json);
  } else if (ext == ".ptm" || ext == ".rti" || ext == ".lp") {
    const formats::FileSummary s = formats::summarize(path);
    std::cout << (json ? s.toJson() : s.toText()) << "\n";
  } else {
    printImage(path, json);
  }
}
}  // namespace

int runCommandInfo(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"json", false, false, "print as JSON (with Surrogate's version and its libraries' as \"version\")", "",
       OptionGroup::Output},
      {"quiet", false, false, "print nothing but errors: the exit code says whether the file could be described",
       "", OptionGroup::Output},
      {"verbose", false, false, "of a capture or carrier, also every file the carrier records, with its role, size "
                                "and SHA-256", "", OptionGroup::Output}};
  Args args(argc, argv, 1, specs);
  const Verbosity verbosity = verbosityOf(args);
  if (helpShown(args, specs,
                {"surrogate info FILE",
                 "Describe a package (a bag folder, .tar or .zip, or the bag an OCFL object or E-ARK SIP "
                 "holds: what it holds by role, who made it when, the "
                 "steps, decisions and results, and the command to verify it), a carrier (carrier.xml: "
                 "creators, metadata, steps, decisions with who, when and why, runs, warnings), a capture "
                 "folder, an image (camera, lens, exposure, date; also one Surrogate cannot decode), an .xmp "
                 "sidecar, a .ptm, .rti or .lp file, RTIBuilder's log XML (what its processing used and "
                 "found), or a web layout (the folder surrogate publish writes, or its info.json). Reads only.",
                 {{"surrogate info stela12", "the capture's record: decisions, runs and every warning"},
                  {"surrogate info stela12.zip --json", "what a package holds, as JSON for a script"}},
                 {{0, "described"},
                  {1, "bad input: a file that cannot be read or described (the message names it)"},
                  {2, "bad usage (an unknown option, a missing or malformed value), or a package that is not "
                      "one: not a bag, .tar or .zip, an OCFL object or E-ARK SIP that cannot be read as one"},
                  {3, "a package archive truncated or damaged"},
                  {5, kInternalError}}}))
    return 0;
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line", "give one file or folder: surrogate info FILE");
  const fs::path path = args.positional()[0];
  const bool json = args.has("json");
  if (verbosity == Verbosity::Quiet && json)
    throw Error(ErrorKind::Usage, "--quiet", "command line", "does not go with --json: give one of them");
  // --quiet: everything is read and checked as without it; only what it prints is dropped.
  CoutTo quiet(nullptr, verbosity == Verbosity::Quiet);
  // Error codes, not exceptions: a loop of symbolic links is the user's path, not a bug.
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec == std::errc::too_many_symbolic_link_levels)
    throwInputError(path.string(), "info", "is a loop of symbolic links; give the file or folder itself");
  if (!fs::exists(st)) throwInputError(path.string(), "info", "does not exist");
  const std::string ext = lowerCase(path.extension().string());
  if (json) {
    // One JSON object, with the version of the program that read it (and its libraries, as
    // every run records them) as "version": cli/version_text.h.
    std::ostringstream object;
    {
      CoutTo capture(object.rdbuf());
      describe(path, st, ext, true);
    }
    std::string text = object.str();
    while (!text.empty() && text.back() == '\n') text.pop_back();
    std::cout << withVersion(text) << "\n";
  } else {
    describe(path, st, ext, false);
  }
  if (verbosity == Verbosity::Verbose && !json) {
    const fs::path carrierFile = fs::is_directory(st) ? path / capture::kAssemblyDir / "carrier.xml" : path;
    if ((fs::is_directory(st) || ext == ".xml") && fs::is_regular_file(carrierFile, ec) &&
        !audit::looksLikeRtiBuilderLog(carrierFile))
      printRecordedFiles(carrier::loadCarrier(carrierFile));
  }
  return 0;
}

}  // namespace surrogate::cli
