#include "run/plan.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <set>

#include <Eigen/Core>

#include "archive/package.h"
#include "capture/capture.h"
#include "capture/lock.h"
#include "carrier/advice.h"
#include "carrier/xml.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/identity.h"
#include "core/text.h"
#include "core/version.h"
#include "fit/basis.h"
#include "fit/learned.h"
#include "image/decode.h"
#include "image/write.h"
#include "mapping/mapping.h"
#include "meta/metadata.h"
#include "pipeline/runner.h"
#include "pipeline/stage.h"
#include "stages/audit_stage.h"
#include "stages/decode_stage.h"
#include "stages/ingest_stage.h"
#include "stages/held_out_quality.h"
#include "stages/learned_fit_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/registry.h"
#include "stages/prior_work.h"
#include "run/descriptive_run.h"
#include "run/request_checks.h"
#include "run/run_commit.h"

namespace surrogate::run {

namespace fs = std::filesystem;

std::vector<carrier::Software> softwareVersions() {
  return {
      {"LibRaw", image::librawVersion(), "camera raw decoding"},
      {image::libjpegName(), image::libjpegVersion(), "JPEG decoding and encoding"},
      {"libpng", image::libpngVersion(), "PNG decoding and encoding"},
      {"libdeflate", image::libdeflateVersion(), "PNG compression"},
      {"libtiff", image::libtiffVersion(), "TIFF decoding and writing"},
      {"OpenCV", image::opencvVersion(), "image filtering and resampling"},
      {"Exiv2", meta::exiv2Version(), "EXIF/XMP metadata"},
      {"libxml2", xml::libxml2Version(), "XML and schema validation"},
      {"libxslt", mapping::libxsltVersion(), "the carrier's mappings to METS, CIDOC-CRM and RO-Crate"},
      {"libarchive", archive::libarchiveVersion(), ".tar and .zip packages"},
      {"OpenSSL", opensslVersion(), "message digests"},
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION),
       "linear algebra"},
  };
}

namespace {
std::string defaultWho() { return currentUserName(); }
}  // namespace

namespace {

carrier::Step& addPlannedStep(carrier::Carrier& c, const pipeline::StageInfo& info) {
  carrier::Step& s = c.addStep(info.component, info.version);
  s.description = info.description;
  return s;
}

bool inSlot(const std::string& component, pipeline::PlanSlot slot) {
  const pipeline::StageInfo* info = pipeline::StageRegistry::instance().info(component);
  return info && info->slot == slot;
}

}  // namespace

std::vector<PlannedStage> analysisStages(bool captureHasLp, const RunRequest& request) {
  using pipeline::PlanSlot;
  const std::vector<const pipeline::StageInfo*> stages = pipeline::StageRegistry::instance().stages();
  std::vector<PlannedStage> out;
  auto addSlot = [&](PlanSlot slot, const std::string& basis) {
    for (const pipeline::StageInfo* info : stages)
      if (info->slot == slot && (basis.empty() || !info->takesModel || info->takesModel(basis)))
        out.push_back({info->component, info->forModel && !basis.empty() ? info->forModel(basis)
                                                                         : pipeline::Parameters{}});
  };
  addSlot(captureHasLp ? PlanSlot::LightsFromFile : PlanSlot::LightsFromSpheres, "");
  addSlot(PlanSlot::Colour, "");
  for (const PlannedStage& p : request.preprocessing) {
    if (!inSlot(p.component, PlanSlot::Preprocessing))
      throw Error(ErrorKind::Internal, p.component, "plan", "is not a pre-processing stage");
    out.push_back(p);
  }
  const std::vector<std::string> bases = request.bases.value_or(std::vector<std::string>{"ptm-lrgb", "hsh2"});
  for (const std::string& basis : bases) addSlot(PlanSlot::EachModel, basis);
  if (!bases.empty()) addSlot(PlanSlot::AfterModels, bases.front());
  if (request.publish.value_or(false))
    for (const std::string& basis : bases) addSlot(PlanSlot::Publish, basis);
  if (request.auditPriorWork) addSlot(PlanSlot::PriorWork, "");
  return out;
}

carrier::Carrier planRun(const fs::path& capture, const RunRequest& request) {
  stages::registerBuiltinStages();
  if (!fs::is_directory(capture))
    throwInputError(capture.string(), "plan", fs::exists(capture) ? "is not a folder; give the capture folder"
                                                                   : "the capture folder does not exist");
  const std::string who = request.who.empty() ? defaultWho() : request.who;
  carrier::Carrier c = carrier::newCarrier(
      request.title.empty() ? fs::absolute(capture).lexically_normal().filename().string()
                            : request.title,
      request.creators);
  c.header.meta = request.meta;
  c.header.rights = request.rights;
  c.header.license = request.license;
  c.header.audited = request.audited;
  for (const carrier::Software& s : softwareVersions()) c.header.software.push_back(s);
  auto stamped = [&](carrier::Intervention in) {
    if (in.who.empty()) in.who = who;
    if (in.time.empty()) in.time = carrier::timestampNow();
    return in;
  };

  // Ingest and decode take their parameters from the request's own fields (source, dome .lp,
  // exclusions, LibRaw settings); every later stage from its defaults and the request's
  // stage parameters, in the slot its info() names.
  carrier::Step& ingest = addPlannedStep(c, stages::IngestStage::info());
  ingest.setParam("source", capture::sourceName(capture::parseSource(request.source.empty() ? "auto" : request.source)));
  const bool dome = request.lp && !request.lp->empty();
  if (dome) ingest.setParam("lp", *request.lp);
  for (const Exclusion& e : request.exclusions) {
    if (e.reason.empty())
      throw Error(ErrorKind::Usage, "--exclude " + e.image, "options",
                  "an excluded image needs a reason: add --reason \"...\" after it");
    ingest.interventions.push_back(stamped({"exclude-image", e.image, "", e.who, e.time, e.reason}));
  }
  for (const RunRequest::StageIntervention& i : request.stageInterventions)
    if (i.component == ingest.component) ingest.interventions.push_back(stamped(i.intervention));

  carrier::Step& decode = addPlannedStep(c, stages::DecodeStage::info());
  image::RawDecodeSettings settings = image::RawDecodeSettings::fromParameters(request.decodeSettings);
  for (const auto& [name, value] : settings.toParameters()) decode.setParam(name, value);
  for (const RunRequest::StageIntervention& i : request.stageInterventions)
    if (i.component == decode.component) decode.interventions.push_back(stamped(i.intervention));

  const auto& registry = pipeline::StageRegistry::instance();
  for (const PlannedStage& planned : analysisStages(dome, request)) {
    const std::string& name = planned.component;
    const pipeline::StageInfo* info = registry.info(name);
    if (!info) registry.create(name);  // Error(Input) naming the unknown component
    carrier::Step& s = addPlannedStep(c, *info);
    for (const auto& [pname, pvalue] : info->defaults) s.setParam(pname, pvalue);
    for (const RunRequest::StageParam& p : request.stageParams)
      if (p.component == name) s.setParam(p.name, p.value);
    for (const auto& [pname, pvalue] : planned.params) s.setParam(pname, pvalue);
    for (const RunRequest::StageIntervention& i : request.stageInterventions)
      if (i.component == name) s.interventions.push_back(stamped(i.intervention));
  }
  // Stage parameters addressed to a stage that is not in the plan are a usage error (a typo
  // in a component name must not silently do nothing).
  for (const RunRequest::StageParam& p : request.stageParams) {
    bool found = false;
    for (const carrier::Step& s : c.process) found = found || s.component == p.component;
    // --holdout is an option of every fit: enough that one of them is planned.
    if (!found && p.name == "holdout" &&
        (p.component == stages::LearnedFitStage::kComponent || p.component == stages::RtiFitStage::kComponent))
      for (const carrier::Step& s : c.process)
        found = found || s.component == stages::LearnedFitStage::kComponent || s.component == stages::RtiFitStage::kComponent;
    if (!found && p.component == stages::LearnedFitStage::kComponent)
      throw Error(ErrorKind::Usage, "--" + p.name, "options",
                  "applies to the learned bases only: add --basis bln or --basis rbf");
    if (!found)
      throw Error(ErrorKind::Usage, p.name, "options",
                  "is an option of " + p.component + ", which this run does not include");
  }
  return c;
}

namespace {


// The number of steps a lights-only run executes: up to the last step of light estimation.
std::size_t lightStepCount(const carrier::Carrier& c) {
  std::size_t count = 0;
  for (std::size_t n = 0; n < c.process.size(); ++n)
    if (inSlot(c.process[n].component, pipeline::PlanSlot::LightsFromSpheres) ||
        inSlot(c.process[n].component, pipeline::PlanSlot::LightsFromFile))
      count = n + 1;
  return count ? count : c.process.size();
}

// `--accept-changed PATH`: the intervention names exactly what the file is now (its SHA-256, or
// "removed"), so it accepts this change and no later one.
void addAcceptedChanges(const fs::path& capture, const RunRequest& request, const carrier::Carrier* previous,
                        RunRequest& merged, std::vector<std::string>& changes) {
  for (const AcceptedChange& a : request.acceptedChanges) {
    const carrier::FileRecord* before = previous ? previous->findFileByPath(a.path) : nullptr;
    if (!before || !carrier::isEvidenceRole(before->role))
      throw Error(ErrorKind::Usage, "--accept-changed " + a.path, "command line",
                  "the carrier records no original, export, sidecar, dome .lp or prior work at that path; give "
                  "the path as the carrier has it (e.g. original-captures/IMG_0005.dng)");
    const fs::path file = capture / fs::u8path(a.path);
    const std::string now = fs::is_regular_file(file) ? "sha256:" + digestFile(file).sha256 : "removed";
    merged.stageInterventions.push_back(
        {stages::IngestStage::kComponent, {"accept-changed-original", a.path, now, "", "", a.reason}});
    changes.push_back("accepted the change of " + a.path + " (now " + now + "): " + a.reason);
  }
}

// `--accept-damaged IMAGE`: the file of the capture the run decodes for that name (a path or
// file name; a shot name means the file the image source selects), recorded with its bytes
// (SHA-256), so the acceptance holds for this damage and no later change of the file.
void addAcceptedDamage(const fs::path& capture, const capture::CaptureLayout& layout, const RunRequest& request,
                       RunRequest& merged, std::vector<std::string>& changes) {
  for (const AcceptedDamage& a : request.acceptedDamage) {
    std::optional<std::string> path;
    for (const capture::Shot& shot : layout.shots)
      for (const std::optional<capture::ImageFile>& f : {shot.original, shot.exported})
        if (f && (f->relativePath == a.image || fs::path(f->relativePath).filename().string() == a.image)) path = f->relativePath;
    if (!path) {
      if (const auto stem = capture::findShotStem(layout, a.image)) {
        const std::vector<capture::ImageFile> chosen =
            capture::selectImages(layout, capture::parseSource(merged.source.empty() ? "auto" : merged.source));
        for (const capture::ImageFile& f : chosen)
          if (fs::path(f.relativePath).stem().string() == *stem) path = f.relativePath;
      }
    }
    if (!path)
      throw Error(ErrorKind::Usage, "--accept-damaged " + a.image, "command line",
                  "no image of the capture has that name; give the file as it is in original-captures/ "
                  "or jpeg-exports/ (e.g. jpeg-exports/IMG_0003.jpg), or the shot's name");
    const std::string bytes = "sha256:" + digestFile(capture / fs::u8path(*path)).sha256;
    auto& list = merged.stageInterventions;
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const RunRequest::StageIntervention& i) {
                                return i.component == stages::DecodeStage::kComponent && i.intervention.kind == stages::kAcceptDecoderWarning &&
                                       i.intervention.target == *path;
                              }),
               list.end());
    list.push_back({stages::DecodeStage::kComponent, {stages::kAcceptDecoderWarning, *path, bytes, "", "", a.reason}});
    changes.push_back("accepted the damage its decoder reports in " + *path + " (" + bytes + "): " + a.reason);
  }
}

// A learned basis (fit/learned.h) needs 4 photographs (and fits as many planes as they hold,
// fit::learnedPlanesFor): checked before any processing.
void checkLearnedPhotographs(const std::string& basis, const RunRequest& request, const RunRequest& given,
                             int photographs) {
  pipeline::Parameters params;
  for (const RunRequest::StageParam& p : request.stageParams)
    if (p.component == stages::LearnedFitStage::kComponent) params.emplace_back(p.name, p.value);
  const stages::LearnedFitOptions options = stages::LearnedFitOptions::fromParameters(params);
  const std::string which = given.bases ? "--basis " + basis : "--basis " + basis + " (standing from an earlier run)";
  if (photographs < 4)
    throw Error(ErrorKind::Usage, which, "command line",
                "a learned basis needs at least 4 photographs; the capture has " + std::to_string(photographs) +
                    ". Include more photographs, or fit --basis hsh2");
  // --holdout K fits again on N - K photographs, with as many planes as they hold
  // (fit::learnedPlanesFor): at least 4 of them must remain.
  if (options.holdout > 0) stages::checkHoldoutCount(options.holdout, photographs);
}

// Every basis to fit needs at least as many photographs as it has coefficients: checked before
// any processing, naming the option, since the basis choice stands for later runs. The message
// names the bases as they came (this command's --basis, an earlier run's, or the default) and
// suggests only bases that fit and are not the one refused.
void checkEnoughPhotographs(const capture::CaptureLayout& layout, const RunRequest& request, const RunRequest& given) {
  if (request.lightsOnly) return;
  std::set<std::string> excluded;
  for (const Exclusion& e : request.exclusions)
    if (const auto stem = capture::findShotStem(layout, e.image)) excluded.insert(*stem);
  const int photographs = static_cast<int>(layout.shots.size() - excluded.size());
  const std::vector<std::string> defaults{"ptm-lrgb", "hsh2"};
  const std::vector<std::string> bases = request.bases.value_or(defaults);
  for (const std::string& basis : bases) {
    if (fit::isLearnedBasisName(basis)) {
      checkLearnedPhotographs(basis, request, given, photographs);
      continue;
    }
    const int terms = fit::basisTerms(fit::parseBasis(basis));
    if (photographs >= terms) {
      // --holdout K fits again on N - K photographs: they must still determine every term.
      int holdout = 0;
      for (const RunRequest::StageParam& p : request.stageParams)
        if (p.component == stages::RtiFitStage::kComponent && p.name == "holdout") holdout = std::atoi(p.value.c_str());
      if (holdout > 0 && photographs - holdout < terms)
        throw Error(ErrorKind::Usage, "--holdout " + std::to_string(holdout), "command line",
                    basis + " fits " + std::to_string(terms) + " coefficients per pixel, and the fit without them has " +
                        std::to_string(photographs - holdout) + " photographs: leave out at most " +
                        std::to_string(photographs - terms));
      continue;
    }
    // The bases in use that fit; else the largest that fits (the first of equals in the
    // order of --basis's help).
    std::vector<std::string> fitting;
    for (const std::string& b : bases)
      if (!fit::isLearnedBasisName(b) && fit::basisTerms(fit::parseBasis(b)) <= photographs) fitting.push_back(b);
    if (fitting.empty()) {
      int most = 0;
      for (fit::Basis b : {fit::Basis::PtmLrgb, fit::Basis::PtmRgb, fit::Basis::Hsh2, fit::Basis::Hsh3})
        if (fit::basisTerms(b) <= photographs && fit::basisTerms(b) > most) {
          most = fit::basisTerms(b);
          fitting = {fit::basisName(b)};
        }
    }
    std::string option;
    for (const std::string& b : fitting) option += " --basis " + b;
    const std::string fix = fitting.empty()
                                ? ". No basis fits fewer than " + std::to_string(fit::basisTerms(fit::Basis::Hsh2)) +
                                      " photographs (hsh2 needs " + std::to_string(fit::basisTerms(fit::Basis::Hsh2)) +
                                      "): include more photographs, or estimate the lights only (surrogate lights)"
                                : ". Fit only what the photographs allow (" + option.substr(1) +
                                      ") or include more photographs";
    const std::string which = given.bases        ? "--basis " + basis
                              : bases != defaults ? "--basis " + basis + " (standing from an earlier run)"
                                                  : "the default basis " + basis + " (no --basis given)";
    throw Error(ErrorKind::Usage, which, "command line",
                "fits " + std::to_string(terms) + " coefficients per pixel and needs at least " +
                    std::to_string(terms) + " photographs; the capture has " + std::to_string(photographs) +
                    (excluded.empty() ? "" : " once " + std::to_string(excluded.size()) + " excluded") + fix);
  }
}

// The plan, with an Audit step when the capture holds prior work of kind lp or rti (judged
// with the outputs of the plan itself, so that a leftover of Surrogate's is not taken for it).
// Without prior work, an Audit threshold standing from an earlier run has no step to go to.
carrier::Carrier planRunWithAudit(const fs::path& capture, const carrier::Carrier* previous, RunRequest& merged) {
  merged.auditPriorWork = true;
  const carrier::Carrier withAudit = planRun(capture, merged);
  if (!stages::priorWorkToAudit(capture, previous, stages::plannedOutputs(withAudit)).empty()) return withAudit;
  merged.auditPriorWork = false;
  auto& params = merged.stageParams;
  params.erase(std::remove_if(params.begin(), params.end(),
                              [](const RunRequest::StageParam& p) { return p.component == stages::AuditStage::kComponent; }),
               params.end());
  return planRun(capture, merged);
}

}  // namespace

carrier::Carrier runCapture(const fs::path& captureArg, const RunRequest& request,
                            const pipeline::RunSettings& settings, bool takeLock) {
  stages::registerBuiltinStages();
  if (!fs::is_directory(captureArg))
    throwInputError(captureArg.string(), "plan", fs::exists(captureArg) ? "is not a folder; give the capture folder"
                                                                        : "the capture folder does not exist");
  const fs::path capture = fs::absolute(captureArg).lexically_normal();
  // Refuse a folder that is no capture before writing anything into it.
  capture::CaptureLayout layout = capture::scanCapture(capture, settings.threads);
  std::optional<capture::CaptureLock> lock;
  if (takeLock) lock.emplace(capture, request.command);
  const std::optional<std::string> interrupted = recoverRun(capture);

  std::optional<carrier::Carrier> previous;
  if (fs::exists(capture / capture::kCarrierPath)) {
    try {
      previous = carrier::loadCarrier(capture / capture::kCarrierPath);
    } catch (const Error& e) {
      throw Error(ErrorKind::Input, (capture / capture::kCarrierPath).string(), "plan",
                  "the capture's carrier cannot be read (" + e.message() + "); it is the "
                  "capture's memory, so Surrogate will not start a new one over it: restore it "
                  "from a backup or package, or move it out of the capture to start afresh");
    }
  }
  std::vector<std::string> changes;
  if (interrupted) changes.push_back(*interrupted);
  RunRequest merged = applyDecisions(previous ? standingDecisions(*previous) : RunRequest{}, request, changes);
  addAcceptedChanges(capture, request, previous ? &*previous : nullptr, merged, changes);
  if (merged.lp && !merged.lp->empty()) layout = capture::scanCapture(capture, settings.threads, *merged.lp);
  addAcceptedDamage(capture, layout, request, merged, changes);
  const auto [width, height] = layout.frameSize();
  checkRequestAgainstFrame(merged, width, height);
  checkRequestNames(request, layout);
  checkEnoughPhotographs(layout, merged, request);

  carrier::Carrier c = planRunWithAudit(capture, previous ? &*previous : nullptr, merged);
  // Before anything runs: never a plan that writes over a file another tool made. The files
  // are listed again: recoverRun may have just finished an interrupted commit.
  const std::vector<std::string> outputFolderFiles = capture::listOutputFolderFiles(capture);
  stages::refuseOutputsOverPriorWork(outputFolderFiles, previous ? &*previous : nullptr, stages::plannedOutputs(c));
  pipeline::RunSettings s = settings;
  if (s.who.empty()) s.who = request.who.empty() ? defaultWho() : request.who;
  carrier::RunRecord record{"r" + std::to_string((previous ? previous->header.runs.size() : 0) + 1),
                            request.command, s.who, carrier::timestampNow(), "", "",
                            request.arguments, changes};
  // A title, creator, rights, licence or --meta change alone, on a complete record whose files
  // are as recorded: no step runs again (run/descriptive_run.h).
  if (previous && !request.lightsOnly && !request.audited &&
      onlyDescriptiveChange(capture, layout, outputFolderFiles, *previous, c, s.threads))
    return commitDescriptiveRun(capture, *previous, c, record);
  if (previous) {
    c.header.created = previous->header.created;
    c.header.runs = previous->header.runs;
  }
  for (const Withdrawal& w : merged.withdrawals)
    c.addLog("intervention", "s1", "withdrew " + w.kind + " " + w.target + ": " + w.reason, s.who);
  if (merged.resetReason) c.addLog("intervention", "s1", "reset every processing decision: " + *merged.resetReason, s.who);

  const fs::path staging = stagingRoot(capture);
  fs::remove_all(staging);
  fs::create_directories(staging / capture::kAssemblyDir);
  fs::create_directories(staging / capture::kFinishedDir);
  pipeline::Context ctx(capture, c, s);
  ctx.outputRoot = staging;
  ctx.previous = previous ? &*previous : nullptr;
  // The ingest takes the capture as scanned above rather than reading it all again, unless the
  // output folders changed since (recoverRun finished a commit): then it scans.
  if (outputFolderFiles == layout.outputFolderFiles)
    ctx.put(stages::kScannedCapture, std::make_shared<const stages::ScannedCapture>(
                                         stages::ScannedCapture{std::move(layout), merged.lp.value_or("")}));
  const std::size_t steps = request.lightsOnly ? lightStepCount(c) : c.process.size();
  const fs::path stagedCarrier = staging / capture::kCarrierPath;
  // The plan as made, for a failure's record: its decisions stand though its results are dropped.
  const std::vector<carrier::Step> planned = c.process;
  try {
    // Saved once after the last step, below, with the run's record; by the runner only when a
    // step fails.
    pipeline::runProcess(ctx, stagedCarrier, steps, pipeline::Saves::FailureOnly);
  } catch (const Error& e) {
    record.ended = carrier::timestampNow();
    record.outcome = "failed";
    record.notes.push_back("failed: " + e.text());
    if (previous) {
      // The last state stays whole (complete or not: a failure must never re-record what the
      // previous carrier holds, such as an original's hash): its carrier only learns that this
      // run failed, and the decisions it stood on (the plan), which the next run starts from
      // (carrier::standingProcess): dropped, they would make a user who follows a refusal's
      // advice one frame at a time go round in circles.
      record.planned = planned;
      previous->header.runs.push_back(record);
      previous->header.modified = carrier::timestampNow();
      carrier::saveCarrier(*previous, capture / capture::kCarrierPath);
      fs::remove_all(staging);
    } else {
      // A first run: its failed record (and what it made) becomes the state, so the capture
      // shows plainly that it is not processed.
      c.header.runs.push_back(record);
      carrier::saveCarrier(c, stagedCarrier);
      commitRun(capture, previous ? &*previous : nullptr, c);
    }
    // A write that failed names the file the user knows (the capture's finished-files/...),
    // not its staged copy in .surrogate/.
    const fs::path failed = fs::path(e.file()).lexically_relative(staging);
    if (!e.file().empty() && !failed.empty() && *failed.begin() != "..")
      throw Error(e.kind(), (capture / failed).string(), e.step(), e.message());
    throw;
  }
  record.ended = carrier::timestampNow();
  record.outcome = "completed";
  if (request.lightsOnly && steps < c.process.size())
    record.notes.push_back("light estimation only: steps " + c.process[steps].id + " to " +
                           c.process.back().id + " are planned with the standing decisions but "
                           "did not run");
  for (const SupersededFile& f : supersededFiles(capture, previous ? &*previous : nullptr, c, record.id))
    record.notes.push_back("moved " + f.path + " (a result of the previous record that this run "
                           "does not produce) to " + f.movedTo);
  c.header.runs.push_back(record);
  c.header.modified = carrier::timestampNow();
  carrier::saveCarrier(c, stagedCarrier);
  commitRun(capture, previous ? &*previous : nullptr, c);
  return c;
}

carrier::Carrier replayCarrier(const fs::path& captureRoot, const carrier::Carrier& recorded,
                               const pipeline::RunSettings& settings, const fs::path& carrierPath) {
  stages::registerBuiltinStages();
  carrier::Carrier c;
  c.header = recorded.header;
  c.header.machine = carrier::currentMachine();
  c.header.modified = carrier::timestampNow();
  c.header.software = {{"Surrogate", surrogateVersion(), "pipeline"}};
  for (const carrier::Software& s : softwareVersions()) c.header.software.push_back(s);
  c.process = recorded.process;
  for (const carrier::Step& s : c.process) {
    auto stage = pipeline::StageRegistry::instance().create(s.component);
    if (!pipeline::StageRegistry::instance().runsAsRecorded(s.component, s.version))
      carrier::addWarning(c, s.id,
                          {s.component + " is another version here than the one the record was made with",
                           carrier::Usable::WithCare, "its results may differ a little from the recorded ones",
                           "compare them with surrogate verify --reexecute, which names every difference",
                           "version " + stage->version() + " here; the carrier records version " + s.version});
  }
  fs::create_directories(captureRoot / capture::kAssemblyDir);
  fs::create_directories(captureRoot / capture::kFinishedDir);
  pipeline::Context ctx(fs::absolute(captureRoot).lexically_normal(), c, settings);
  pipeline::runProcess(ctx, carrierPath);
  return c;
}

}  // namespace surrogate::run
