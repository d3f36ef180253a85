#include "meta/camera_text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "core/text.h"

namespace surrogate::meta {

namespace {

// The f-numbers marked on lenses and shown by cameras for Av = k/3, k = 0..36 (f/1 to f/64):
// sqrt(2)^(k/3) rounded by photographic convention (5.657 is written 5.6, 7.127 is 7.1).
constexpr double kMarkedThirdStops[] = {1.0, 1.1, 1.2, 1.4, 1.6, 1.8, 2, 2.2, 2.5, 2.8, 3.2, 3.5, 4,
                                        4.5, 5, 5.6, 6.3, 7.1, 8, 9, 10, 11, 13, 14, 16, 18, 20, 22,
                                        25, 29, 32, 36, 40, 45, 51, 57, 64};
// An f-number within this many stops of a third stop is that stop: cameras store the exact
// power of two (2828427/500000 for f/5.6), a half stop (f/4.8, f/6.7) is 1/6 stop away.
constexpr double kThirdStopTolerance = 0.05;
// Lens names round focal lengths ("18-55mm" for 18.3-55.4 mm): a name agrees with the
// recorded range when each end is within this many millimetres or this fraction of it.
constexpr double kFocalToleranceMm = 1.0;
constexpr double kFocalToleranceFraction = 0.05;

// `v` with at most one decimal, the ".0" dropped: 31 -> "31", 4.24 -> "4.2".
std::string oneDecimal(double v) {
  std::string s = fixedDecimals(v, 1);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

bool startsWithWord(const std::string& text, const std::string& word) {
  if (word.empty() || text.size() < word.size()) return false;
  if (lowerCase(text.substr(0, word.size())) != lowerCase(word)) return false;
  return text.size() == word.size() || text[word.size()] == ' ' || text[word.size()] == '-';
}

bool closeFocal(double a, double b) {
  return std::abs(a - b) <= std::max(kFocalToleranceMm, kFocalToleranceFraction * std::max(a, b));
}

}  // namespace

std::string apertureText(double fNumber) {
  if (!(fNumber > 0)) return "";
  const double av = 2 * std::log2(fNumber);
  const double third = std::round(av * 3);
  const int k = static_cast<int>(third);
  const int marked = static_cast<int>(sizeof kMarkedThirdStops / sizeof kMarkedThirdStops[0]);
  if (k >= 0 && k < marked && std::abs(av - third / 3) <= kThirdStopTolerance)
    return "f/" + oneDecimal(kMarkedThirdStops[k]);
  return "f/" + (fNumber < 10 ? oneDecimal(fNumber) : fixedDecimals(fNumber, 0));
}

std::string exposureText(double seconds) {
  if (!(seconds > 0)) return "";
  if (seconds < 1) {
    const double n = std::round(1 / seconds);
    // 1/n as cameras store it; a time that is no such fraction (0.6 s) as a decimal.
    if (seconds < 0.1 || std::abs(n * seconds - 1) < 0.01) return "1/" + fixedDecimals(n, 0) + " s";
  }
  return oneDecimal(seconds) + " s";
}

std::string focalLengthText(double mm) { return oneDecimal(mm) + " mm"; }

std::string exposureSettingsText(const CameraMetadata& m) {
  std::string line;
  auto add = [&](const std::string& part) {
    if (!part.empty()) line += (line.empty() ? "" : ", ") + part;
  };
  if (m.focalLengthMm) add(focalLengthText(*m.focalLengthMm));
  if (m.fNumber) add(apertureText(*m.fNumber));
  if (m.exposureSeconds) add(exposureText(*m.exposureSeconds));
  else if (m.exposureTime) add(*m.exposureTime);
  if (m.iso) add("ISO " + std::to_string(*m.iso));
  return line;
}

std::string focalRangeText(double minMm, double maxMm) {
  return oneDecimal(minMm) == oneDecimal(maxMm) ? focalLengthText(minMm)
                                                 : oneDecimal(minMm) + "-" + oneDecimal(maxMm) + " mm";
}

std::string cameraText(const CameraMetadata& m) {
  const std::string make = m.make.value_or(""), model = m.model.value_or("");
  if (model.empty()) return make;
  if (make.empty()) return model;
  const std::string makeWord = make.substr(0, make.find(' '));  // "NIKON" of "NIKON CORPORATION"
  if (startsWithWord(model, make) || startsWithWord(model, makeWord)) return model;
  return make + " " + model;
}

std::string dateTimeText(const std::string& exif, const std::optional<std::string>& offset) {
  static const std::regex kExif(R"((\d{4}):(\d{2}):(\d{2}) (\d{2}:\d{2}:\d{2}))");
  static const std::regex kOffset(R"([+-]\d{2}:\d{2}|Z)");
  std::smatch m;
  if (!std::regex_match(exif, m, kExif)) return exif;
  std::string iso = m[1].str() + "-" + m[2].str() + "-" + m[3].str() + "T" + m[4].str();
  if (offset && std::regex_match(*offset, kOffset)) iso += *offset;
  return iso;
}

std::string orientationText(long orientation) {
  static const char* kText[] = {"as stored", "mirror left to right", "rotate 180°", "mirror top to bottom",
                                "mirror left to right, then rotate 90° counter-clockwise",
                                "rotate 90° clockwise", "mirror left to right, then rotate 90° clockwise",
                                "rotate 90° counter-clockwise"};
  return orientation >= 1 && orientation <= 8 ? kText[orientation - 1] : "unknown";
}

std::string resolutionUnitText(long unit) {
  return unit == 3 ? "pixels per cm" : unit == 4 ? "pixels per mm" : "pixels per inch";
}

bool lensAgreesWithRange(const CameraMetadata& m) {
  if (!m.lens || !m.lensFromMakerNote || !m.lensMinFocalMm || !m.lensMaxFocalMm) return true;
  static const std::regex kFocal(R"((\d+(?:\.\d+)?)(?:\s*-\s*(\d+(?:\.\d+)?))?\s*mm)", std::regex::icase);
  std::smatch f;
  if (!std::regex_search(*m.lens, f, kFocal)) return true;  // a name without focal lengths
  const double lo = std::strtod(f[1].str().c_str(), nullptr);
  const double hi = f[2].matched ? std::strtod(f[2].str().c_str(), nullptr) : lo;
  return closeFocal(lo, *m.lensMinFocalMm) && closeFocal(hi, *m.lensMaxFocalMm);
}

std::string lensText(const CameraMetadata& m) {
  const bool range = m.lensMinFocalMm && m.lensMaxFocalMm;
  const std::string recorded = range ? focalRangeText(*m.lensMinFocalMm, *m.lensMaxFocalMm) : "";
  if (!m.lens) return recorded;
  if (lensAgreesWithRange(m)) return *m.lens;
  return recorded + " (recorded focal range; the lens code reads as " + *m.lens +
         ", which does not match it)";
}

}  // namespace surrogate::meta
