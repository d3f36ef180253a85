// The verdict in parts (audit.h, "The verdict in parts"): lights, model, tone, integrity.
#include <algorithm>
#include <cmath>

#include "audit/audit.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

using State = VerdictPart::State;

constexpr std::size_t kNamesListed = 4;

std::string deg(double d) { return fixedDecimals(d, 1) + " degrees"; }
std::string db(double d) { return fixedDecimals(d, 2) + " dB"; }

const LightComparison* lightsOf(const AuditReport& report, const Verdict& v) {
  if (v.lightFile.empty()) return nullptr;
  for (const LightComparison& l : report.lights)
    if (l.file == v.lightFile) return &l;
  return nullptr;
}

const ModelCheck* modelOf(const AuditReport& report, const Verdict& v) {
  if (v.model.empty()) return nullptr;
  for (const ModelCheck& m : report.models)
    if (m.file == v.model) return &m;
  return nullptr;
}

std::string missingText(const LightComparison& l) {
  std::string out;
  if (!l.onlyInSurrogate.empty())
    out += "; " + std::to_string(l.onlyInSurrogate.size()) + " photograph(s) have no prior light";
  if (!l.onlyInPrior.empty())
    out += "; the file names " + std::to_string(l.onlyInPrior.size()) + " image(s) that are not among the photographs";
  return out;
}

VerdictPart lightsPart(const LightComparison* l, const Verdict& v) {
  VerdictPart p{"lights", State::CannotTell, "", ""};
  if (!l) {
    p.figure = v.lightFile.empty() ? "no prior light file to compare"
                                   : "the lights of " + v.lightFile.generic_string() +
                                         " were not compared: Surrogate's lights come from the capture's own .lp";
    return p;
  }
  if (l->angles.empty()) {
    p.figure = "the light file names none of the photographs" + missingText(*l);
    return p;
  }
  const std::string n = std::to_string(l->angles.size());
  if (l->aboveThreshold.empty()) {
    // The largest distance, judged in words: a light beyond the threshold is seen to be within
    // its uncertainty.
    p.state = State::Reproduced;
    p.figure = "all " + n + " lights agree with Surrogate's within their combined uncertainty or the threshold " +
               deg(l->thresholdDegrees) + " (median " + fixedDecimals(l->medianDegrees, 1) + " degrees; largest " +
               lightJudgement(*l->largest(), l->thresholdDegrees) + ")" + missingText(*l);
    return p;
  }
  p.state = State::Differs;
  std::vector<ImageAngle> worst = l->aboveThreshold;
  std::stable_sort(worst.begin(), worst.end(), [](const ImageAngle& a, const ImageAngle& b) { return a.degrees > b.degrees; });
  std::vector<std::string> worstNames;
  for (const ImageAngle& a : worst) worstNames.push_back(lightJudgement(a, l->thresholdDegrees));
  std::string named;
  for (std::size_t i = 0; i < worstNames.size() && i < kNamesListed; ++i) named += (i ? "; " : "") + worstNames[i];
  if (worstNames.size() > kNamesListed) named += "; and " + std::to_string(worstNames.size() - kNamesListed) + " more";
  p.figure = std::to_string(l->aboveThreshold.size()) + " of " + n +
             " images differ by more than both their combined uncertainty and the threshold " +
             deg(l->thresholdDegrees) + ": " + named + " (median of all " + n + ": " +
             fixedDecimals(l->medianDegrees, 1) + " degrees)" + missingText(*l);
  p.cause = 2 * l->aboveThreshold.size() > l->angles.size()
                ? "most lights differ: another axis convention, another sphere, or a sphere found at another place or size"
                : "these images' highlights were taken elsewhere (a reflection, a mis-click) or their lines were swapped";
  return p;
}

bool hasFinding(const Verdict& v, Finding::Cause cause) {
  return std::any_of(v.findings.begin(), v.findings.end(), [&](const Finding& f) { return f.cause == cause; });
}

VerdictPart modelPart(const ModelCheck* m, const Verdict& v, double margin) {
  VerdictPart p{"model", State::CannotTell, "", ""};
  if (!m) {
    p.figure = "no prior model (.ptm, .rti) to compare";
    return p;
  }
  if (!m->prior.computed) {
    p.figure = "not compared: " + m->prior.note;
    return p;
  }
  p.figure = "the prior " + db(m->prior.psnr) + " against the photographs";
  if (m->refitPriorLights.computed) p.figure += "; Surrogate's refit " + db(m->refitPriorLights.psnr) + " at the prior's lights";
  if (m->refitSurrogateLights.computed)
    p.figure += (m->refitPriorLights.computed ? ", " : "; Surrogate's refit ") + db(m->refitSurrogateLights.psnr) +
                " at Surrogate's lights";
  if (!m->refitPriorLights.computed) return p;
  if (v.dbBelowRefit <= margin) {
    p.state = State::Reproduced;
    p.figure += " (within " + db(margin) + ")";
    return p;
  }
  p.state = State::Differs;
  p.figure += " (" + db(v.dbBelowRefit) + " below the refit)";
  if (hasFinding(v, Finding::Cause::BrokenBias)) p.cause = "clipped coefficients in the file (see integrity)";
  else if (hasFinding(v, Finding::Cause::ColourHandling)) p.cause = "the prior was fitted from differently processed photographs (see tone)";
  else if (hasFinding(v, Finding::Cause::DifferentSize)) p.cause = "the model is of another crop or size (see integrity)";
  else p.cause = "another fitting method, or other photographs, than the ones audited";
  return p;
}

VerdictPart tonePart(const ModelCheck* m) {
  VerdictPart p{"tone", State::CannotTell, "", ""};
  if (!m || !m->colour.measured) {
    p.figure = m ? "not measured (too few mid-tone pixels, or the model was not compared)" : "no prior model to compare";
    return p;
  }
  const std::string curve = "one tone curve: gain " + fixedDecimals(m->colour.gain, 3) + ", gamma " +
                            fixedDecimals(m->colour.gamma, 3) + ", mid-tone RMSE " +
                            fixedDecimals(m->colour.rmseBefore, 2) + " -> " + fixedDecimals(m->colour.rmseAfter, 2) +
                            " levels once corrected";
  if (m->colour.differs && !m->quantisation.clamped) {
    p.state = State::Differs;
    p.figure = curve;
    p.cause = "the prior's photographs were processed otherwise (white balance, gamma curve or exposure)";
  } else {
    p.state = State::Reproduced;
    p.figure = m->colour.differs ? curve + " (the clipped coefficients bend it: see integrity)"
                                 : "the same tone as the photographs (" + curve + ")";
  }
  return p;
}

VerdictPart integrityPart(const ModelCheck* m) {
  VerdictPart p{"integrity", State::CannotTell, "", ""};
  if (!m) {
    p.figure = "no prior model to check";
    return p;
  }
  std::vector<std::string> clipped;
  for (const PlaneCheck& plane : m->quantisation.planes)
    if (plane.clamped)
      clipped.push_back(plane.plane + " " + fixedDecimals(100 * (plane.atZero + plane.atFull), 1) + "% at 0 or 255");
  if (m->size.kind == SizeRelation::Kind::Different) {
    p.state = State::Differs;
    p.figure = m->size.describe();
    p.cause = "the model was made from another crop of the photographs, or from other photographs";
    return p;
  }
  if (!clipped.empty()) {
    p.state = State::Differs;
    p.figure = std::to_string(clipped.size()) + " plane(s) clipped by the file's scale and bias: " +
               listedWithMore(clipped, kNamesListed);
    p.cause = "the writer chose a scale or bias that cannot hold the fitted coefficients (a writer's fault, not the photographs')";
    return p;
  }
  p.state = State::Reproduced;
  p.figure = (m->size.kind == SizeRelation::Kind::Same ? "the photographs' size" : m->size.describe()) +
             std::string("; no coefficient plane clipped");
  return p;
}

std::string subjectOf(const Verdict& v) {
  if (v.model.empty()) return v.lightFile.generic_string();
  if (v.lightFile.empty()) return v.model.generic_string();
  return v.model.generic_string() + " with the lights of " + v.lightFile.generic_string();
}

}  // namespace

const char* stateName(State state) {
  switch (state) {
    case State::Reproduced: return "reproduced";
    case State::Differs: return "differs";
    case State::CannotTell: return "cannot tell";
  }
  return "unknown";
}

std::vector<VerdictSummary> summarise(const AuditReport& report) {
  std::vector<VerdictSummary> out;
  for (const Verdict& v : report.verdicts) {
    const LightComparison* l = lightsOf(report, v);
    const ModelCheck* m = modelOf(report, v);
    out.push_back({subjectOf(v), v.reproduced, report.thresholdDegrees,
                   {lightsPart(l, v), modelPart(m, v, report.reproducedDb), tonePart(m), integrityPart(m)}});
  }
  return out;
}

bool auditReproduced(const AuditReport& report) {
  if (report.verdicts.empty() || !report.notAudited.empty()) return false;
  return std::all_of(report.verdicts.begin(), report.verdicts.end(), [](const Verdict& v) { return v.reproduced; });
}

int auditExitCode(const AuditReport& report) {
  if (!report.notAudited.empty() || report.verdicts.empty()) return static_cast<int>(ErrorKind::Input);
  for (const Verdict& v : report.verdicts)
    if (!v.reproduced) return static_cast<int>(ErrorKind::NotReproduced);
  return 0;
}

std::vector<std::string> summaryLines(const std::vector<VerdictSummary>& summaries) {
  std::vector<std::string> out;
  for (const VerdictSummary& s : summaries) {
    // Neither the lights nor the model could be compared (a model whose light file cannot be
    // read): nothing was found to differ, so the line does not say "not reproduced".
    const bool nothingCompared = s.parts.size() >= 2 && s.parts[0].state == State::CannotTell &&
                                 s.parts[1].state == State::CannotTell;
    // The threshold on the verdict's own line: it is this audit's, given or the default.
    out.push_back((s.reproduced ? "REPRODUCED      " : nothingCompared ? "CANNOT TELL     " : "NOT REPRODUCED  ") +
                  s.subject + " (threshold " + fixedDecimals(s.thresholdDegrees, 1) + " deg)");
    for (const VerdictPart& p : s.parts) {
      std::string head = "  " + p.name;
      head.resize(13, ' ');
      std::string state = stateName(p.state);
      state.resize(12, ' ');
      out.push_back(head + state + p.figure);
      if (!p.cause.empty()) out.push_back(std::string(25, ' ') + "likely: " + p.cause);
    }
  }
  return out;
}

std::vector<std::string> logSummaryLines(const AuditReport& report) {
  std::vector<std::string> out;
  for (const AuditReport::PriorLog& l : report.logs) {
    const std::string head = "  log        " + l.file.generic_string() + " (" +
                             (l.records.empty() ? std::string("a processing log") : l.records.front()) + "): ";
    if (l.discrepancies.empty()) out.push_back(head + "agrees with the photographs audited");
    else out.push_back(head + std::to_string(l.discrepancies.size()) + " difference(s), first: " + l.discrepancies.front());
  }
  return out;
}

void writeSummaryJson(JsonWriter& j, const std::vector<VerdictSummary>& summaries) {
  j.beginArray();
  for (const VerdictSummary& s : summaries) {
    j.beginObject().key("subject").value(s.subject).key("reproduced").value(s.reproduced);
    j.key("thresholdDegrees").value(s.thresholdDegrees).key("parts").beginArray();
    for (const VerdictPart& p : s.parts) {
      j.beginObject().key("part").value(p.name).key("state").value(stateName(p.state)).key("figure").value(p.figure);
      if (!p.cause.empty()) j.key("likelyCause").value(p.cause);
      j.endObject();
    }
    j.endArray().endObject();
  }
  j.endArray();
}

}  // namespace surrogate::audit
