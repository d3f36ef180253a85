#include "cli/option_checks.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <system_error>

#include "archive/bag.h"
#include "capture/capture.h"
#include "capture/output_rule.h"
#include "core/error.h"
#include "core/sphere_reference.h"
#include "core/text.h"
#include "stages/frame_checks.h"

namespace surrogate::cli {

namespace {

[[noreturn]] void usage(const std::string& option, const std::string& message) {
  throw Error(ErrorKind::Usage, option, "command line", message);
}

bool isControl(unsigned char c) { return c < 0x20 || c == 0x7f; }

// The value as it can be shown in a message: control bytes (and, in text that is not UTF-8,
// every byte above 0x7f) as \xNN.
std::string printable(const std::string& value, bool utf8) {
  std::string out;
  for (const unsigned char c : value) {
    if (isControl(c) || (!utf8 && c >= 0x80)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  return out;
}

// C1 control characters (U+0080..U+009F) are the UTF-8 pairs C2 80..C2 9F.
bool hasC1Control(const std::string& s) {
  for (std::size_t i = 0; i + 1 < s.size(); ++i)
    if (static_cast<unsigned char>(s[i]) == 0xC2 && static_cast<unsigned char>(s[i + 1]) >= 0x80 &&
        static_cast<unsigned char>(s[i + 1]) <= 0x9F)
      return true;
  return false;
}

// Every value goes into the carrier (XML, UTF-8) and some into bag-info.txt.
void checkText(const std::string& name, const std::string& value) {
  if (!isValidUtf8(value))
    usage(optionName(name) + " " + printable(value, false),
          "is not valid UTF-8 text (the bytes above 0x7F are shown as \\xNN); give the text "
          "in UTF-8, as a terminal with a UTF-8 locale does");
  if (std::any_of(value.begin(), value.end(), [](unsigned char c) { return isControl(c); }) ||
      hasC1Control(value))
    usage(optionName(name) + " " + printable(value, true),
          "contains a control character (a line break, tab or other invisible character, shown "
          "as \\xNN); give plain text on one line");
}

void checkMeasure(const std::string& name, const std::string& value, double low, double high,
                  const std::string& what) {
  const double v = parseNumberList(value, 1, optionName(name))[0];
  if (!(v >= low && v <= high)) {
    char range[64];
    std::snprintf(range, sizeof range, "from %g to %g", low, high);
    usage(optionName(name) + " " + value, std::string("must be a number ") + range + ": " + what);
  }
}

void checkSphere(const std::string& value) {
  const std::vector<double> v = parseNumberList(value, 3, "--sphere");
  const std::string why = stages::sphereCircleProblem(v[0], v[1], v[2]);
  if (!why.empty()) usage("--sphere " + value, why + "; give the sphere's circle as CX,CY,R in pixels");
}

void checkHighlight(const std::string& value) {
  const std::string option = "--highlight " + value;
  const auto eq = value.find('=');
  if (eq == std::string::npos) usage(option, "needs the form IMAGE:sphereN=X,Y (sphere1 is the first sphere)");
  const std::string target = value.substr(0, eq);
  const auto colon = target.rfind(':');
  const std::string image = colon == std::string::npos ? target : target.substr(0, colon);
  if (image.empty())
    usage(option, "names no image; give the form IMAGE:sphereN=X,Y, e.g. IMG_0004:sphere1=326,70");
  if (colon != std::string::npos) {
    const std::string sphere = target.substr(colon + 1);
    if (!sphereIndexOfReference(sphere))
      usage(option, "the sphere in IMAGE:sphereN=X,Y must be sphere1 for the first sphere, sphere2 for the second "
                    "(or its index from 0), not \"" + sphere + "\"");
  }
  const std::vector<double> v = parseNumberList(value.substr(eq + 1), 2, "--highlight");
  const std::string why = stages::highlightPointProblem(v[0], v[1]);
  if (!why.empty()) usage(option, why + "; give X,Y in pixels of the full frame");
}

void checkRegion(const std::string& value) {
  const std::vector<double> v = parseNumberList(value, 4, "--sphere-roi");
  const std::string why = stages::frameRegionProblem(v[0], v[1], v[2], v[3]);
  if (!why.empty()) usage("--sphere-roi " + value, why + "; give the region as X,Y,W,H in pixels");
}

void checkMeta(const std::string& value) {
  const auto eq = value.find('=');
  if (eq == std::string::npos || eq == 0) usage("--meta " + value, "needs the form KEY=VALUE");
  const std::string key = value.substr(0, eq);
  const std::string why = archive::bagInfoLabelProblem(key);
  if (!why.empty())
    usage("--meta " + value, "the key becomes a label of the package's bag-info.txt, and \"" + key +
                                 "\" " + why);
}

}  // namespace

void checkPipelineOptionValues(const Args& args) {
  for (const auto& [name, value] : args.ordered()) checkText(name, value);
  for (const auto& [name, value] : args.ordered()) {
    if (name == "sphere") checkSphere(value);
    else if (name == "highlight") checkHighlight(value);
    else if (name == "sphere-roi") checkRegion(value);
    else if (name == "meta") checkMeta(value);
    else if ((name == "exclude" || name == "creator") && value.empty())
      usage(optionName(name) + " \"\"", name == "exclude" ? "needs the name of an image, e.g. IMG_0003"
                                                     : "needs a name, e.g. \"Ana Silva:photographer\"");
  }
  if (const auto m = args.value("light-model"); m && *m != "orthographic" && *m != "perspective")
    usage("--light-model " + *m, "use orthographic or perspective");
  if (const auto f = args.value("focal-length"))
    checkMeasure("focal-length", *f, kMinFocalLengthMm, kMaxFocalLengthMm,
                 "the lens focal length in millimetres, e.g. 50");
  if (const auto p = args.value("pixel-pitch"))
    checkMeasure("pixel-pitch", *p, kMinPixelPitchMm, kMaxPixelPitchMm,
                 "the sensor's pixel pitch in millimetres, e.g. 0.006 for 6 micrometres");
  if (const auto d = args.value("sphere-diameter"))
    checkMeasure("sphere-diameter", *d, kMinSphereDiameterMm, kMaxSphereDiameterMm,
                 "the real sphere's diameter in millimetres, e.g. 25");
}

int threadsOption(const Args& args) {
  const auto v = args.value("threads");
  if (!v) return 0;
  const int n = args.intValue("threads", 0);  // Error(Usage) for anything but a whole number
  if (n < 0 || n > kMaxThreads)
    usage("--threads " + *v, "needs a number of worker threads from 1 to " + std::to_string(kMaxThreads) +
                                 ", or 0 for all cores (the default)");
  return n;
}

void checkOutputFile(const std::string& option, const std::filesystem::path& output,
                     const std::string& example) {
  namespace fs = std::filesystem;
  const std::string named = option + " " + output.string();
  if (output.empty()) usage(option, "needs the name of the file to write");
  std::error_code ec;
  if (fs::is_directory(output, ec))
    usage(named, "is a folder; give the name of the file to write, e.g. " + (output / example).string());
  if (!output.has_filename())
    usage(named, "ends in a folder separator; give the name of the file to write");
  const fs::path parent = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  const fs::file_status st = fs::status(parent, ec);
  if (!fs::exists(st))
    usage(named, "is in the folder " + parent.string() + ", which does not exist; create it first (mkdir -p " +
                     parent.string() + ") or write elsewhere");
  if (!fs::is_directory(st))
    usage(named, "is in " + parent.string() + ", which is not a folder; write elsewhere");
  capture::checkOutputTarget(output, option, capture::ExistingOutput::ReplaceOutput);
}

namespace {
// The folders a capture holds, by the names capture/capture.h gives them.
const char* const kCaptureFolders[] = {capture::kSourceFolders[0], capture::kSourceFolders[1],
                                       capture::kSourceFolders[2], capture::kAssemblyDir, capture::kFinishedDir};

// `path` as the user typed it, without trailing separators ("CAPTURE/original-captures/").
std::filesystem::path withoutTrailingSlash(const std::filesystem::path& path) {
  std::string text = path.string();
  while (text.size() > 1 && text.back() == '/') text.pop_back();
  return text;
}

bool hasCaptureFolder(const std::filesystem::path& folder) {
  std::error_code ec;
  for (const char* dir : kCaptureFolders)
    if (std::filesystem::is_directory(folder / dir, ec)) return true;
  return false;
}
}  // namespace

void refuseCaptureSubfolder(const std::filesystem::path& folder, const std::string& command) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec) || hasCaptureFolder(folder)) return;
  const std::filesystem::path given = withoutTrailingSlash(folder);
  const std::string name = given.filename().string();
  if (std::none_of(std::begin(kCaptureFolders), std::end(kCaptureFolders), [&](const char* d) { return name == d; }))
    return;
  // The parent as the user can type it: "." when the folder was given by its name alone.
  std::filesystem::path parent = given.parent_path();
  if (parent.empty()) parent = ".";
  throw Error(ErrorKind::Usage, escapedText(given.string()), "command line",
              "is the " + name + " folder of a capture; " + command + " works on the capture folder, its parent: "
              "surrogate " + command + " " + escapedText(parent.string()));
}

void refuseCaptureForPackage(const std::filesystem::path& path, const std::string& command) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec) || std::filesystem::exists(path / "bagit.txt", ec)) return;
  if (!std::filesystem::is_regular_file(path / capture::kCarrierPath, ec) && !capture::hasSourceFolder(path)) return;
  const std::string name = escapedText(withoutTrailingSlash(path).string());
  throw Error(ErrorKind::Usage, name, "command line",
              "is a capture, not a package: pack it first with surrogate pack " + name + " -o OUT, then " +
                  command + " OUT");
}

}  // namespace surrogate::cli
