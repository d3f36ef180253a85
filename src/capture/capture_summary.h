// CaptureSummary: what a capture folder holds, as plain data for `surrogate info` and any page
// that shows a capture before or after it is processed.
//
//   const capture::CaptureSummary s = capture::describeCapture("/data/stela12");
//   std::cout << s.shots << " shots of " << s.width << "x" << s.height << "\n";
//
// The folder is scanned and checked as `run` scans it (scanCapture), with the dome capture's
// .lp that its carrier records, if it has one.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::capture {

struct CaptureSummary {
  std::size_t shots = 0;
  int originals = 0, exports = 0;  // shots with an original, with an export
  std::string originalsDir;        // "original-captures", "raw-images", "" for exports alone
  // What the carrier records as the originals, with a '/': the exports in a capture of
  // exports alone ("jpeg-exports/").
  std::string originalsFolder;
  int width = 0, height = 0;       // of the first shot's original, else its export
  std::string format;              // "camera raw", "DNG", "JPEG", "TIFF", "PNG"
  std::optional<std::string> lp;   // the dome capture's .lp its carrier records
  std::vector<std::string> unusedLp;  // .lp files at the top of the capture, not used
  bool processed = false;          // holds a carrier (kCarrierPath)

  bool hasOriginals() const { return !originalsDir.empty(); }
};

// Throws Error(Input) as scanCapture does for a folder that is not a sound capture, and as
// loadCarrier does for a carrier it cannot read.
CaptureSummary describeCapture(const std::filesystem::path& root);

}  // namespace surrogate::capture
