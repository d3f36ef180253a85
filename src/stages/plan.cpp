#include "stages/plan.h"

#include <cstdlib>
#include <mutex>

#include <Eigen/Core>

#include "archive/digest.h"
#include "capture/capture.h"
#include "carrier/xml.h"
#include "core/error.h"
#include "core/text.h"
#include "core/version.h"
#include "image/decode.h"
#include "meta/metadata.h"
#include "pipeline/runner.h"
#include "pipeline/stage.h"
#include "stages/decode_stage.h"
#include "stages/ingest_stage.h"
#include "stages/registry.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

void registerBuiltinStages() {
  static std::once_flag once;
  std::call_once(once, [] {
    auto& r = pipeline::StageRegistry::instance();
    r.add("CaptureIngest", [] { return std::make_unique<IngestStage>(); });
    r.add("ImageDecode", [] { return std::make_unique<DecodeStage>(); });
    registerAnalysisStages(r);
  });
}

std::vector<carrier::Software> softwareVersions() {
  return {
      {"LibRaw", image::librawVersion(), "camera raw decoding"},
      {"OpenCV", image::opencvVersion(), "image decoding and filtering"},
      {"Exiv2", meta::exiv2Version(), "EXIF/XMP metadata"},
      {"libxml2", xml::libxml2Version(), "XML and schema validation"},
      {"OpenSSL", archive::opensslVersion(), "message digests"},
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION),
       "linear algebra"},
  };
}

namespace {
std::string defaultWho() {
  if (const char* user = std::getenv("USER"); user && *user) return user;
  return "unknown";
}
}  // namespace

carrier::Carrier planRun(const fs::path& capture, const RunRequest& request) {
  registerBuiltinStages();
  if (!fs::is_directory(capture))
    throwInputError(capture.string(), "plan", fs::exists(capture) ? "is not a folder; give the capture folder"
                                                                   : "the capture folder does not exist");
  const std::string who = request.who.empty() ? defaultWho() : request.who;
  carrier::Carrier c = carrier::newCarrier(
      request.title.empty() ? fs::absolute(capture).lexically_normal().filename().string()
                            : request.title,
      request.creators);
  c.header.meta = request.meta;
  for (const carrier::Software& s : softwareVersions()) c.header.software.push_back(s);

  carrier::Step& ingest = c.addStep("CaptureIngest", IngestStage().version());
  ingest.description = "Read the capture folder, hash every file, read EXIF/XMP";
  ingest.setParam("source", capture::sourceName(capture::parseSource(request.source)));
  for (const Exclusion& e : request.exclusions) {
    if (e.reason.empty())
      throw Error(ErrorKind::Usage, "--exclude " + e.image, "options",
                  "an excluded image needs a reason: add --reason \"...\" after it");
    ingest.interventions.push_back(
        {"exclude-image", e.image, "", who, carrier::timestampNow(), e.reason});
  }

  carrier::Step& decode = c.addStep("ImageDecode", DecodeStage().version());
  decode.description = "Decode each image once (LibRaw for raw/DNG, OpenCV for exports)";
  image::RawDecodeSettings settings = image::RawDecodeSettings::fromParameters(request.decodeSettings);
  for (const auto& [name, value] : settings.toParameters()) decode.setParam(name, value);

  bool hasLp = false;
  for (const auto& entry : fs::directory_iterator(capture)) {
    if (entry.is_regular_file() && lowerCase(entry.path().extension().string()) == ".lp") hasLp = true;
  }
  auto& registry = pipeline::StageRegistry::instance();
  for (const PlannedStage& planned : analysisStages(hasLp, request)) {
    const std::string& name = planned.component;
    auto stage = registry.create(name);
    carrier::Step& s = c.addStep(name, stage->version());
    s.description = describeStage(name);
    for (const auto& [pname, pvalue] : defaultParameters(name)) s.setParam(pname, pvalue);
    for (const RunRequest::StageParam& p : request.stageParams)
      if (p.component == name) s.setParam(p.name, p.value);
    for (const auto& [pname, pvalue] : planned.params) s.setParam(pname, pvalue);
    for (const RunRequest::StageIntervention& i : request.stageInterventions) {
      if (i.component != name) continue;
      carrier::Intervention in = i.intervention;
      if (in.who.empty()) in.who = who;
      if (in.time.empty()) in.time = carrier::timestampNow();
      s.interventions.push_back(in);
    }
  }
  // Stage parameters addressed to a stage that is not in the plan are a usage error (a typo
  // in a component name must not silently do nothing).
  for (const RunRequest::StageParam& p : request.stageParams) {
    bool found = false;
    for (const carrier::Step& s : c.process) found = found || s.component == p.component;
    if (!found)
      throw Error(ErrorKind::Usage, p.name, "options",
                  "is an option of " + p.component + ", which this run does not include");
  }
  return c;
}

carrier::Carrier runCapture(const fs::path& capture, const RunRequest& request,
                            const pipeline::RunSettings& settings) {
  carrier::Carrier c = planRun(capture, request);
  const fs::path assembly = capture / capture::kAssemblyDir;
  const fs::path finished = capture / capture::kFinishedDir;
  fs::create_directories(assembly);
  fs::create_directories(finished);
  pipeline::RunSettings s = settings;
  if (s.who.empty()) s.who = request.who.empty() ? defaultWho() : request.who;
  pipeline::Context ctx(fs::absolute(capture).lexically_normal(), c, s);
  pipeline::runProcess(ctx, assembly / "carrier.xml");
  return c;
}

carrier::Carrier replayCarrier(const fs::path& captureRoot, const carrier::Carrier& recorded,
                               const pipeline::RunSettings& settings, const fs::path& carrierPath) {
  registerBuiltinStages();
  carrier::Carrier c;
  c.header = recorded.header;
  c.header.machine = carrier::currentMachine();
  c.header.modified = carrier::timestampNow();
  c.header.software = {{"Surrogate", surrogateVersion(), "pipeline"}};
  for (const carrier::Software& s : softwareVersions()) c.header.software.push_back(s);
  c.process = recorded.process;
  for (const carrier::Step& s : c.process) {
    auto stage = pipeline::StageRegistry::instance().create(s.component);
    if (stage->version() != s.version)
      c.addLog("warning", s.id, s.component + " is version " + stage->version() +
                                    " here but the carrier records version " + s.version +
                                    ": its results may differ");
  }
  fs::create_directories(captureRoot / capture::kAssemblyDir);
  fs::create_directories(captureRoot / capture::kFinishedDir);
  pipeline::Context ctx(fs::absolute(captureRoot).lexically_normal(), c, settings);
  pipeline::runProcess(ctx, carrierPath);
  return c;
}

}  // namespace surrogate::stages
