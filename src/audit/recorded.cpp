// The audit in a carrier result and back (the layout is in recorded.h).
#include "audit/recorded.h"

#include <sstream>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::audit {
namespace {

constexpr const char* kLpInput = "prior-lp";
constexpr const char* kModelInput = "prior-model";
constexpr const char* kLogInput = "prior-log";
constexpr const char* kPhotographInput = "image";
const char* const kErrorSets[] = {"prior", "refitPriorLights", "refitSurrogateLights"};

const char* relationName(SizeRelation::Kind kind) {
  switch (kind) {
    case SizeRelation::Kind::Same: return "same";
    case SizeRelation::Kind::UniformScale: return "uniform-scale";
    case SizeRelation::Kind::Different: return "different";
  }
  return "different";
}

SizeRelation::Kind relationOf(const std::string& name) {
  if (name == "same") return SizeRelation::Kind::Same;
  if (name == "uniform-scale") return SizeRelation::Kind::UniformScale;
  return SizeRelation::Kind::Different;
}

std::string idOf(const std::map<std::string, std::string>& ids, const std::string& key) {
  const auto it = ids.find(key);
  if (it == ids.end())
    throw Error(ErrorKind::Internal, key, "audit", "the audit names a file the carrier does not list");
  return it->second;
}

std::string triple(const Light& l) {
  return formatNumber(l[0]) + " " + formatNumber(l[1]) + " " + formatNumber(l[2]);
}

// Writes <imageValue image=id name=... value=...>.
class Writer {
 public:
  explicit Writer(carrier::Result& r) : r_(r) {}
  void text(const std::string& id, const std::string& name, const std::string& value,
            const std::string& unit = "") {
    carrier::DataItem& d = r_.add("imageValue").set("image", id).set("name", name).set("value", value);
    if (!unit.empty()) d.set("unit", unit);
  }
  void number(const std::string& id, const std::string& name, double v, const std::string& unit = "") {
    text(id, name, formatNumber(v), unit);
  }
  void flag(const std::string& id, const std::string& name, bool v) { text(id, name, v ? "true" : "false"); }
  void input(const std::string& id, const char* kind) { r_.add("input").set("file", id).set("kind", kind); }

 private:
  carrier::Result& r_;
};

void writeLights(Writer& w, const LightComparison& l, const RecordedIds& ids) {
  const std::string lp = idOf(ids.priorFiles, l.file.generic_string());
  w.input(lp, kLpInput);
  w.number(lp, "imagesCompared", static_cast<double>(l.angles.size()));
  w.number(lp, "medianDegrees", l.medianDegrees, "degree");
  w.number(lp, "p95Degrees", l.p95Degrees, "degree");
  w.number(lp, "maxDegrees", l.maxDegrees, "degree");
  for (const std::string& name : l.onlyInPrior) w.text(lp, "onlyInPrior", name);
  for (const ImageAngle& a : l.angles) {
    const std::string photo = idOf(ids.photographs, a.image);
    w.number(photo, "lightAngle", a.degrees, "degree");
    w.text(photo, "priorLight", triple(a.prior));
    // The uncertainties the light was judged with (Audit version 7), where stated.
    if (a.ours) w.number(photo, "lightUncertainty", *a.ours, "degree");
    if (a.priors) w.number(photo, "priorLightUncertainty", *a.priors, "degree");
  }
  for (const ImageAngle& a : l.aboveThreshold) w.number(idOf(ids.photographs, a.image), "aboveThreshold", a.degrees, "degree");
  for (const std::string& name : l.onlyInSurrogate) w.text(idOf(ids.photographs, name), "noPriorLight", "true");
}

void writeErrors(Writer& w, const std::string& model, const std::string& set, const ModelErrors& e,
                 const RecordedIds& ids) {
  if (!e.computed) {
    w.text(model, set + " note", e.note.empty() ? "not computed" : e.note);
    return;
  }
  w.number(model, set + " psnr", e.psnr, "dB");
  w.number(model, set + " rmse", e.rmse, "8-bit levels");
  w.number(model, set + " medianPsnr", e.medianPsnr, "dB");
  w.number(model, set + " worstPsnr", e.worstPsnr, "dB");
  w.text(model, set + " worstImage", e.worstImage);
  for (const ImageError& i : e.images) {
    const std::string photo = idOf(ids.photographs, i.image);
    w.number(photo, set + " psnr", i.psnr, "dB");
    w.number(photo, set + " rmse", i.rmse, "8-bit levels");
    // The light each photograph was rendered at, for the report's plot of the prior's errors
    // (the prior's lights only: the refits are rendered at the same or at Surrogate's).
    if (set == kErrorSets[0] && i.light) w.text(photo, set + " light", triple(*i.light));
  }
}

void writeModel(Writer& w, const ModelCheck& m, const RecordedIds& ids) {
  const std::string id = idOf(ids.priorFiles, m.file.generic_string());
  w.input(id, kModelInput);
  if (!m.lightFile.empty()) w.text(id, "lightFile", m.lightFile.generic_string());
  w.text(id, "basis", m.basis.empty() ? "unknown" : m.basis);
  w.text(id, "values", m.values.empty() ? "unknown" : m.values);
  w.text(id, "size", relationName(m.size.kind));
  w.text(id, "modelSize", std::to_string(m.size.modelWidth) + " " + std::to_string(m.size.modelHeight));
  w.text(id, "photographSize", std::to_string(m.size.photoWidth) + " " + std::to_string(m.size.photoHeight));
  w.number(id, "scale", m.size.scale);
  writeErrors(w, id, kErrorSets[0], m.prior, ids);
  writeErrors(w, id, kErrorSets[1], m.refitPriorLights, ids);
  writeErrors(w, id, kErrorSets[2], m.refitSurrogateLights, ids);
  if (m.colour.measured) {
    w.number(id, "toneGain", m.colour.gain);
    w.number(id, "toneGamma", m.colour.gamma);
    w.number(id, "toneRmseBefore", m.colour.rmseBefore, "8-bit levels");
    w.number(id, "toneRmseAfter", m.colour.rmseAfter, "8-bit levels");
    w.flag(id, "toneDiffers", m.colour.differs);
  }
  w.flag(id, "clamped", m.quantisation.clamped);
  for (const PlaneCheck& p : m.quantisation.planes)
    w.text(id, "plane " + p.plane, formatNumber(p.atZero) + " " + formatNumber(p.atFull) + " " +
                                       formatNumber(p.outsideRange) + (p.clamped ? " clamped" : " fine"));
  for (const DifferenceImage& d : m.differences) {
    w.text(id, "differenceImage", d.file.generic_string());  // opens the picture's figures
    if (!d.image.empty()) w.text(id, "differenceOf", d.image);
    if (d.light) w.text(id, "differenceLight", triple(*d.light));
    w.number(id, "differenceFullScale", d.fullScale, "8-bit levels");
    w.flag(id, "differenceWorst", d.worst);
    w.text(id, "difference", d.description);
  }
}

void writeLog(Writer& w, const AuditReport::PriorLog& l, const RecordedIds& ids) {
  const std::string id = idOf(ids.priorFiles, l.file.generic_string());
  w.input(id, kLogInput);
  for (const std::string& r : l.records) w.text(id, "logRecord", r);
  for (const std::string& d : l.discrepancies) w.text(id, "logDiscrepancy", d);
}

void writeVerdict(Writer& w, const Verdict& v, const RecordedIds& ids) {
  const std::string id = idOf(ids.priorFiles, (v.model.empty() ? v.lightFile : v.model).generic_string());
  if (!v.model.empty() && !v.lightFile.empty()) w.text(id, "verdict lightFile", v.lightFile.generic_string());
  w.flag(id, "verdict reproduced", v.reproduced);
  w.number(id, "verdict dbBelowRefit", v.dbBelowRefit, "dB");
  w.number(id, "verdict maxDegrees", v.maxDegrees, "degree");
  for (const Finding& f : v.findings) w.text(id, std::string("finding ") + causeName(f.cause), f.text);
  w.text(id, "verdict", v.sentence);
}

// ---- reading -------------------------------------------------------------------------------

double numberIn(const std::string& text, const std::string& what) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  throw Error(ErrorKind::Input, "carrier", "audit", "the audit figure " + what + " is not a number: \"" + text + "\"");
}

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

Finding::Cause causeOf(const std::string& name) {
  for (Finding::Cause c : {Finding::Cause::DifferentLights, Finding::Cause::MissingImages,
                           Finding::Cause::DifferentSize, Finding::Cause::ColourHandling,
                           Finding::Cause::BrokenBias, Finding::Cause::FitShortfall})
    if (name == causeName(c)) return c;
  throw Error(ErrorKind::Input, "carrier", "audit", "the audit finding \"" + name + "\" is not one Surrogate writes");
}

ModelErrors* errorSet(ModelCheck& m, const std::string& set) {
  if (set == kErrorSets[0]) return &m.prior;
  if (set == kErrorSets[1]) return &m.refitPriorLights;
  if (set == kErrorSets[2]) return &m.refitSurrogateLights;
  return nullptr;
}

class Reader {
 public:
  Reader(const carrier::Carrier& c, AuditReport& out) : c_(c), out_(out) {}

  void input(const carrier::DataItem& d) {
    const std::string kind = d.get("kind").value_or("");
    const std::string path = pathOf(d.get("file").value_or(""));
    lights_ = nullptr;
    model_ = nullptr;
    log_ = nullptr;
    if (kind == kLogInput) {
      out_.logs.emplace_back();
      log_ = &out_.logs.back();
      log_->file = path;
    } else if (kind == kLpInput) {
      out_.lights.emplace_back();
      lights_ = &out_.lights.back();
      lights_->file = path;
      lights_->thresholdDegrees = out_.thresholdDegrees;
    } else if (kind == kModelInput) {
      out_.models.emplace_back();
      model_ = &out_.models.back();
      model_->file = path;
    }
  }

  void value(const carrier::DataItem& d) {
    const std::string id = d.get("image").value_or(""), name = d.get("name").value_or("");
    const std::string v = d.get("value").value_or("");
    const carrier::FileRecord* f = c_.findFile(id);
    const bool photograph = f && f->role != "prior";
    if (name == "notAudited") return out_.notAudited.push_back({pathOf(id), v});
    if (name.rfind("verdict", 0) == 0 || name.rfind("finding ", 0) == 0) return verdict(name, v, pathOf(id));
    if (photograph) return perPhotograph(fileName(*f), name, v);
    if (log_) {
      if (name == "logRecord") log_->records.push_back(v);
      else if (name == "logDiscrepancy") log_->discrepancies.push_back(v);
      return;
    }
    if (lights_) return lightFigure(name, v);
    if (model_) return modelFigure(name, v);
  }

 private:
  std::string pathOf(const std::string& id) const {
    const carrier::FileRecord* f = c_.findFile(id);
    return f ? f->path : id;
  }
  static std::string fileName(const carrier::FileRecord& f) {
    return std::filesystem::u8path(f.path).filename().u8string();
  }

  void lightFigure(const std::string& name, const std::string& v) {
    if (name == "medianDegrees") lights_->medianDegrees = numberIn(v, name);
    else if (name == "p95Degrees") lights_->p95Degrees = numberIn(v, name);
    else if (name == "maxDegrees") lights_->maxDegrees = numberIn(v, name);
    else if (name == "onlyInPrior") lights_->onlyInPrior.push_back(v);
  }

  void modelFigure(const std::string& name, const std::string& v) {
    ModelCheck& m = *model_;
    const auto space = name.find(' ');
    if (space != std::string::npos) {
      const std::string head = name.substr(0, space), tail = name.substr(space + 1);
      if (head == "plane") return plane(tail, v);
      if (ModelErrors* e = errorSet(m, head)) return errorFigure(*e, tail, v);
    }
    if (name == "lightFile") m.lightFile = v;
    else if (name == "basis") m.basis = v;
    else if (name == "values") m.values = v;
    else if (name == "size") m.size.kind = relationOf(v);
    else if (name == "modelSize" || name == "photographSize") {
      const auto wh = words(v);
      if (wh.size() != 2) numberIn(v, name);
      (name == "modelSize" ? m.size.modelWidth : m.size.photoWidth) = static_cast<int>(numberIn(wh[0], name));
      (name == "modelSize" ? m.size.modelHeight : m.size.photoHeight) = static_cast<int>(numberIn(wh[1], name));
    } else if (name == "scale") m.size.scale = numberIn(v, name);
    else if (name == "toneGain") m.colour.measured = true, m.colour.gain = numberIn(v, name);
    else if (name == "toneGamma") m.colour.gamma = numberIn(v, name);
    else if (name == "toneRmseBefore") m.colour.rmseBefore = numberIn(v, name);
    else if (name == "toneRmseAfter") m.colour.rmseAfter = numberIn(v, name);
    else if (name == "toneDiffers") m.colour.differs = v == "true";
    else if (name == "clamped") m.quantisation.clamped = v == "true";
    else if (name == "differenceImage") m.differences.push_back({v, "", std::nullopt, 0, false, ""});
    else if (name.rfind("difference", 0) == 0 && !m.differences.empty()) difference(m.differences.back(), name, v);
  }

  // The figures of the difference picture last opened by differenceImage (results before Audit
  // version 5 have its `difference` only).
  static void difference(DifferenceImage& d, const std::string& name, const std::string& v) {
    if (name == "differenceOf") d.image = v;
    else if (name == "differenceLight") d.light = lightIn(v, name);
    else if (name == "differenceFullScale") d.fullScale = numberIn(v, name);
    else if (name == "differenceWorst") d.worst = v == "true";
    else if (name == "difference") d.description = v;
  }

  static Light lightIn(const std::string& v, const std::string& name) {
    const auto w = words(v);
    if (w.size() != 3) numberIn(v, name);
    return {numberIn(w[0], name), numberIn(w[1], name), numberIn(w[2], name)};
  }

  void errorFigure(ModelErrors& e, const std::string& name, const std::string& v) {
    if (name == "note") {
      e.note = v;
      return;
    }
    e.computed = true;
    if (name == "psnr") e.psnr = numberIn(v, name);
    else if (name == "rmse") e.rmse = numberIn(v, name);
    else if (name == "medianPsnr") e.medianPsnr = numberIn(v, name);
    else if (name == "worstPsnr") e.worstPsnr = numberIn(v, name);
    else if (name == "worstImage") e.worstImage = v;
  }

  void plane(const std::string& plane, const std::string& v) {
    const auto w = words(v);
    if (w.size() != 4) numberIn(v, "plane " + plane);
    model_->quantisation.planes.push_back({plane, numberIn(w[0], plane), numberIn(w[1], plane),
                                           numberIn(w[2], plane), w[3] == "clamped"});
  }

  void perPhotograph(const std::string& image, const std::string& name, const std::string& v) {
    if (lights_) {
      ImageAngle* last = !lights_->angles.empty() && lights_->angles.back().image == image ? &lights_->angles.back() : nullptr;
      if (name == "lightAngle") lights_->angles.push_back({image, numberIn(v, name), {}, std::nullopt, std::nullopt});
      else if (name == "lightUncertainty" && last) last->ours = numberIn(v, name);
      else if (name == "priorLightUncertainty" && last) last->priors = numberIn(v, name);
      else if (name == "aboveThreshold") aboveThreshold(image, numberIn(v, name));
      else if (name == "noPriorLight") lights_->onlyInSurrogate.push_back(image);
      else if (name == "priorLight" && !lights_->angles.empty() && lights_->angles.back().image == image) {
        const auto w = words(v);
        if (w.size() != 3) numberIn(v, name);
        for (int k = 0; k < 3; ++k) lights_->angles.back().prior[k] = numberIn(w[k], name);
      }
      return;
    }
    if (!model_) return;
    const auto space = name.find(' ');
    ModelErrors* e = space == std::string::npos ? nullptr : errorSet(*model_, name.substr(0, space));
    if (!e) return;
    const std::string figure = name.substr(space + 1);
    if (figure == "psnr") e->images.push_back({image, 0, numberIn(v, name), std::nullopt});
    else if (figure == "rmse" && !e->images.empty() && e->images.back().image == image)
      e->images.back().rmse = numberIn(v, name);
    else if (figure == "light" && !e->images.empty() && e->images.back().image == image)
      e->images.back().light = lightIn(v, name);
  }

  // A light that differs, with the uncertainties its angle was recorded with (written before it).
  void aboveThreshold(const std::string& image, double degrees) {
    ImageAngle a{image, degrees, {}, std::nullopt, std::nullopt};
    for (const ImageAngle& known : lights_->angles)
      if (known.image == image) a = known;
    a.degrees = degrees;
    lights_->aboveThreshold.push_back(a);
  }

  void verdict(const std::string& name, const std::string& v, const std::string& path) {
    if (name == "verdict lightFile") pending_.lightFile = v;
    else if (name == "verdict reproduced") pending_.reproduced = v == "true";
    else if (name == "verdict dbBelowRefit") pending_.dbBelowRefit = numberIn(v, name);
    else if (name == "verdict maxDegrees") pending_.maxDegrees = numberIn(v, name);
    else if (name.rfind("finding ", 0) == 0) pending_.findings.push_back({causeOf(name.substr(8)), v});
    else if (name == "verdict") {
      pending_.sentence = v;
      bool isModel = false;
      for (const ModelCheck& m : out_.models) isModel = isModel || m.file == path;
      (isModel ? pending_.model : pending_.lightFile) = path;
      out_.verdicts.push_back(pending_);
      pending_ = Verdict{};
    }
  }

  const carrier::Carrier& c_;
  AuditReport& out_;
  LightComparison* lights_ = nullptr;
  ModelCheck* model_ = nullptr;
  AuditReport::PriorLog* log_ = nullptr;
  Verdict pending_;
};

}  // namespace

void recordAudit(const AuditReport& report, const RecordedIds& ids, carrier::Result& result) {
  Writer w(result);
  result.add("value").set("name", "thresholdDegrees").set("value", formatNumber(report.thresholdDegrees)).set("unit", "degree");
  for (const auto& [name, id] : ids.photographs) w.input(id, kPhotographInput);
  for (const LightComparison& l : report.lights) writeLights(w, l, ids);
  for (const ModelCheck& m : report.models) writeModel(w, m, ids);
  for (const Verdict& v : report.verdicts) writeVerdict(w, v, ids);
  for (const AuditReport::PriorLog& l : report.logs) writeLog(w, l, ids);
  for (const auto& n : report.notAudited) w.text(idOf(ids.priorFiles, n.file.generic_string()), "notAudited", n.reason);
}

AuditReport recordedAudit(const carrier::Carrier& carrier, const carrier::Result& result) {
  AuditReport out;
  for (const carrier::DataItem* d : result.itemsOf("value"))
    if (d->get("name") == "thresholdDegrees") out.thresholdDegrees = numberIn(d->get("value").value_or(""), "thresholdDegrees");
  // The margin is a parameter of the step (its default when the step does not say).
  if (const carrier::Step* step = carrier.findStep(result.step); step && step->hasParam("reproducedMarginDb"))
    out.reproducedDb = numberIn(step->param("reproducedMarginDb"), "reproducedMarginDb");
  // Sections point into out.lights / out.models: reserve so that no pointer moves.
  std::size_t inputs = 0;
  for (const carrier::DataItem& d : result.items) inputs += d.element == "input";
  out.lights.reserve(inputs);
  out.models.reserve(inputs);
  out.logs.reserve(inputs);
  Reader reader(carrier, out);
  for (const carrier::DataItem& d : result.items) {
    if (d.element == "input" && d.get("kind") != std::string(kPhotographInput)) reader.input(d);
    else if (d.element == "imageValue") reader.value(d);
  }
  return out;
}

const carrier::Result* auditResult(const carrier::Carrier& carrier) {
  const carrier::Result* found = nullptr;
  for (const carrier::Step& s : carrier.process)
    if (s.component == kAuditComponent)
      if (const carrier::Result* r = carrier.findResult(s.id); r && r->status == "completed") found = r;
  return found;
}

}  // namespace surrogate::audit
