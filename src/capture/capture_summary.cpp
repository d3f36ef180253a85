#include "capture/capture_summary.h"

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/text.h"

namespace surrogate::capture {

namespace fs = std::filesystem;

CaptureSummary describeCapture(const fs::path& root) {
  CaptureSummary s;
  // A dome capture's .lp is a decision the carrier records (`run --lp`).
  const fs::path carrierPath = root / kCarrierPath;
  std::string domeLp;
  s.processed = fs::exists(carrierPath);
  if (s.processed)
    for (const carrier::Step& step : carrier::loadCarrier(carrierPath).process)
      if (step.component == "CaptureIngest") domeLp = step.param("lp", "");
  const CaptureLayout layout = scanCapture(root, 0, domeLp);
  s.shots = layout.shots.size();
  for (const Shot& shot : layout.shots) {
    s.originals += shot.original.has_value();
    s.exports += shot.exported.has_value();
  }
  s.originalsDir = layout.originalsDir;
  s.originalsFolder = (layout.hasOriginals() ? layout.originalsDir : std::string(kExportsDir)) + "/";
  if (!layout.shots.empty()) {
    const Shot& first = layout.shots.front();
    const ImageFile& sample = first.original ? *first.original : *first.exported;
    s.width = sample.width;
    s.height = sample.height;
    s.format = sample.format;
  }
  s.lp = layout.lp;
  for (const std::string& other : layout.others)
    if (other.find('/') == std::string::npos && lowerCase(fs::path(other).extension().string()) == ".lp")
      s.unusedLp.push_back(other);
  return s;
}

}  // namespace surrogate::capture
