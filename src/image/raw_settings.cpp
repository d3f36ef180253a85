#include "image/raw_settings.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::image {

namespace {

using Parameters = std::vector<std::pair<std::string, std::string>>;

// LibRaw settings Surrogate never varies, recorded so the carrier names every setting that
// shapes the pixels.
const Parameters& fixedParameters() {
  static const Parameters fixed = {
      {"gamma", "linear"},                 // gamm = (1, 1): values proportional to light
      {"brightness", "1"},                 // bright = 1
      {"chromaticAberration", "none"},     // aber = (1, 1)
      {"exposureCorrection", "none"},      // exp_correc = 0
      {"fbddNoiseReduction", "none"},      // fbdd_noiserd = 0
      {"fujiRotate", "true"},              // use_fuji_rotate = 1 (SuperCCD sensors only)
      {"shotSelect", "0"},                 // shot_select = 0: the file's first image
      {"autoBrightThreshold", "0.01"},     // auto_bright_thr (only used with noAutoBright=false)
      {"cropBeforeProcessing", "none"},    // cropbox left at LibRaw's default: the whole image
      {"channelBlackOverride", "none"},    // user_cblack unset: the file's per-channel blacks
      {"darkFrame", "none"},               // dark_frame = NULL: no dark-frame subtraction
      {"badPixels", "none"},               // bad_pixels = NULL: no bad-pixel map
  };
  return fixed;
}

[[noreturn]] void refuse(const std::string& name, const std::string& value, const std::string& why) {
  throw Error(ErrorKind::Usage, name + "=" + value, "raw decode settings", why);
}

void requireOneOf(const std::string& name, const std::string& value,
                  std::initializer_list<const char*> allowed) {
  for (const char* a : allowed)
    if (value == a) return;
  std::string list;
  for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  refuse(name, value, "unknown value; use one of: " + list);
}

bool parseBool(const std::string& name, const std::string& value) {
  if (value == "true") return true;
  if (value == "false") return false;
  refuse(name, value, "needs true or false");
}

int parseInt(const std::string& name, const std::string& value, int lo, int hi) {
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < lo || v > hi)
    refuse(name, value, "needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
  return static_cast<int>(v);
}

double parseDouble(const std::string& name, const std::string& value, double lo, double hi) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !(v >= lo && v <= hi))
    refuse(name, value, "needs a number from " + formatNumber(lo) + " to " + formatNumber(hi));
  return v;
}

}  // namespace

Parameters RawDecodeSettings::toParameters() const {
  Parameters p = {
      {"demosaic", demosaic},
      {"dcbIterations", std::to_string(dcbIterations)},
      {"dcbEnhance", dcbEnhance ? "true" : "false"},
      {"medianPasses", std::to_string(medianPasses)},
      {"fourColorRgb", fourColorRgb ? "true" : "false"},
      {"greenMatching", greenMatching ? "true" : "false"},
      {"noiseThreshold", formatNumber(noiseThreshold)},
      {"whiteBalance", whiteBalance},
      {"outputColorSpace", outputColorSpace},
      {"colorMatrix", colorMatrix},
      {"highlightMode", std::to_string(highlightMode)},
      {"blackLevel", std::to_string(blackLevel)},
      {"whiteLevel", std::to_string(whiteLevel)},
      {"adjustMaximumThreshold", formatNumber(adjustMaximumThreshold)},
      {"noAutoBright", noAutoBright ? "true" : "false"},
      {"orientation", orientation},
      {"halfSize", halfSize ? "true" : "false"},
      {"outputBits", std::to_string(outputBits)},
  };
  p.insert(p.end(), fixedParameters().begin(), fixedParameters().end());
  return p;
}

RawDecodeSettings RawDecodeSettings::fromParameters(const Parameters& params) {
  RawDecodeSettings s;
  for (const auto& [name, value] : params) {
    if (name == "demosaic") {
      requireOneOf(name, value, {"linear", "VNG", "PPG", "AHD", "DCB"});
      s.demosaic = value;
    } else if (name == "dcbIterations") {
      s.dcbIterations = parseInt(name, value, 0, 10);
    } else if (name == "dcbEnhance") {
      s.dcbEnhance = parseBool(name, value);
    } else if (name == "medianPasses") {
      s.medianPasses = parseInt(name, value, 0, 10);
    } else if (name == "fourColorRgb") {
      s.fourColorRgb = parseBool(name, value);
    } else if (name == "greenMatching") {
      s.greenMatching = parseBool(name, value);
    } else if (name == "noiseThreshold") {
      s.noiseThreshold = parseDouble(name, value, 0, 10000);
    } else if (name == "whiteBalance") {
      requireOneOf(name, value, {"camera", "daylight", "none"});
      s.whiteBalance = value;
    } else if (name == "outputColorSpace") {
      requireOneOf(name, value, {"srgb", "raw"});
      s.outputColorSpace = value;
    } else if (name == "colorMatrix") {
      requireOneOf(name, value, {"auto", "embedded", "builtin"});
      s.colorMatrix = value;
    } else if (name == "highlightMode") {
      s.highlightMode = parseInt(name, value, 0, 9);
    } else if (name == "blackLevel") {
      s.blackLevel = parseInt(name, value, -1, 65535);
    } else if (name == "whiteLevel") {
      s.whiteLevel = parseInt(name, value, -1, 65535);
    } else if (name == "adjustMaximumThreshold") {
      s.adjustMaximumThreshold = parseDouble(name, value, 0, 1);
    } else if (name == "noAutoBright") {
      s.noAutoBright = parseBool(name, value);
    } else if (name == "orientation") {
      requireOneOf(name, value, {"as-stored", "camera"});
      s.orientation = value;
    } else if (name == "halfSize") {
      s.halfSize = parseBool(name, value);
    } else if (name == "outputBits") {
      requireOneOf(name, value, {"16"});
    } else {
      const auto& fixed = fixedParameters();
      const std::string& key = name;  // a structured binding cannot be captured in C++17 (clang)
      const auto it = std::find_if(fixed.begin(), fixed.end(), [&key](const auto& f) { return f.first == key; });
      if (it == fixed.end()) refuse(name, value, "is not a raw decoding setting");
      if (value != it->second) refuse(name, value, "Surrogate always decodes with " + name + "=" + it->second);
    }
  }
  return s;
}

}  // namespace surrogate::image
