// The whole audit: every prior light file against Surrogate's lights, every prior model
// against the photographs, one verdict each.
#include <algorithm>

#include "audit/audit.h"
#include "core/error.h"

namespace surrogate::audit {
namespace {

std::size_t matchedImages(const PriorLights& p) {
  return static_cast<std::size_t>(std::count_if(p.lineOfImage.begin(), p.lineOfImage.end(),
                                                [](const auto& line) { return line.has_value(); }));
}

// The light file a model was fitted with: the one with the model's stem (RTIBuilder names
// both after the project), else the one naming most photographs; -1 when there is none.
int lightFileOf(const std::filesystem::path& model, const std::vector<PriorLights>& files) {
  for (std::size_t i = 0; i < files.size(); ++i)
    if (files[i].file.stem() == model.stem()) return static_cast<int>(i);
  int best = -1;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (best < 0 || matchedImages(files[i]) > matchedImages(files[best])) best = static_cast<int>(i);
  return best;
}

}  // namespace

AuditReport runAudit(const AuditInputs& inputs, const AuditOptions& options) {
  AuditReport report;
  report.thresholdDegrees = options.angleThresholdDegrees;
  report.reproducedDb = options.reproducedDb;
  const Photographs& photos = inputs.photographs;
  if (!photos.stack || photos.stack->size() != static_cast<int>(photos.files.size()) ||
      (!inputs.surrogateLights.empty() && inputs.surrogateLights.size() != photos.files.size()))
    throw Error(ErrorKind::Internal, "", "audit",
                "the photographs, their files and Surrogate's lights differ in number");
  std::vector<std::string> names;
  for (const auto& f : photos.files) names.push_back(f.filename().string());

  std::vector<PriorLights> priors;
  std::vector<int> comparisonOf;  // per light file: its index in report.lights, or -1
  for (const auto& lp : inputs.priorLightFiles) {
    priors.push_back(readPriorLights(lp, photos.files));
    comparisonOf.push_back(-1);
    if (inputs.surrogateLights.empty()) continue;  // a dome capture without spheres: fit only
    comparisonOf.back() = static_cast<int>(report.lights.size());
    report.lights.push_back(compareLights(priors.back(), names, inputs.surrogateLights,
                                          options.angleThresholdDegrees, inputs.surrogateUncertainty));
  }

  std::vector<bool> used(priors.size(), false);
  for (const auto& model : inputs.priorModels) {
    const int lp = lightFileOf(model, priors);
    PriorLights none;
    none.lineOfImage.assign(photos.files.size(), std::nullopt);
    report.models.push_back(checkModel(model, photos, lp >= 0 ? priors[lp] : none, inputs.surrogateLights, options));
    const LightComparison* lights = nullptr;
    if (lp >= 0) {
      used[lp] = true;
      if (comparisonOf[lp] >= 0) lights = &report.lights[comparisonOf[lp]];
    }
    report.verdicts.push_back(diagnose(lights, &report.models.back(), options));
  }
  for (std::size_t i = 0; i < priors.size(); ++i)
    if (!used[i] && comparisonOf[i] >= 0)
      report.verdicts.push_back(diagnose(&report.lights[comparisonOf[i]], nullptr, options));
  return report;
}

}  // namespace surrogate::audit
