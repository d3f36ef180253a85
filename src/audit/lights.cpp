// Matching a prior light file to the photographs, and the angles between its lights and
// Surrogate's.
#include <algorithm>
#include <cmath>
#include <system_error>

#include "audit/audit.h"
#include "audit/statistics.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

std::filesystem::path sameFileKey(const std::filesystem::path& p) {
  std::error_code ec;
  std::filesystem::path c = std::filesystem::weakly_canonical(std::filesystem::absolute(p), ec);
  return ec ? p : c;
}

// Lines matchLpLines left alone that resolveLpImage finds at one of the photographs' paths
// (a name such as "..\\jpeg-exports\\000.jpg" whose base name differs from the file's).
void matchByResolvedPath(PriorLights& prior, const std::vector<std::filesystem::path>& images,
                         const std::vector<std::optional<std::size_t>>& imageOfLine) {
  std::vector<std::filesystem::path> canonicalImages;
  for (const auto& image : images) canonicalImages.push_back(sameFileKey(image));
  for (std::size_t line = 0; line < prior.lines.size(); ++line) {
    if (imageOfLine[line]) continue;
    const auto found = formats::resolveLpImage(prior.file, prior.lines[line].filename);
    if (!found) continue;
    const auto at = std::find(canonicalImages.begin(), canonicalImages.end(), sameFileKey(*found));
    if (at == canonicalImages.end()) continue;
    const auto image = static_cast<std::size_t>(at - canonicalImages.begin());
    if (!prior.lineOfImage[image]) prior.lineOfImage[image] = line;
  }
}

double angleDegrees(const Light& a, const Light& b) {
  // atan2 of |a x b| and a . b keeps small angles exact (acos loses them near 1).
  const double cx = a[1] * b[2] - a[2] * b[1];
  const double cy = a[2] * b[0] - a[0] * b[2];
  const double cz = a[0] * b[1] - a[1] * b[0];
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * 180.0 / M_PI;
}

Light unit(const Light& l) {
  const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  return {l[0] / n, l[1] / n, l[2] / n};
}

std::string deg(double d) { return fixedDecimals(d, 1) + " deg"; }

}  // namespace

double ImageAngle::combinedDegrees() const {
  const double a = ours.value_or(0), b = priors.value_or(0);
  return std::sqrt(a * a + b * b);
}

bool ImageAngle::differs(double thresholdDegrees) const {
  return degrees > thresholdDegrees && degrees > combinedDegrees();
}

std::string lightJudgement(const ImageAngle& a, double thresholdDegrees) {
  const std::string uncertainty =
      "the combined uncertainty " + deg(a.combinedDegrees()) + " (ours " +
      (a.ours ? fixedDecimals(*a.ours, 1) : std::string("not recorded")) + ", " +
      (a.priors ? "the prior's " + fixedDecimals(*a.priors, 1) : std::string("the prior states none")) + ")";
  const std::string head = a.image + ": " + deg(a.degrees) + " apart; ";
  if (a.differs(thresholdDegrees)) return head + "beyond " + uncertainty + " and the threshold " + deg(thresholdDegrees);
  if (a.degrees <= a.combinedDegrees()) return head + "within " + uncertainty + "; threshold " + deg(thresholdDegrees);
  return head + "within the threshold " + deg(thresholdDegrees) + ", beyond " + uncertainty;
}

const ImageAngle* LightComparison::largest() const {
  const ImageAngle* out = nullptr;
  for (const ImageAngle& a : angles)
    if (!out || a.degrees > out->degrees) out = &a;
  return out;
}

std::optional<double> PriorLights::uncertaintyOfImage(std::size_t image) const {
  if (image >= lineOfImage.size() || !lineOfImage[image] || *lineOfImage[image] >= uncertaintyOfLine.size())
    return std::nullopt;
  return uncertaintyOfLine[*lineOfImage[image]];
}

std::vector<std::optional<Light>> PriorLights::lightOfImage() const {
  std::vector<std::optional<Light>> out;
  for (const auto& line : lineOfImage) {
    if (!line) {
      out.emplace_back();
      continue;
    }
    const formats::LightEntry& e = lines[*line];
    out.push_back(unit({e.x, e.y, e.z}));
  }
  return out;
}

PriorLights matchPriorLights(const std::filesystem::path& lpFile,
                             std::vector<formats::LightEntry> lines,
                             const std::vector<std::filesystem::path>& images) {
  PriorLights prior;
  prior.file = lpFile;
  prior.lines = std::move(lines);
  std::vector<std::string> names;
  for (const auto& image : images) names.push_back(image.filename().string());
  const formats::LpMatch match = formats::matchLpLines(lpFile.string(), prior.lines, names);
  prior.lineOfImage = match.lineOfImage;
  matchByResolvedPath(prior, images, match.imageOfLine);
  return prior;
}

PriorLights readPriorLights(const std::filesystem::path& lpFile,
                            const std::vector<std::filesystem::path>& images) {
  return matchPriorLights(lpFile, formats::readLp(lpFile), images);
}

LightComparison compareLights(const PriorLights& prior, const std::vector<std::string>& imageNames,
                              const std::vector<Light>& surrogateLights, double thresholdDegrees,
                              const std::vector<std::optional<double>>& surrogateUncertainty) {
  LightComparison out;
  out.file = prior.file;
  out.thresholdDegrees = thresholdDegrees;
  std::vector<bool> lineUsed(prior.lines.size(), false);
  const auto priorOfImage = prior.lightOfImage();
  for (std::size_t i = 0; i < imageNames.size(); ++i) {
    const bool hasPrior = i < priorOfImage.size() && priorOfImage[i];
    if (hasPrior) lineUsed[*prior.lineOfImage[i]] = true;
    if (!hasPrior || i >= surrogateLights.size()) {
      out.onlyInSurrogate.push_back(imageNames[i]);
      continue;
    }
    ImageAngle a{imageNames[i], angleDegrees(*priorOfImage[i], unit(surrogateLights[i])), *priorOfImage[i],
                 std::nullopt, prior.uncertaintyOfImage(i)};
    if (i < surrogateUncertainty.size()) a.ours = surrogateUncertainty[i];
    out.angles.push_back(a);
    if (a.differs(thresholdDegrees)) out.aboveThreshold.push_back(a);
  }
  for (std::size_t line = 0; line < prior.lines.size(); ++line)
    if (!lineUsed[line]) out.onlyInPrior.push_back(prior.lines[line].filename);
  std::vector<double> degrees;
  for (const ImageAngle& a : out.angles) degrees.push_back(a.degrees);
  out.medianDegrees = median(degrees);
  out.p95Degrees = percentile(degrees, 0.95);
  out.maxDegrees = degrees.empty() ? 0 : *std::max_element(degrees.begin(), degrees.end());
  return out;
}

}  // namespace surrogate::audit
