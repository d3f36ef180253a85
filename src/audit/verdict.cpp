// The verdict: what the figures say about the prior, in a sentence.
#include <algorithm>
#include <cmath>

#include "audit/audit.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

// Names listed in a sentence before "and N more".
constexpr std::size_t kNamesListed = 5;

std::string degreesText(double d) { return fixedDecimals(d, 1) + " degrees"; }
std::string dbText(double d) { return fixedDecimals(d, 2) + " dB"; }

std::string listNames(const std::vector<std::string>& names) { return listedWithMore(names, kNamesListed); }

void lightFindings(Verdict& v, const LightComparison& lights, const ModelCheck* model) {
  if (!lights.aboveThreshold.empty()) {
    std::vector<std::string> named;
    for (const ImageAngle& a : lights.aboveThreshold)
      named.push_back(a.image + " " + degreesText(a.degrees) + ", combined uncertainty " +
                      fixedDecimals(a.combinedDegrees(), 1));
    std::string text = std::to_string(lights.aboveThreshold.size()) + " of " +
                       std::to_string(lights.angles.size()) +
                       " prior lights differ from Surrogate's by more than both their combined uncertainty and the "
                       "threshold " + degreesText(lights.thresholdDegrees) + " (" + listNames(named) + ")";
    if (model && model->prior.computed && model->refitSurrogateLights.computed)
      text += "; with Surrogate's lights the same basis reaches " + dbText(model->refitSurrogateLights.psnr) +
              " against the prior's " + dbText(model->prior.psnr);
    v.findings.push_back({Finding::Cause::DifferentLights, text});
  }
  std::vector<std::string> parts;
  if (!lights.onlyInPrior.empty())
    parts.push_back("the light file names " + std::to_string(lights.onlyInPrior.size()) +
                    " images not among the photographs (" + listNames(lights.onlyInPrior) + ")");
  if (!lights.onlyInSurrogate.empty())
    parts.push_back(std::to_string(lights.onlyInSurrogate.size()) + " photographs have no prior light (" +
                    listNames(lights.onlyInSurrogate) + ")");
  if (!parts.empty())
    v.findings.push_back({Finding::Cause::MissingImages, parts.size() == 2 ? parts[0] + "; " + parts[1] : parts[0]});
}

// Findings said beside a reproduction without denying it: photographs missing from one side,
// a resized model (compared at its own size), and clipped coefficients that cost the prior
// less than AuditOptions::reproducedDb.
bool informative(const Finding& f, const Verdict& v, const ModelCheck* model, const AuditOptions& options) {
  switch (f.cause) {
    case Finding::Cause::MissingImages: return true;
    case Finding::Cause::DifferentSize: return model && model->size.kind == SizeRelation::Kind::UniformScale;
    case Finding::Cause::BrokenBias: return model && model->prior.computed && v.dbBelowRefit <= options.reproducedDb;
    default: return false;
  }
}

void modelFindings(Verdict& v, const ModelCheck& m, const AuditOptions& options) {
  if (m.size.kind != SizeRelation::Kind::Same)
    v.findings.push_back({Finding::Cause::DifferentSize, m.size.describe()});
  // Clipped coefficients bend the rendering's tone curve themselves: no evidence of another
  // processing of the photographs then.
  if (m.colour.differs && !m.quantisation.clamped)
    v.findings.push_back({Finding::Cause::ColourHandling,
                          "the prior's rendering and the photographs differ by one tone curve (gain " +
                              fixedDecimals(m.colour.gain, 3) + ", gamma " + fixedDecimals(m.colour.gamma, 3) +
                              "; correcting it lowers the mid-tone RMSE from " + fixedDecimals(m.colour.rmseBefore, 2) +
                              " to " + fixedDecimals(m.colour.rmseAfter, 2) +
                              "): the prior was fitted from differently processed images"});
  if (m.quantisation.clamped) {
    std::vector<std::string> planes;
    for (const PlaneCheck& p : m.quantisation.planes)
      if (p.clamped)
        planes.push_back(p.plane + " (" + fixedDecimals(100 * (p.atZero + p.atFull), 1) + "% at 0 or 255, " +
                         fixedDecimals(100 * p.outsideRange, 1) + "% outside its range)");
    v.findings.push_back({Finding::Cause::BrokenBias,
                          "the file's scale and bias clip coefficients: " + listNames(planes)});
  }
  const bool explained = std::any_of(v.findings.begin(), v.findings.end(),
                                     [&](const Finding& f) { return !informative(f, v, &m, options); });
  if (!explained && v.dbBelowRefit > options.reproducedDb)
    v.findings.push_back({Finding::Cause::FitShortfall,
                          "the prior is " + dbText(v.dbBelowRefit) +
                              " below Surrogate's fit with the same lights and nothing above explains it "
                              "(another fitting method, or other photographs)"});
}

// The lights' part names the largest distance with the uncertainty and the threshold it was
// judged against, so that a light farther than the threshold is seen to be within its
// uncertainty.
std::string reproducedSentence(const Verdict& v, const LightComparison* lights, bool hasModel) {
  std::string s = "reproduced within ";
  if (hasModel) s += dbText(std::max(0.0, v.dbBelowRefit));
  if (hasModel && lights) s += " / ";
  if (lights) s += degreesText(v.maxDegrees);
  if (const ImageAngle* largest = lights ? lights->largest() : nullptr)
    s += " (largest " + lightJudgement(*largest, lights->thresholdDegrees) + ")";
  return s;
}

}  // namespace

const char* causeName(Finding::Cause cause) {
  switch (cause) {
    case Finding::Cause::DifferentLights: return "different-lights";
    case Finding::Cause::MissingImages: return "missing-images";
    case Finding::Cause::DifferentSize: return "different-size";
    case Finding::Cause::ColourHandling: return "colour-handling";
    case Finding::Cause::BrokenBias: return "broken-bias";
    case Finding::Cause::FitShortfall: return "fit-shortfall";
  }
  return "unknown";
}

Verdict diagnose(const LightComparison* lights, const ModelCheck* model, const AuditOptions& options) {
  Verdict v;
  if (model) v.model = model->file, v.lightFile = model->lightFile;
  if (lights) v.lightFile = lights->file, v.maxDegrees = lights->maxDegrees;
  if (model && model->prior.computed && model->refitPriorLights.computed)
    v.dbBelowRefit = model->refitPriorLights.psnr - model->prior.psnr;
  if (lights) lightFindings(v, *lights, model);
  if (model) modelFindings(v, *model, options);
  const bool blocking = std::any_of(v.findings.begin(), v.findings.end(),
                                    [&](const Finding& f) { return !informative(f, v, model, options); });
  v.reproduced = !blocking && (!model || model->prior.computed);
  std::vector<std::string> texts;
  for (const Finding& f : v.findings) texts.push_back(f.text);
  if (v.reproduced) {
    v.sentence = reproducedSentence(v, lights, model != nullptr);
    for (const std::string& t : texts) v.sentence += "; " + t;
    return v;
  }
  v.sentence = "not reproduced: ";
  for (std::size_t i = 0; i < texts.size(); ++i) v.sentence += (i ? "; " : "") + texts[i];
  if (texts.empty()) v.sentence += model ? model->prior.note : "nothing to compare";
  return v;
}

}  // namespace surrogate::audit
