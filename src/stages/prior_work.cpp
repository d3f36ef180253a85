#include "stages/prior_work.h"

#include <cctype>

#include "capture/capture.h"
#include "carrier/xml.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/summary.h"
#include "pipeline/stage.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

using capture::kCarrierPath;
using capture::kReportPath;
// A processing log larger than this is recorded without reading its root element: RTIBuilder's
// logs are a few kilobytes, and the whole document is parsed to find the root.
constexpr std::uintmax_t kMaxLogBytes = 64u << 20;
// What madeBy keeps of a log's root attributes: enough for a tool's name, version and date,
// not a whole document someone put into an attribute.
constexpr std::size_t kMaxAttributeBytes = 200;
constexpr std::size_t kMaxAttributes = 8;

// `text` cut to at most `bytes` bytes, never inside a UTF-8 sequence (the carrier is UTF-8).
std::string utf8Prefix(const std::string& text, std::size_t bytes) {
  if (text.size() <= bytes) return text;
  std::size_t n = bytes;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
  return text.substr(0, n) + "...";
}

std::string kindOf(const std::string& extension) {
  if (extension == ".lp") return "lp";
  if (extension == ".ptm" || extension == ".rti") return "rti";
  if (extension == ".xml" || extension == ".log") return "log";
  return "other";
}

// The root element of a log XML and its attributes, as the file writes them.
std::string rootElementText(const fs::path& file, const std::string& relativePath) {
  std::error_code ec;
  if (fs::file_size(file, ec) > kMaxLogBytes)
    throwInputError(relativePath, "prior work", "is larger than a processing log Surrogate reads");
  const xml::RootElement root = xml::readRootElement(readFile(file, "prior work"), relativePath);
  std::string out = root.name;
  for (std::size_t i = 0; i < root.attributes.size() && i < kMaxAttributes; ++i)
    out += " " + root.attributes[i].first + "=\"" + utf8Prefix(root.attributes[i].second, kMaxAttributeBytes) + "\"";
  return out;
}

// Reads what the file's content says (see PriorFile); throws Error when it cannot be read as
// what its name says.
void readContent(const fs::path& file, const std::string& relativePath, PriorFile& out) {
  const std::string ext = lowerCase(fs::path(relativePath).extension().string());
  if (out.kind == "rti" || out.kind == "lp") {
    const formats::FileSummary s = formats::summarize(file);
    if (s.kind == "ptm") {
      out.format = s.format;
      out.mediaType = "application/x-ptm";
      out.madeBy = s.version + " " + s.format;
    } else if (s.kind == "rti") {
      out.format = "RTI_HSH";
      out.mediaType = "application/x-rti";
      out.madeBy = s.version;
    } else {
      out.format = "LP";
      out.mediaType = "text/plain";
    }
  } else if (ext == ".xml") {
    out.mediaType = "application/xml";
    out.madeBy = rootElementText(file, relativePath);
  }
}

}  // namespace

PriorFile describePriorFile(const fs::path& file, const std::string& relativePath) {
  PriorFile out;
  const std::string ext = lowerCase(fs::path(relativePath).extension().string());
  out.kind = kindOf(ext);
  // Until the content says more: the extension, as for other files of the capture.
  std::string upper = ext.size() > 1 ? ext.substr(1) : "unknown";
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  out.format = upper;
  try {
    readContent(file, relativePath, out);
  } catch (const Error& e) {
    out.madeBy.clear();
    out.warning = relativePath + " is recorded as prior work, but it cannot be read as a ." + ext.substr(ext.empty() ? 0 : 1) +
                  " file (" + e.message() + "): nothing is recorded of what made it";
  }
  return out;
}

std::vector<std::string> plannedOutputs(const carrier::Carrier& plan) {
  std::vector<std::string> out = {kCarrierPath, kReportPath};
  for (const carrier::Step& step : plan.process) {
    const pipeline::StageInfo* info = pipeline::StageRegistry::instance().info(step.component);
    if (!info || !info->outputs) continue;
    try {
      for (const std::string& path : info->outputs(step)) out.push_back(path);
    } catch (const Error&) {
      // A parameter that cannot be read: the runner refuses the step, naming it, before it
      // writes anything.
    }
  }
  return out;
}

bool isPlannedOutput(const std::string& path, const std::vector<std::string>& planned) {
  for (const std::string& p : planned) {
    const auto star = p.find('*');
    if (star == std::string::npos) {
      if (p == path) return true;
      continue;
    }
    const std::string head = p.substr(0, star), tail = p.substr(star + 1);
    if (path.size() >= head.size() + tail.size() && path.compare(0, head.size(), head) == 0 &&
        path.compare(path.size() - tail.size(), tail.size(), tail) == 0)
      return true;
  }
  return false;
}

bool isPriorWork(const std::string& path, const carrier::Carrier* previous,
                 const std::vector<std::string>& planned) {
  if (!previous) return true;
  if (const carrier::FileRecord* f = previous->findFileByPath(path)) return f->role == "prior";
  return !isPlannedOutput(path, planned);
}

void refuseOutputsOverPriorWork(const std::vector<std::string>& outputFolderFiles,
                                const carrier::Carrier* previous,
                                const std::vector<std::string>& planned) {
  for (const std::string& path : outputFolderFiles) {
    if (!isPriorWork(path, previous, planned) || !isPlannedOutput(path, planned)) continue;
    const bool recorded = previous && previous->findFileByPath(path);
    throw Error(ErrorKind::Usage, path, "plan",
                "was not written by Surrogate (prior work, e.g. RTIBuilder's), and this run would write its "
                "own result under the same name; Surrogate never writes over prior work. Move the file (with "
                "any file that names it) into a folder of its own, e.g. " +
                    fs::path(path).parent_path().generic_string() + "/prior/, then run again: it is recorded "
                    "there as prior work" +
                    (recorded ? std::string(" (it is recorded here already: accept its move with "
                                            "--accept-changed " + path + " --reason \"...\")")
                              : std::string()));
  }
}

}  // namespace surrogate::stages
