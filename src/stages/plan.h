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
#include <string>
#include <utility>
#include <vector>

#include "carrier/carrier.h"
#include "pipeline/context.h"

namespace surrogate::stages {

struct Exclusion {
  std::string image;   // shot name, file name or path
  std::string reason;  // mandatory
};

// A step to plan: its component and the parameters that differ from the stage's defaults.
struct PlannedStage {
  std::string component;
  std::vector<std::pair<std::string, std::string>> params;
};

struct RunRequest {
  // Header.
  std::string title;
  std::vector<carrier::Creator> creators;
  std::vector<std::pair<std::string, std::string>> meta;
  std::string who;  // the person running Surrogate (interventions); default: $USER

  // CaptureIngest.
  std::string source = "auto";  // auto, original, export
  std::vector<Exclusion> exclusions;

  // ImageDecode: LibRaw settings as name=value pairs (see image::RawDecodeSettings); empty
  // means the defaults.
  std::vector<std::pair<std::string, std::string>> decodeSettings;

  // Stage parameters given on the command line, by stage component: {component, name, value}.
  struct StageParam {
    std::string component, name, value;
  };
  std::vector<StageParam> stageParams;
  // Interventions given on the command line for later stages (manual spheres, highlights).
  struct StageIntervention {
    std::string component;
    carrier::Intervention intervention;
  };
  std::vector<StageIntervention> stageInterventions;

  // Pre-processing of the images the fit reads (WhiteBalance, Crop, Resize with their
  // full parameters, see stages/preprocess.h), planned in the order given after light
  // estimation and before fitting (`surrogate run` gives WhiteBalance, Crop, Resize). Empty:
  // the fit reads the decoded images as they are.
  std::vector<PlannedStage> preprocessing;

  // Models to fit (RtiFit steps, in order): ptm-lrgb, ptm-rgb, hsh2, hsh3.
  std::vector<std::string> bases = {"ptm-lrgb", "hsh2"};
  // Stop after light estimation (surrogate lights): no fitting, no derived maps.
  bool lightsOnly = false;
};

// Registers every stage this build of Surrogate has with the pipeline's registry (once).
void registerBuiltinStages();

// The stages after ImageDecode for a capture (with or without a .lp file) and a request.
std::vector<PlannedStage> analysisStages(bool captureHasLp, const RunRequest& request);

// Builds a new carrier whose process list is what `request` asks for.
carrier::Carrier planRun(const std::filesystem::path& capture, const RunRequest& request);

// Plans and runs; the carrier is saved to CAPTURE/assembly-files/carrier.xml after each step.
carrier::Carrier runCapture(const std::filesystem::path& capture, const RunRequest& request,
                            const pipeline::RunSettings& settings);

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

}  // namespace surrogate::stages
