// Auditing an RTI that another tool made (RTIBuilder, relight-cli, a dome's software): how far
// its light file is from Surrogate's lights, how well its model reproduces the photographs
// beside Surrogate's own fit of the same basis, and a plain-language verdict
// (docs/hrti-math.md, "Auditing a prior RTI", defines every figure).
//
//   audit::AuditInputs in;
//   in.priorLightFiles = {"cap/assembly-files/stela.lp"};
//   in.priorModels = {"cap/finished-files/stela.ptm"};
//   in.photographs = {stacks.rgb.get(), files};        // as Surrogate fits them
//   in.surrogateLights = lightsPerPhotograph;           // spheres, or assembly-files/lights.lp
//   audit::AuditReport report = audit::runAudit(in, {});
//   for (const std::string& line : audit::auditLines(report)) std::cout << line << "\n";
//
// Nothing here writes into the capture except the difference image, when asked for, at the
// path the caller chose. Figures do not depend on the thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/json.h"
#include "core/stack.h"
#include "formats/lp.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::audit {

using Light = std::array<double, 3>;  // x right, y up, z towards the camera (docs/formats.md)

struct AuditOptions {
  // Images whose two light directions differ by more than this and by more than their combined
  // uncertainty are named (ImageAngle::differs). 2 degrees is about what sphere-based estimates
  // of one light agree to between tools; a wrong light in an .lp (a swapped line, a sign error)
  // is off by far more.
  double angleThresholdDegrees = 2.0;
  // The prior counts as reproduced when its PSNR is at most this far below Surrogate's fit of
  // the same basis with the prior's own lights: quantisation and fitting details differ by
  // tenths of a dB between tools, a wrong light or a clipped coefficient costs several dB.
  double reproducedDb = 1.0;
  // The difference images of each model, written when not empty: "<folder>/<model stem>-difference.png"
  // at the worst image (differencePicture, docs/hrti-math.md "Difference image").
  std::filesystem::path differenceFolder;
  enum class DifferenceAgainst { Photograph, SurrogateFit };
  DifferenceAgainst differenceAgainst = DifferenceAgainst::Photograph;
  // The photograph (stack index) whose prior light the first difference is rendered at; -1 =
  // the worst image, where the prior's PSNR against its photograph is lowest (the first in
  // stack order among equals).
  int differenceImage = -1;
  // Photographs (stack indices) at which a difference image is made besides the first, each
  // "<folder>/<model stem>-difference-<photograph stem>.png"; Error(Usage) for one without a
  // prior light.
  std::vector<int> differenceAt;
  // Against SurrogateFit only: render both models at this light instead of a photograph's.
  std::optional<Light> differenceLight;
  int threads = 0;  // 0 = all cores; the figures are identical at any count
  std::size_t memoryBudgetBytes = 2ull << 30;  // for Surrogate's fits (fit::FitOptions) and the prior model
  std::size_t memoryOption = 0;  // the --memory memoryBudgetBytes is a part of (in a run), for messages
};

// The photographs as Surrogate decodes and fits them (stages::decodeImages' rgb stack, or any
// view of it), with each image's file for matching against the prior light file's names.
struct Photographs {
  const ImageStack* stack = nullptr;
  std::vector<std::filesystem::path> files;  // one per stack image, same order
};

// ---- 1. Light comparison -------------------------------------------------------------------

// Which line of a prior light file lights which photograph: formats::matchLpLines by name
// (folders, '\\', case and extension ignored as lpNameRank says), then, for lines still
// unmatched, formats::resolveLpImage against the photographs' paths.
struct PriorLights {
  std::filesystem::path file;
  std::vector<formats::LightEntry> lines;
  std::vector<std::optional<std::size_t>> lineOfImage;  // per photograph
  // Per line, the 95 % bound in degrees the prior states on its light's error; unset (or the
  // vector shorter) where it states none. An .lp states none: the format has no place for it.
  std::vector<std::optional<double>> uncertaintyOfLine;
  std::vector<std::optional<Light>> lightOfImage() const;  // unit vectors, per photograph
  std::optional<double> uncertaintyOfImage(std::size_t image) const;
};
// Reads and matches; Error(Input) naming the file when it cannot be read or the names are
// ambiguous (formats/lp.h).
PriorLights readPriorLights(const std::filesystem::path& lpFile,
                            const std::vector<std::filesystem::path>& images);
PriorLights matchPriorLights(const std::filesystem::path& lpFile,
                             std::vector<formats::LightEntry> lines,
                             const std::vector<std::filesystem::path>& images);

struct ImageAngle {
  std::string image;  // the photograph's file name
  double degrees = 0; // angle between the prior's and Surrogate's unit vectors
  Light prior{};      // the prior's unit vector (for the report's hemisphere plot)
  // The 95 % bounds in degrees on each light's error: Surrogate's as its light item records it
  // (uncertaintyDegrees), the prior's where it states one; unset = none stated, taken as exact.
  std::optional<double> ours, priors;
  // sqrt(ours^2 + priors^2): the distance two estimates of one true light can lie apart.
  double combinedDegrees() const;
  // The light differs only where its distance exceeds both the combined uncertainty and the
  // threshold (docs/hrti-math.md, "Auditing a prior RTI").
  bool differs(double thresholdDegrees) const;
};

// One light judged, in words, naming its distance, the combined uncertainty with its parts and
// the threshold: "Image_05.JPG: 2.3 deg apart; within the combined uncertainty 2.6 deg (ours 2.6,
// the prior states none); threshold 2.0 deg".
std::string lightJudgement(const ImageAngle& angle, double thresholdDegrees);

struct LightComparison {
  std::filesystem::path file;             // the prior light file
  double thresholdDegrees = 0;
  std::vector<ImageAngle> angles;         // photographs with both lights, in stack order
  double medianDegrees = 0, p95Degrees = 0, maxDegrees = 0;  // 0 when `angles` is empty
  // The lights that differ (ImageAngle::differs: beyond both the combined uncertainty and the
  // threshold), in stack order; the name is the carrier's and the JSON's since Audit version 1.
  std::vector<ImageAngle> aboveThreshold;
  std::vector<std::string> onlyInPrior;   // .lp lines naming no photograph (as written)
  std::vector<std::string> onlyInSurrogate;  // photographs the .lp does not name
  // The light of `angles` farthest from Surrogate's (the first in stack order among equals), or
  // null when there is none.
  const ImageAngle* largest() const;
};

// `surrogateLights`: one per photograph (the stack order of `prior.lineOfImage`);
// `surrogateUncertainty`: the 95 % bound of each, in degrees (unset, or the vector shorter:
// none recorded).
LightComparison compareLights(const PriorLights& prior, const std::vector<std::string>& imageNames,
                              const std::vector<Light>& surrogateLights, double thresholdDegrees,
                              const std::vector<std::optional<double>>& surrogateUncertainty = {});

// ---- 2. Model check -------------------------------------------------------------------------

struct SizeRelation {
  enum class Kind { Same, UniformScale, Different };
  Kind kind = Kind::Same;
  int modelWidth = 0, modelHeight = 0, photoWidth = 0, photoHeight = 0;
  double scale = 1;  // photograph side / model side, for UniformScale
  std::string describe() const;
};
// Same size; or one factor for both sides, each side within one pixel of the photograph's side
// divided by it (a resized export); else Different (another crop: not compared).
SizeRelation relateSizes(int modelWidth, int modelHeight, int photoWidth, int photoHeight);

struct ImageError {
  std::string image;
  double rmse = 0;  // 0..255 units of Rec. 709 luminance
  double psnr = 0;  // 20 log10(255 / rmse), capped at 100 dB
  std::optional<Light> light;  // the light it was rendered at (recorded for the prior's errors)
};

// A model's error against the photographs, each rendered at its own light.
struct ModelErrors {
  bool computed = false;
  std::string note;                 // why not computed
  std::vector<ImageError> images;   // stack order
  double rmse = 0, psnr = 0;        // over every pixel of every image
  double medianPsnr = 0, worstPsnr = 0;
  std::string worstImage;
};

// A consistent tone difference between the model's rendering r and the photographs p, fitted
// as p = 255 g (r / 255)^gamma on mid-tones; `explains` when correcting it removes most of
// the error (another white balance, gamma or exposure in the prior's processing).
struct ColourRelation {
  bool measured = false;
  double gain = 1, gamma = 1;
  double rmseBefore = 0, rmseAfter = 0;  // on the sampled mid-tone pixels
  bool differs = false;
};

// Clipping in a model's quantised coefficients (docs/formats.md, "Quantisation"; the rule in
// docs/hrti-math.md, "Auditing a prior RTI"). Clipping piles texels up at byte 0 or 255: a spike.
struct PlaneCheck {
  std::string plane;        // "a3", "red a3" (PTM RGB), "term 2" (HSH)
  double atZero = 0, atFull = 0;  // share of texels in a spike at byte 0 / 255 not decoding to 0
  double outsideRange = 0;  // share of texels in a spike whose refitted value lies beyond the
                            // range the scale and bias can hold
  bool clamped = false;     // one of the three shares is 1% or more
};
struct QuantisationCheck {
  bool clamped = false;
  std::vector<PlaneCheck> planes;  // every plane, flagged or not
};
QuantisationCheck checkQuantisation(const formats::PtmFile& prior, const formats::PtmFile* refit);
QuantisationCheck checkQuantisation(const formats::HshFile& prior, const formats::HshFile* refit);

// One difference image of a model (differencePicture): where it is, at which photograph and
// light, and the full scale of its colours.
struct DifferenceImage {
  std::filesystem::path file;
  std::string image;      // the photograph's file name; empty at a light chosen without one
  std::optional<Light> light;  // the light both sides are at (absent in results before Audit 5)
  double fullScale = 0;   // luminance levels at the ends of the colour scale (0: before Audit 5,
                          // a mid-grey picture of 128 + difference)
  bool worst = false;     // made at the worst image (the first of ModelCheck::differences)
  std::string description;  // "prior model minus the photograph IMG_3.jpg at its prior light ..."
};

struct ModelCheck {
  std::filesystem::path file;
  std::filesystem::path lightFile;   // whose lights the prior was rendered at
  std::string basis;                 // "ptm-lrgb", "ptm-rgb", "hsh2", "hsh3", "hsh4"
  std::string values;                // what the photographs' values are: "sRGB-encoded" or "linear"
  SizeRelation size;
  ModelErrors prior;                 // the prior model at the prior lights
  ModelErrors refitPriorLights;      // Surrogate's fit of the same basis, prior lights
  ModelErrors refitSurrogateLights;  // Surrogate's fit of the same basis, Surrogate's lights
  ColourRelation colour;
  QuantisationCheck quantisation;
  std::vector<DifferenceImage> differences;  // when written: the worst image's, then the named ones
};

// `priorLights` and `surrogateLights` (empty when Surrogate has none) are per photograph.
// Error(Input) when the model cannot be read; a size that does not match is reported, not
// thrown.
ModelCheck checkModel(const std::filesystem::path& model, const Photographs& photographs,
                      const PriorLights& priorLights, const std::vector<Light>& surrogateLights,
                      const AuditOptions& options);

// ---- The difference picture (docs/hrti-math.md, "Difference image") ----------------------

// The smallest full scale (8-bit levels of luminance) a difference picture is drawn at: below
// it, 8-bit rounding of the render and the photograph's own noise would fill the scale.
inline constexpr double kMinDifferenceScale = 4;

// The colour of a luminance difference of `levels` (prior minus photograph) on a diverging scale
// whose ends are -fullScale and +fullScale: ColorBrewer's RdBu (11 classes, which stays legible
// to red-green colour-blind viewers), blue where the prior is darker, near-white (247, 247, 247)
// at 0, red where it is brighter; linear between the 11 stops, clamped beyond the ends. RGB.
std::array<std::uint8_t, 3> differenceColour(double levels, double fullScale);

// The full scale for these differences (16-bit units: levels * 257): the 99th percentile of
// their magnitudes (nearest rank), in levels, rounded up to the next of 4, 5, 6, 8, 10, 12, 16,
// 20, 25, 32, 40, 50, 64, 80, 100, 128, 160, 200, 255.
double differenceScale(const std::vector<std::int32_t>& differences);

struct DifferencePicture {
  Image picture;          // 8-bit RGB: the map at the top left, the legend band below
  double fullScale = 0;   // the scale's ends in levels (differenceScale)
};
// The signed difference of the Rec. 709 luminance of `prior` minus that of `photograph` (RGB or
// grey, 16-bit units; the same size), per pixel, in false colour (differenceColour at
// differenceScale), with the legend drawn below it: the colour ramp, its ends and middle in
// 8-bit levels, and `caption` (one line: what is shown). The picture is at least 560 pixels wide
// so that the legend fits; right of a narrower map is mid-grey. The same bytes at any thread
// count. Error(Internal) for images of different sizes.
DifferencePicture differencePicture(const Image& prior, const Image& photograph, const std::string& caption);

// ---- 3. Verdict -----------------------------------------------------------------------------

struct Finding {
  enum class Cause { DifferentLights, MissingImages, DifferentSize, ColourHandling, BrokenBias,
                     FitShortfall };
  Cause cause;
  std::string text;
};
const char* causeName(Finding::Cause cause);  // "different-lights", ...

struct Verdict {
  std::filesystem::path model;      // empty for a light file audited alone
  std::filesystem::path lightFile;
  bool reproduced = false;
  double dbBelowRefit = 0;  // Surrogate's PSNR with the prior's lights minus the prior's
  double maxDegrees = 0;    // the light comparison's max (0 without one)
  std::vector<Finding> findings;
  std::string sentence;
};
// Either argument may be null (a light file alone, or a model in a capture without Surrogate
// lights).
Verdict diagnose(const LightComparison* lights, const ModelCheck* model, const AuditOptions& options);

// ---- 4. The whole audit and its output ------------------------------------------------------

struct AuditInputs {
  std::vector<std::filesystem::path> priorLightFiles;  // .lp
  std::vector<std::filesystem::path> priorModels;      // .ptm / .rti
  Photographs photographs;
  std::vector<Light> surrogateLights;  // per photograph; empty when there are none
  // Per photograph, the 95 % bound in degrees on Surrogate's light (its carrier item's
  // uncertaintyDegrees); unset, or empty, where none is recorded: the light is then taken as exact.
  std::vector<std::optional<double>> surrogateUncertainty;
};

struct AuditReport {
  double thresholdDegrees = 0;
  double reproducedDb = 1.0;  // AuditOptions::reproducedDb the verdicts were made with
  // Prior files left out because they cannot be read as what their name says (filled by the
  // caller that leaves them out: stages::AuditStage), with the reader's words.
  struct NotAudited {
    std::filesystem::path file;
    std::string reason;
  };
  std::vector<NotAudited> notAudited;
  std::vector<LightComparison> lights;
  std::vector<ModelCheck> models;
  std::vector<Verdict> verdicts;  // one per model, then one per light file no model used
  // The prior tool's processing logs (audit/rtibuilder_log.h): what each records of the
  // processing, one line a fact, and where it disagrees with the capture audited. Filled by the
  // caller (stages::AuditStage), which knows the capture; they inform, they do not decide the
  // verdicts.
  struct PriorLog {
    std::filesystem::path file;
    std::vector<std::string> records;
    std::vector<std::string> discrepancies;
  };
  std::vector<PriorLog> logs;
};

// Each model is rendered at the lights of the light file with the same stem, else of the one
// naming most photographs; a model without any is reported as not compared. Error(Input) when a
// prior file cannot be read.
AuditReport runAudit(const AuditInputs& inputs, const AuditOptions& options);

// ---- 5. The verdict in parts ----------------------------------------------------------------

// What an auditor asks of a prior RTI, one question at a time: are its lights Surrogate's, does
// its model fit the photographs as well as a refit does, were the photographs processed alike,
// is the file sound. Each part says reproduced, differs or cannot tell, with its figure and,
// when it differs, the likely cause, one line each. A part says "differs" only for what denies
// the reproduction (the Verdict's blocking findings); what does not (a resized model, images
// one side lacks) is said in its figure.
struct VerdictPart {
  enum class State { Reproduced, Differs, CannotTell };
  std::string name;  // "lights", "model", "tone", "integrity"
  State state = State::CannotTell;
  std::string figure;
  std::string cause;  // when it differs
};
const char* stateName(VerdictPart::State state);  // "reproduced", "differs", "cannot tell"

struct VerdictSummary {
  std::string subject;  // "finished-files/stela.ptm with the lights of assembly-files/stela.lp"
  bool reproduced = false;
  double thresholdDegrees = 0;  // the audit's (AuditReport::thresholdDegrees), shown on its line
  std::vector<VerdictPart> parts;  // lights, model, tone, integrity
};
// One summary per verdict of `report`, in its order.
std::vector<VerdictSummary> summarise(const AuditReport& report);
// Whether every verdict says reproduced and every prior file was audited.
bool auditReproduced(const AuditReport& report);
// The exit code of `surrogate audit` for `report`: 1 (Error(Input)'s) when a prior file was left
// out because it cannot be read, whatever the verdicts say (they were judged without it: a
// model whose .lp is unreadable is compared with no lights); else 4 when a verdict says not
// reproduced; 0 when every one says reproduced; 1 when there is none.
int auditExitCode(const AuditReport& report);

// The summaries for the terminal: per verdict, a line with its subject and REPRODUCED, NOT
// REPRODUCED or (neither its lights nor its model compared) CANNOT TELL, then one line per part.
std::vector<std::string> summaryLines(const std::vector<VerdictSummary>& summaries);
void writeSummaryJson(JsonWriter& json, const std::vector<VerdictSummary>& summaries);
// One line per prior processing log: what made it, and whether it agrees with the capture.
std::vector<std::string> logSummaryLines(const AuditReport& report);

// Numbers rounded for display: angles to 0.1 degree, dB to 0.01, RMSE to 0.01.
void writeAuditJson(JsonWriter& json, const AuditReport& report);
std::string auditJson(const AuditReport& report);
std::vector<std::string> auditLines(const AuditReport& report);

}  // namespace surrogate::audit
