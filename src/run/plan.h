// From what the user asked to a carrier's process list, and running it.
//
// `surrogate run` does not hard-code a sequence of calls: it writes the steps it will run,
// with all their parameters and the user's interventions, into a new carrier, then executes
// that list. Re-execution (the verifier) executes the same list from the recorded carrier.
//
//   RunRequest request;
//   request.title = "Stela 12";
//   request.exclusions.push_back({"IMG_0007", "the flash did not fire"});
//   carrier::Carrier c = runCapture("/data/stela12", request, settings);
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "carrier/carrier.h"
#include "pipeline/context.h"

namespace surrogate::run {

struct Exclusion {
  std::string image;   // shot name, file name or path
  std::string reason;  // mandatory
  std::string who, time;  // set when the decision was recorded (empty: now, by the operator)
};

// A standing decision withdrawn on purpose (`--forget-exclusion`, `--forget-sphere`,
// `--forget-highlight`): recorded with its reason like the decision itself.
struct Withdrawal {
  std::string kind;    // exclude-image, manual-sphere, manual-highlight, accept-decoder-warning
  std::string target;  // shot, sphere index, "IMAGE:SPHERE", image (shot, file name or path)
  std::string reason;
};

// An original whose bytes changed (or that was removed) since it was recorded, accepted on
// purpose (`--accept-changed`): without one, the run stops with a fixity failure.
struct AcceptedChange {
  std::string path;  // relative to the capture, as the carrier records it
  std::string reason;
};

// An image whose decoder reports damaged data, accepted on purpose (`--accept-damaged`): without
// one, ImageDecode refuses it. Resolved by runCapture to the file the run decodes and recorded
// as an `accept-decoder-warning` intervention on ImageDecode that names its bytes (SHA-256).
struct AcceptedDamage {
  std::string image;   // shot name, file name or path relative to the capture
  std::string reason;  // mandatory
};

// A step to plan: its component and the parameters that differ from the stage's defaults.
struct PlannedStage {
  std::string component;
  std::vector<std::pair<std::string, std::string>> params;
};

// What a command asks for. Every field is a decision that adds to or overrides the decisions
// the capture's carrier already holds (standingDecisions + applyDecisions): an empty field
// leaves the recorded decision as it is.
struct RunRequest {
  // Header.
  std::string title;  // empty: keep
  std::vector<carrier::Creator> creators;  // added (a known name gets the role given)
  std::vector<std::pair<std::string, std::string>> meta;  // set by key
  std::string rights;   // rights statement (--rights); empty: keep
  std::string license;  // licence URI (--license); empty: keep
  std::string who;  // the person running Surrogate (interventions); default: $USER
  // In an audit's work folder: the prior files copied into it (set by `surrogate audit` when it
  // makes the folder; unset: keep).
  std::optional<carrier::AuditedSource> audited;

  // CaptureIngest.
  std::string source;  // auto, original, export; empty: keep (first run: auto)
  std::vector<Exclusion> exclusions;
  std::optional<std::string> lp;  // dome capture: the .lp giving the lights ("" = none)
  std::vector<AcceptedChange> acceptedChanges;

  // ImageDecode: LibRaw settings as name=value pairs (see image::RawDecodeSettings), set by name.
  std::vector<std::pair<std::string, std::string>> decodeSettings;
  std::vector<AcceptedDamage> acceptedDamage;

  // Stage parameters given on the command line, by stage component: {component, name, value}.
  struct StageParam {
    std::string component, name, value;
    std::string reason = {};  // why, when the user gave one (--light-distance ... --reason): the run's note
  };
  std::vector<StageParam> stageParams;
  // Interventions given on the command line for later stages (manual spheres, highlights); one
  // with the same component, kind and target as a recorded one replaces it.
  struct StageIntervention {
    std::string component;
    carrier::Intervention intervention;
  };
  std::vector<StageIntervention> stageInterventions;

  // Pre-processing of the images the fit reads (WhiteBalance, Crop, Resize with their
  // full parameters, see stages/preprocess.h), planned in the order given after light
  // estimation and before fitting; one replaces a recorded step of the same component.
  std::vector<PlannedStage> preprocessing;

  // Models to fit (RtiFit steps, in order): ptm-lrgb, ptm-rgb, hsh2, hsh3. Unset: keep (first
  // run: ptm-lrgb and hsh2).
  std::optional<std::vector<std::string>> bases;
  // The web copy of each model (the Publish slot: WebCopy steps, stages/web_copy_stage.h),
  // with its options as stage parameters of WebCopy. Unset: keep (first run: none); false
  // withdraws it (and its options).
  std::optional<bool> publish;
  // Run only up to light estimation (surrogate lights): the later steps are planned (so no
  // decision about them is lost) but not run.
  bool lightsOnly = false;
  // Whether the capture holds prior work to audit (a prior .lp, .ptm or .rti): plans the
  // PriorWork slot. Not a decision: runCapture sets it from the capture's files.
  bool auditPriorWork = false;

  // Withdrawn decisions, and `--reset`: every processing decision back to the defaults (the
  // header and accepted changes of originals stay).
  std::vector<Withdrawal> withdrawals;
  std::optional<std::string> resetReason;

  // For the run history: the command ("run", "lights", "pack") and its arguments as given.
  std::string command = "run";
  std::vector<std::string> arguments;
};

// The decisions a carrier holds, as the request that would reproduce them: header, source,
// dome .lp, exclusions and interventions (with their who, time and reason), LibRaw settings,
// stage parameters that differ from the defaults, pre-processing steps and bases.
RunRequest standingDecisions(const carrier::Carrier& recorded);

// `given` applied to `standing`: overrides and additions, withdrawals, reset. `changes` gets
// one sentence per decision changed (for the run history). Throws Error(Usage) for a
// withdrawal that names no standing decision, and for a dome .lp with sphere options.
RunRequest applyDecisions(const RunRequest& standing, const RunRequest& given,
                          std::vector<std::string>& changes);

// The stages after ImageDecode for a capture (with or without a dome .lp) and a request whose
// decisions are complete (applyDecisions): every registered stage in the slot its info() names
// (pipeline::PlanSlot), slot by slot, in registration order within a slot.
std::vector<PlannedStage> analysisStages(bool captureHasLp, const RunRequest& request);

// Builds a new carrier whose process list is what `request` (complete decisions) asks for.
carrier::Carrier planRun(const std::filesystem::path& capture, const RunRequest& request);

// One command's work on a capture, with the capture's memory: takes the capture's lock,
// finishes a commit an earlier process was killed in, starts from the decisions the carrier
// records and applies `request` to them, checks every value against the frame, plans, runs
// into a staging folder, and only when every step succeeded makes the staged results and
// carrier the capture's state (run/run_commit.h); results no longer produced are moved to
// superseded-files/. A failed run leaves the previous state whole and adds itself,
// with its cause, to that carrier's run history. Returns the new carrier. `takeLock` false: the
// caller holds the capture's lock already (pack, which holds it while it packs).
carrier::Carrier runCapture(const std::filesystem::path& capture, const RunRequest& request,
                            const pipeline::RunSettings& settings, bool takeLock = true);

// Re-execution: runs `recorded`'s process list again (same steps, parameters and
// interventions) on the files under `captureRoot` (a capture folder, or a bag's data/ folder),
// writing outputs there. Returns the new carrier: same header and process list, fresh files,
// data and log, with this build's software versions. The carrier is saved to `carrierPath`
// when that is not empty. Steps naming unknown components are an Error(Input).
carrier::Carrier replayCarrier(const std::filesystem::path& captureRoot,
                               const carrier::Carrier& recorded,
                               const pipeline::RunSettings& settings,
                               const std::filesystem::path& carrierPath = {});

// The name, version and role of every library whose behaviour can change results.
std::vector<carrier::Software> softwareVersions();

}  // namespace surrogate::run
