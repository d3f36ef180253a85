// The audit as JSON (--json, the carrier's figures) and as lines for the terminal. Numbers are
// rounded for display: angles to 0.1 degree, dB and RMSE to 0.01, shares to 0.0001.
#include <cmath>

#include "audit/audit.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

double degrees(double v) { return std::round(v * 10) / 10; }
double db(double v) { return std::round(v * 100) / 100; }
double share(double v) { return std::round(v * 10000) / 10000; }

const char* relationName(SizeRelation::Kind kind) {
  switch (kind) {
    case SizeRelation::Kind::Same: return "same";
    case SizeRelation::Kind::UniformScale: return "uniform-scale";
    case SizeRelation::Kind::Different: return "different";
  }
  return "unknown";
}

void optionalDegrees(JsonWriter& j, const char* key, const std::optional<double>& v) {
  j.key(key);
  if (v) j.value(degrees(*v));
  else j.null();
}

// Each light with the uncertainties it was judged with (null: none stated) and the judgement.
void angleList(JsonWriter& j, const std::vector<ImageAngle>& angles, double threshold) {
  j.beginArray();
  for (const ImageAngle& a : angles) {
    j.beginObject().key("image").value(a.image).key("degrees").value(degrees(a.degrees));
    j.key("uncertaintyDegrees").value(degrees(a.combinedDegrees()));
    optionalDegrees(j, "ourUncertaintyDegrees", a.ours);
    optionalDegrees(j, "priorUncertaintyDegrees", a.priors);
    j.key("differs").value(a.differs(threshold)).key("judgement").value(lightJudgement(a, threshold)).endObject();
  }
  j.endArray();
}

void nameList(JsonWriter& j, const std::vector<std::string>& names) {
  j.beginArray();
  for (const auto& n : names) j.value(n);
  j.endArray();
}

void lightsJson(JsonWriter& j, const LightComparison& l) {
  j.beginObject().key("file").value(l.file.string()).key("compared").value(static_cast<int>(l.angles.size()));
  j.key("medianDegrees").value(degrees(l.medianDegrees)).key("p95Degrees").value(degrees(l.p95Degrees));
  j.key("maxDegrees").value(degrees(l.maxDegrees)).key("thresholdDegrees").value(l.thresholdDegrees);
  j.key("aboveThreshold");
  angleList(j, l.aboveThreshold, l.thresholdDegrees);
  j.key("onlyInPrior");
  nameList(j, l.onlyInPrior);
  j.key("onlyInSurrogate");
  nameList(j, l.onlyInSurrogate);
  j.key("angles");
  angleList(j, l.angles, l.thresholdDegrees);
  j.endObject();
}

void errorsJson(JsonWriter& j, const ModelErrors& e) {
  j.beginObject().key("computed").value(e.computed);
  if (!e.computed) {
    j.key("note").value(e.note).endObject();
    return;
  }
  j.key("psnr").value(db(e.psnr)).key("rmse").value(db(e.rmse)).key("medianPsnr").value(db(e.medianPsnr));
  j.key("worstPsnr").value(db(e.worstPsnr)).key("worstImage").value(e.worstImage).key("images").beginArray();
  for (const ImageError& i : e.images)
    j.beginObject().key("image").value(i.image).key("rmse").value(db(i.rmse)).key("psnr").value(db(i.psnr)).endObject();
  j.endArray().endObject();
}

void modelJson(JsonWriter& j, const ModelCheck& m) {
  j.beginObject().key("file").value(m.file.string()).key("lightFile").value(m.lightFile.string());
  j.key("basis").value(m.basis).key("measure").value("Rec. 709 luminance of the " + m.values + " values, 0..255");
  j.key("size").beginObject().key("relation").value(relationName(m.size.kind));
  j.key("model").beginArray().value(m.size.modelWidth).value(m.size.modelHeight).endArray();
  j.key("photographs").beginArray().value(m.size.photoWidth).value(m.size.photoHeight).endArray();
  j.key("scale").value(std::round(m.size.scale * 1000) / 1000).endObject();
  j.key("prior");
  errorsJson(j, m.prior);
  j.key("refitPriorLights");
  errorsJson(j, m.refitPriorLights);
  j.key("refitSurrogateLights");
  errorsJson(j, m.refitSurrogateLights);
  j.key("tone").beginObject().key("measured").value(m.colour.measured).key("gain").value(db(m.colour.gain));
  j.key("gamma").value(db(m.colour.gamma)).key("differs").value(m.colour.differs).endObject();
  j.key("quantisation").beginObject().key("clamped").value(m.quantisation.clamped).key("planes").beginArray();
  for (const PlaneCheck& p : m.quantisation.planes)
    j.beginObject().key("plane").value(p.plane).key("atZero").value(share(p.atZero)).key("atFull").value(share(p.atFull))
        .key("outsideRange").value(share(p.outsideRange)).key("clamped").value(p.clamped).endObject();
  j.endArray().endObject();
  if (!m.differences.empty()) {
    // The first picture (the worst image's) as before Audit version 5, then every picture.
    j.key("differenceImage").value(m.differences[0].file.string()).key("difference").value(m.differences[0].description);
    j.key("differences").beginArray();
    for (const DifferenceImage& d : m.differences) {
      j.beginObject().key("file").value(d.file.string()).key("image").value(d.image).key("worst").value(d.worst);
      j.key("light");
      if (d.light) j.beginArray().value((*d.light)[0]).value((*d.light)[1]).value((*d.light)[2]).endArray();
      else j.null();
      j.key("fullScale").value(d.fullScale).key("description").value(d.description).endObject();
    }
    j.endArray();
  }
  j.endObject();
}

void verdictJson(JsonWriter& j, const Verdict& v) {
  j.beginObject().key("model").value(v.model.string()).key("lightFile").value(v.lightFile.string());
  j.key("reproduced").value(v.reproduced).key("dbBelowRefit").value(db(v.dbBelowRefit));
  j.key("maxDegrees").value(degrees(v.maxDegrees)).key("findings").beginArray();
  for (const Finding& f : v.findings)
    j.beginObject().key("cause").value(causeName(f.cause)).key("text").value(f.text).endObject();
  j.endArray().key("sentence").value(v.sentence).endObject();
}

std::string errorsLine(const std::string& label, const ModelErrors& e) {
  if (!e.computed) return "  " + label + ": not computed (" + e.note + ")";
  return "  " + label + ": PSNR " + fixedDecimals(e.psnr, 2) + " dB (RMSE " + fixedDecimals(e.rmse, 2) +
         "; median " + fixedDecimals(e.medianPsnr, 2) + " dB, worst " + fixedDecimals(e.worstPsnr, 2) + " dB at " +
         e.worstImage + ")";
}

void lightLines(std::vector<std::string>& out, const LightComparison& l) {
  std::string line = "prior light file " + l.file.string() + ": " + std::to_string(l.angles.size()) +
                     " images compared, median " + fixedDecimals(l.medianDegrees, 1) + ", p95 " +
                     fixedDecimals(l.p95Degrees, 1) + ", max " + fixedDecimals(l.maxDegrees, 1) + " degrees; " +
                     std::to_string(l.aboveThreshold.size()) + " differ (beyond both the combined uncertainty and " +
                     "the threshold " + fixedDecimals(l.thresholdDegrees, 1) + " deg)";
  for (std::size_t i = 0; i < l.aboveThreshold.size(); ++i)
    line += (i ? ", " : ": ") + l.aboveThreshold[i].image + " (" + fixedDecimals(l.aboveThreshold[i].degrees, 1) + ")";
  out.push_back(line);
  // Every light past the threshold, judged: those the uncertainty covers are said so.
  for (const ImageAngle& a : l.angles)
    if (a.degrees > l.thresholdDegrees) out.push_back("  " + lightJudgement(a, l.thresholdDegrees));
  auto names = [](const std::vector<std::string>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
    return s;
  };
  if (!l.onlyInPrior.empty()) out.push_back("  named by the light file only: " + names(l.onlyInPrior));
  if (!l.onlyInSurrogate.empty()) out.push_back("  photographs without a prior light: " + names(l.onlyInSurrogate));
}

void modelLines(std::vector<std::string>& out, const ModelCheck& m) {
  out.push_back("prior model " + m.file.string() + " (" + m.basis + ", lights of " +
                (m.lightFile.empty() ? std::string("none") : m.lightFile.filename().string()) + "): " +
                m.size.describe());
  out.push_back("  error on Rec. 709 luminance of the " + m.values + " photographs, 0..255:");
  out.push_back(errorsLine("prior model, prior lights  ", m.prior));
  out.push_back(errorsLine("Surrogate fit, prior lights", m.refitPriorLights));
  out.push_back(errorsLine("Surrogate fit, its lights  ", m.refitSurrogateLights));
  if (m.colour.measured)
    out.push_back("  tone of the prior against the photographs: gain " + fixedDecimals(m.colour.gain, 3) + ", gamma " +
                  fixedDecimals(m.colour.gamma, 3) + (m.colour.differs ? " (differs)" : ""));
  std::string clipped;
  for (const PlaneCheck& p : m.quantisation.planes)
    if (p.clamped) clipped += (clipped.empty() ? "" : ", ") + p.plane;
  out.push_back("  quantisation: " + (clipped.empty() ? std::string("no clipped plane") : "clipped planes " + clipped));
  for (const DifferenceImage& d : m.differences)
    out.push_back(std::string(d.worst ? "  difference image (worst image): " : "  difference image: ") +
                  d.file.string() + " (" + d.description + ")");
}

}  // namespace

void writeAuditJson(JsonWriter& j, const AuditReport& report) {
  j.beginObject().key("thresholdDegrees").value(report.thresholdDegrees).key("lightFiles").beginArray();
  for (const auto& l : report.lights) lightsJson(j, l);
  j.endArray().key("models").beginArray();
  for (const auto& m : report.models) modelJson(j, m);
  j.endArray().key("verdicts").beginArray();
  for (const auto& v : report.verdicts) verdictJson(j, v);
  j.endArray().key("notAudited").beginArray();
  for (const auto& n : report.notAudited)
    j.beginObject().key("file").value(n.file.generic_string()).key("reason").value(n.reason).endObject();
  j.endArray().key("priorLogs").beginArray();
  for (const auto& l : report.logs) {
    j.beginObject().key("file").value(l.file.generic_string()).key("records");
    nameList(j, l.records);
    j.key("discrepancies");
    nameList(j, l.discrepancies);
    j.endObject();
  }
  j.endArray().endObject();
}

std::string auditJson(const AuditReport& report) {
  JsonWriter j;
  writeAuditJson(j, report);
  return j.str();
}

std::vector<std::string> auditLines(const AuditReport& report) {
  std::vector<std::string> out;
  for (const auto& l : report.lights) lightLines(out, l);
  for (const auto& m : report.models) modelLines(out, m);
  for (const auto& v : report.verdicts)
    out.push_back("verdict (" + (v.model.empty() ? v.lightFile : v.model).filename().string() + "): " + v.sentence);
  for (const auto& n : report.notAudited)
    out.push_back("not audited: " + n.file.generic_string() + " (" + n.reason + ")");
  for (const auto& l : report.logs) {
    out.push_back("prior log " + l.file.generic_string() + ": what it records of the processing");
    for (const std::string& r : l.records) out.push_back("  " + r);
    if (l.discrepancies.empty()) out.push_back("  agrees with the photographs audited");
    for (const std::string& d : l.discrepancies) out.push_back("  differs: " + d);
  }
  return out;
}

}  // namespace surrogate::audit
