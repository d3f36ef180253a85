#include <cstdlib>

#include "core/error.h"
#include "core/text.h"
#include "fit/learned.h"

namespace surrogate::fit {

const char* learnedKindName(LearnedKind kind) { return kind == LearnedKind::Rbf ? "rbf" : "bln"; }

bool isLearnedBasisName(const std::string& name) { return name == "rbf" || name == "bln"; }

LearnedKind parseLearnedKind(const std::string& name) {
  if (name == "rbf") return LearnedKind::Rbf;
  if (name == "bln") return LearnedKind::Bilinear;
  throw Error(ErrorKind::Usage, "--basis " + name, "command line",
              "the learned bases are rbf (one node per photograph) and bln (a grid over the light directions)");
}

namespace {

[[noreturn]] void unknown(const std::string& what) {
  throw Error(ErrorKind::Input, "carrier", "fit", "the recorded learned-basis " + what + " is unknown to this version");
}

}  // namespace

std::vector<std::pair<std::string, std::string>> LearnedOptions::toParameters() const {
  std::vector<std::pair<std::string, std::string>> p = {{"basis", learnedKindName(kind)},
                                                        {"planes", std::to_string(planes)}};
  if (kind == LearnedKind::Bilinear) p.push_back({"resolution", std::to_string(resolution)});
  if (kernelWidth > 0) p.push_back({"kernelWidth", formatNumber(kernelWidth)});
  if (ridge > 0) p.push_back({"ridge", formatNumber(ridge)});
  return p;
}

LearnedOptions LearnedOptions::fromParameters(const std::vector<std::pair<std::string, std::string>>& parameters) {
  LearnedOptions o;
  for (const auto& [name, value] : parameters) {
    char* end = nullptr;
    if (name == "basis") {
      if (!isLearnedBasisName(value)) unknown("basis \"" + value + "\"");
      o.kind = parseLearnedKind(value);
    } else if (name == "planes" || name == "resolution") {
      const long v = std::strtol(value.c_str(), &end, 10);
      if (end == value.c_str() || *end) unknown(name + " \"" + value + "\"");
      (name == "planes" ? o.planes : o.resolution) = static_cast<int>(v);
    } else if (name == "kernelWidth" || name == "ridge") {
      const double v = std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end || !(v > 0)) unknown(name + " \"" + value + "\"");
      (name == "ridge" ? o.ridge : o.kernelWidth) = v;
    } else {
      unknown("parameter \"" + name + "\"");
    }
  }
  return o;
}

}  // namespace surrogate::fit
