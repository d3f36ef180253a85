// The capture's memory: the decisions a carrier records, and a new command's decisions applied
// to them (run/plan.h: standingDecisions, applyDecisions).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "carrier/carrier.h"
#include "core/error.h"
#include "core/sphere_reference.h"
#include "core/text.h"
#include "stages/outputs.h"
#include "run/plan.h"
#include "pipeline/stage.h"
#include "stages/decode_stage.h"
#include "stages/learned_fit_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/ingest_stage.h"
#include "stages/registry.h"
#include "stages/recorded_checks.h"

namespace surrogate::run {

namespace fs = std::filesystem;

namespace {

// The slot a component has in the plan (NotPlanned for one this build does not have).
pipeline::PlanSlot slotOf(const std::string& component) {
  const pipeline::StageInfo* info = pipeline::StageRegistry::instance().info(component);
  return info ? info->slot : pipeline::PlanSlot::NotPlanned;
}

// The registration order of a pre-processing stage: the order `surrogate run` records them in.
std::size_t preprocessingRank(const std::string& component) {
  const auto stages = pipeline::StageRegistry::instance().stages();
  for (std::size_t n = 0; n < stages.size(); ++n)
    if (stages[n]->component == component) return n;
  return stages.size();
}

// The shot an exclusion names, for comparing two exclusions ("IMG_0003", "IMG_0003.dng" and
// "original-captures/IMG_0003.dng" are one shot).
std::string shotOf(const std::string& name) {
  const auto slash = name.find_last_of("/\\");
  const std::string base = slash == std::string::npos ? name : name.substr(slash + 1);
  const std::string stem = fs::path(base).stem().string();
  return stem.empty() ? base : stem;
}

// An accepted damaged image named as users name images: its path, file name or shot.
bool namesImage(const std::string& path, const std::string& name) {
  if (path == name) return true;
  const auto slash = path.find_last_of('/');
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  return base == name || (name.find('/') == std::string::npos && shotOf(path) == shotOf(name));
}

// Puts `value` in `list` in place of the element `same` finds, or adds it at the end; returns
// the element replaced (none when added), from which the caller words the change.
template <class T, class Same>
std::optional<T> replaceOrAdd(std::vector<T>& list, const T& value, Same same) {
  const auto it = std::find_if(list.begin(), list.end(), same);
  if (it == list.end()) {
    list.push_back(value);
    return std::nullopt;
  }
  std::optional<T> old = *it;
  *it = value;
  return old;
}

// A decision's target as a person types it: spheres as sphereN (core/sphere_reference.h).
std::string shownTarget(const std::string& kind, const std::string& target) {
  return kind == "manual-sphere" || kind == "manual-highlight" ? personsSphereTarget(target) : target;
}

std::string describe(const carrier::Intervention& i) {
  std::string what = i.kind == "exclude-image"          ? "exclusion of " + i.target
                     : i.kind == "manual-sphere"        ? "circle by hand of " + personsSphereTarget(i.target) + " (" + i.value + ")"
                     : i.kind == "manual-highlight"     ? "highlight by hand " + personsSphereTarget(i.target) + " (" + i.value + ")"
                     : i.kind == "accept-decoder-warning" ? "accepted damage in " + i.target
                     : i.kind == stages::kAcceptCheck   ? "accepted check " + i.target
                                                        : i.kind + " " + i.target;
  return what + ", recorded " + i.time + " by " + i.who + " (\"" + i.reason + "\")";
}

// A recorded parameter value as this version writes it: a number from an older carrier
// ("0.80000000000000004", from "%.17g") becomes its shortest form ("0.8", core/text.h), the same
// double, so that it compares equal to the defaults and to the same value given again, and the
// next run records it short. Integers and text are kept as they are.
std::string recordedValue(const std::string& value) {
  if (value.find_first_of(".eE") == std::string::npos) return value;
  double v = 0;
  const char* end = value.data() + value.size();
  const auto r = std::from_chars(value.data(), end, v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != end || !std::isfinite(v)) return value;
  return formatNumber(v);
}

// The options of a recorded web copy step that differ from the defaults, as stage parameters
// (its model follows from the bases).
void addPublishOptions(const carrier::Step& s, const pipeline::Parameters& defaults, RunRequest& r) {
  for (const carrier::Param& p : s.params) {
    if (p.name == "model") continue;
    const auto d = std::find_if(defaults.begin(), defaults.end(), [&](const auto& kv) { return kv.first == p.name; });
    if (d == defaults.end() || d->second != p.value) r.stageParams.push_back({s.component, p.name, p.value});
  }
}

// Web copy options given without a web copy, standing or asked for, would do nothing: refused.
// When the web copy is withdrawn, its standing options go with it.
void settlePublishOptions(RunRequest& r, const RunRequest& given) {
  if (r.publish.value_or(false)) return;
  for (const RunRequest::StageParam& p : given.stageParams)
    if (slotOf(p.component) == pipeline::PlanSlot::Publish)
      throw Error(ErrorKind::Usage, "--publish-" + std::string(p.name == "tileSize" ? "tile-size" : p.name), "command line",
                  "sets an option of the web copy, which this capture does not make; add --publish");
  auto& params = r.stageParams;
  params.erase(std::remove_if(params.begin(), params.end(),
                              [](const RunRequest::StageParam& p) { return slotOf(p.component) == pipeline::PlanSlot::Publish; }),
               params.end());
}

// A parameter of the step the command plans only (pipeline::StageInfo::perCommand).
bool isPerCommand(const RunRequest::StageParam& p) {
  const pipeline::StageInfo* info = pipeline::StageRegistry::instance().info(p.component);
  return info && std::find(info->perCommand.begin(), info->perCommand.end(), p.name) != info->perCommand.end();
}

}  // namespace

RunRequest standingDecisions(const carrier::Carrier& recorded) {
  RunRequest r;
  r.title = recorded.header.title;
  r.creators = recorded.header.creators;
  r.meta = recorded.header.meta;
  r.rights = recorded.header.rights;
  r.license = recorded.header.license;
  r.audited = recorded.header.audited;
  stages::registerBuiltinStages();
  std::vector<std::string> bases;
  for (const carrier::Step& s : carrier::standingProcess(recorded)) {
    const pipeline::StageInfo* info = pipeline::StageRegistry::instance().info(s.component);
    const pipeline::PlanSlot slot = info ? info->slot : pipeline::PlanSlot::NotPlanned;
    if (s.component == stages::IngestStage::kComponent) {
      r.source = s.param("source", "auto");
      if (s.hasParam("lp")) r.lp = s.param("lp");
      for (const carrier::Intervention& i : s.interventions) {
        if (i.kind == "exclude-image") r.exclusions.push_back({i.target, i.reason, i.who, i.time});
        else r.stageInterventions.push_back({s.component, i});
      }
    } else if (s.component == stages::DecodeStage::kComponent) {
      for (const carrier::Param& p : s.params) r.decodeSettings.emplace_back(p.name, recordedValue(p.value));
      for (const carrier::Intervention& i : s.interventions) r.stageInterventions.push_back({s.component, i});
    } else if (slot == pipeline::PlanSlot::Preprocessing) {
      PlannedStage p{s.component, {}};
      for (const carrier::Param& q : s.params) p.params.emplace_back(q.name, recordedValue(q.value));
      r.preprocessing.push_back(std::move(p));
    } else if (slot == pipeline::PlanSlot::Publish) {
      // One step per model, with the same options: those of the first, without its model.
      if (!r.publish) addPublishOptions(s, info->defaults, r);
      r.publish = true;
    } else if (s.component == stages::RtiFitStage::kComponent) {
      const stages::RtiFitOptions fitted = stages::RtiFitOptions::fromParameters(stages::parametersOf(s));
      bases.push_back(fit::basisName(fitted.fit.basis));
      // --holdout stands like the bases (the same K for every fit step: the first one's).
      const bool known = std::any_of(r.stageParams.begin(), r.stageParams.end(), [](const RunRequest::StageParam& p) {
        return p.component == stages::RtiFitStage::kComponent && p.name == "holdout";
      });
      if (fitted.holdout > 0 && !known)
        r.stageParams.push_back({s.component, "holdout", std::to_string(fitted.holdout)});
    } else if (s.component == stages::LearnedFitStage::kComponent) {
      // One step per learned basis, with the same options (--planes, --holdout, ...): those of
      // the first that differ from the defaults, without its basis, which the plan gives.
      const stages::LearnedFitOptions o = stages::LearnedFitOptions::fromParameters(stages::parametersOf(s));
      if (std::find(bases.begin(), bases.end(), "rbf") == bases.end() &&
          std::find(bases.begin(), bases.end(), "bln") == bases.end())
        for (const auto& [name, value] : o.toParameters())
          for (const auto& [dname, dvalue] : info->defaults)
            if (name == dname && name != "basis" && value != dvalue) r.stageParams.push_back({s.component, name, value});
      bases.push_back(o.basis);
    } else if (!info || !info->forModel) {  // the plan derives a forModel stage's parameters
      const pipeline::Parameters defaults = info ? info->defaults : pipeline::Parameters{};
      for (const carrier::Param& p : s.params) {
        // A parameter given for that step only (an audit's threshold, in carriers of every
        // version): the step keeps it for re-execution; the next run plans the default.
        if (isPerCommand({s.component, p.name, p.value})) continue;
        const std::string value = recordedValue(p.value);
        const auto d = std::find_if(defaults.begin(), defaults.end(),
                                    [&](const auto& kv) { return kv.first == p.name; });
        if (d == defaults.end() || d->second != value)
          r.stageParams.push_back({s.component, p.name, value});
      }
      for (const carrier::Intervention& i : s.interventions)
        r.stageInterventions.push_back({s.component, i});
    }
  }
  if (!bases.empty()) r.bases = bases;
  return r;
}

RunRequest applyDecisions(const RunRequest& standing, const RunRequest& given,
                          std::vector<std::string>& changes) {
  RunRequest r = standing;
  r.who = given.who;
  r.command = given.command;
  r.arguments = given.arguments;
  r.lightsOnly = given.lightsOnly;
  r.withdrawals = given.withdrawals;
  r.resetReason = given.resetReason;
  r.acceptedChanges = given.acceptedChanges;

  if (given.resetReason) {
    std::size_t n = r.exclusions.size() + r.stageParams.size() + r.preprocessing.size();
    for (const auto& i : r.stageInterventions) n += i.intervention.kind != "accept-changed-original";
    r.exclusions.clear();
    r.stageParams.clear();
    r.preprocessing.clear();
    r.decodeSettings.clear();
    r.bases.reset();
    r.publish.reset();
    r.lp.reset();
    r.source.clear();
    r.stageInterventions.erase(
        std::remove_if(r.stageInterventions.begin(), r.stageInterventions.end(),
                       [](const auto& i) { return i.intervention.kind != "accept-changed-original"; }),
        r.stageInterventions.end());
    changes.push_back("reset every processing decision to the defaults (" + std::to_string(n) +
                      " withdrawn): " + *given.resetReason);
  }

  for (const Withdrawal& w : given.withdrawals) {
    bool found = false;
    if (w.kind == "exclude-image") {
      for (auto it = r.exclusions.begin(); it != r.exclusions.end(); ++it) {
        if (shotOf(it->image) != shotOf(w.target)) continue;
        changes.push_back("withdrew the " + describe({"exclude-image", it->image, "", it->who, it->time, it->reason}) +
                          ": " + w.reason);
        r.exclusions.erase(it);
        found = true;
        break;
      }
    } else if (w.kind == "accept-decoder-warning") {
      // Named as the user names images: every accepted file of that name goes (an original and
      // its export share a shot name).
      for (auto it = r.stageInterventions.begin(); it != r.stageInterventions.end();) {
        if (it->intervention.kind != w.kind || !namesImage(it->intervention.target, w.target)) {
          ++it;
          continue;
        }
        changes.push_back("withdrew the " + describe(it->intervention) + ": " + w.reason);
        it = r.stageInterventions.erase(it);
        found = true;
      }
    } else {
      for (auto it = r.stageInterventions.begin(); it != r.stageInterventions.end(); ++it) {
        if (it->intervention.kind != w.kind || it->intervention.target != w.target) continue;
        changes.push_back("withdrew the " + describe(it->intervention) + ": " + w.reason);
        r.stageInterventions.erase(it);
        found = true;
        break;
      }
    }
    if (!found) {
      std::string standingList;
      for (const Exclusion& e : r.exclusions) standingList += (standingList.empty() ? "" : ", ") + shotOf(e.image);
      for (const auto& i : r.stageInterventions)
        if (i.intervention.kind == w.kind)
          standingList += (standingList.empty() ? "" : ", ") + shownTarget(w.kind, i.intervention.target);
      const std::string option = w.kind == "exclude-image"            ? "--forget-exclusion"
                                 : w.kind == "manual-sphere"          ? "--forget-sphere"
                                 : w.kind == "accept-decoder-warning" ? "--forget-damaged"
                                 : w.kind == stages::kAcceptCheck     ? "--forget-accept"
                                                                      : "--forget-highlight";
      throw Error(ErrorKind::Usage, option + " " + shownTarget(w.kind, w.target), "command line",
                  "the capture's carrier holds no such decision (standing: " +
                      (standingList.empty() ? std::string("none") : standingList) +
                      "); see them with: surrogate info CAPTURE");
    }
  }

  if (!given.title.empty() && given.title != r.title) {
    // A first run states its title too: the change list is the record of what the user gave.
    changes.push_back(r.title.empty() ? "title \"" + given.title + "\""
                                      : "title \"" + r.title + "\" -> \"" + given.title + "\"");
    r.title = given.title;
  }
  for (const carrier::Creator& c : given.creators) {
    const auto old = replaceOrAdd(r.creators, c, [&](const carrier::Creator& k) { return k.name == c.name; });
    if (!old) changes.push_back("added creator " + c.name + " (" + c.role + ")");
    else if (old->role != c.role) changes.push_back("creator " + c.name + ": role " + old->role + " -> " + c.role);
  }
  for (const auto& kv : given.meta) {
    const auto& [key, value] = kv;
    const auto old = replaceOrAdd(r.meta, kv, [&](const auto& k) { return k.first == key; });
    if (!old) changes.push_back("metadata " + key + " = \"" + value + "\"");
    else if (old->second != value) changes.push_back("metadata " + key + ": \"" + old->second + "\" -> \"" + value + "\"");
  }
  if (!given.rights.empty() && given.rights != r.rights) {
    changes.push_back(r.rights.empty() ? "rights \"" + given.rights + "\""
                                       : "rights \"" + r.rights + "\" -> \"" + given.rights + "\"");
    r.rights = given.rights;
  }
  if (given.audited) {
    if (!r.audited) changes.push_back("the audit's evidence: " + std::to_string(given.audited->files.size()) +
                                      " files copied from " + given.audited->source);
    r.audited = given.audited;
  }
  if (!given.license.empty() && given.license != r.license) {
    changes.push_back(r.license.empty() ? "license " + given.license : "license " + r.license + " -> " + given.license);
    r.license = given.license;
  }
  if (!given.source.empty() && given.source != (r.source.empty() ? "auto" : r.source)) {
    changes.push_back("image source " + (r.source.empty() ? std::string("auto") : r.source) + " -> " + given.source);
    r.source = given.source;
  }
  const bool wasDome = r.lp && !r.lp->empty();
  if (given.lp && given.lp != r.lp && (wasDome || !given.lp->empty())) {
    changes.push_back(given.lp->empty() ? "lights from the spheres again (no dome .lp)"
                                        : "lights from " + *given.lp + " (dome capture)");
    r.lp = given.lp;
  }
  // The lights' distance is a decision about the lights whichever stage gives them: the
  // spheres' (LightDirections) or a dome's .lp (LightsFromFile: its radius). It follows --lp.
  const bool dome = r.lp && !r.lp->empty();
  auto lightsStage = [dome](RunRequest::StageParam p) {
    if (p.name == "lightDistance" && (p.component == "LightDirections" || p.component == "LightsFromFile"))
      p.component = dome ? "LightsFromFile" : "LightDirections";
    return p;
  };
  for (RunRequest::StageParam& p : r.stageParams) p = lightsStage(p);
  for (const Exclusion& e : given.exclusions) {
    const auto old = replaceOrAdd(r.exclusions, e, [&](const Exclusion& k) { return shotOf(k.image) == shotOf(e.image); });
    if (old) changes.push_back("replaced the " + describe({"exclude-image", old->image, "", old->who, old->time, old->reason}));
    changes.push_back("excluded " + e.image + ": " + e.reason);
  }
  for (const auto& kv : given.decodeSettings) {
    const auto old = replaceOrAdd(r.decodeSettings, kv, [&](const auto& k) { return k.first == kv.first; });
    if (old && old->second != kv.second) changes.push_back("LibRaw " + kv.first + ": " + old->second + " -> " + kv.second);
  }
  for (const RunRequest::StageParam& g : given.stageParams) {
    const RunRequest::StageParam p = lightsStage(g);
    const auto old = replaceOrAdd(r.stageParams, p, [&](const RunRequest::StageParam& k) {
      return k.component == p.component && k.name == p.name;
    });
    const std::string why = p.reason.empty() ? "" : ": " + p.reason;
    if (isPerCommand(p)) changes.push_back(p.component + " " + p.name + " = " + p.value + " (this run only)" + why);
    else if (!old) changes.push_back(p.component + " " + p.name + " = " + p.value + why);
    else if (old->value != p.value) changes.push_back(p.component + " " + p.name + ": " + old->value + " -> " + p.value + why);
    else if (!p.reason.empty()) changes.push_back(p.component + " " + p.name + " = " + p.value + " confirmed" + why);
  }
  for (const RunRequest::StageIntervention& i : given.stageInterventions) {
    const auto old = replaceOrAdd(r.stageInterventions, i, [&](const RunRequest::StageIntervention& k) {
      return k.component == i.component && k.intervention.kind == i.intervention.kind &&
             k.intervention.target == i.intervention.target;
    });
    if (old) changes.push_back("replaced the " + describe(old->intervention));
    changes.push_back(i.intervention.kind + " " + shownTarget(i.intervention.kind, i.intervention.target) +
                      (i.intervention.value.empty() ? "" : " = " + i.intervention.value) + ": " +
                      i.intervention.reason);
  }
  for (const PlannedStage& p : given.preprocessing) {
    replaceOrAdd(r.preprocessing, p, [&](const PlannedStage& k) { return k.component == p.component; });
    changes.push_back("pre-processing " + p.component + " set");
  }
  // The recorded order of pre-processing is their registration order (surrogate run's order:
  // WhiteBalance, Crop, Resize).
  std::stable_sort(r.preprocessing.begin(), r.preprocessing.end(), [](const PlannedStage& a, const PlannedStage& b) {
    return preprocessingRank(a.component) < preprocessingRank(b.component);
  });
  if (given.bases && given.bases != r.bases) {
    std::string list;
    for (const std::string& b : *given.bases) list += (list.empty() ? "" : ", ") + b;
    changes.push_back("bases: " + list);
    r.bases = given.bases;
  }

  if (given.publish && given.publish.value_or(false) != r.publish.value_or(false)) {
    changes.push_back(*given.publish ? "web copy of each model (finished-files/web/)" : "no web copy any more");
    r.publish = given.publish;
  }
  settlePublishOptions(r, given);

  // A dome capture takes its lights from the .lp: sphere and highlight decisions would do
  // nothing, and dropping them silently would lose them.
  if (r.lp && !r.lp->empty()) {
    for (const auto& i : r.stageInterventions)
      if (slotOf(i.component) == pipeline::PlanSlot::LightsFromSpheres)
        throw Error(ErrorKind::Usage, "--lp " + *r.lp, "command line",
                    "a dome capture takes its lights from the .lp file, but the capture holds a " +
                        describe(i.intervention) + ", which would then do nothing; withdraw it "
                        "first (--forget-sphere / --forget-highlight, or --reset --reason \"...\")");
    for (const auto& p : r.stageParams)
      if (slotOf(p.component) == pipeline::PlanSlot::LightsFromSpheres)
        throw Error(ErrorKind::Usage, "--lp " + *r.lp, "command line",
                    "a dome capture takes its lights from the .lp file, but the options of " +
                        p.component + " (" + p.name + " = " + p.value + ") apply to light "
                        "estimation from the spheres; leave them out (or --reset --reason \"...\")");
  }
  return r;
}

}  // namespace surrogate::run
