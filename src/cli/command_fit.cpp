// surrogate fit --lp FILE.lp -o OUT.ptm|OUT.rti|DIR [--basis B] [--holdout K]: fit a model from a
// light file and its images, outside any capture folder or carrier (a tool for people who
// already have an .lp from elsewhere, e.g. a dome). The learned bases (rbf, bln) are written as
// the web layout they are read in (a folder); --holdout measures any basis at lights it never saw.
#include <cmath>
#include <iostream>
#include <optional>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/progress.h"
#include "capture/output_rule.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "fit/fit.h"
#include "formats/lp.h"
#include "publish/learned_layout.h"
#include "stages/decode_images.h"
#include "stages/held_out_quality.h"
#include "stages/learned_fit_stage.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// The image an .lp names, by the one rule of formats::resolveLpImage: relative to the .lp's
// folder, then to the folder above it (RTIBuilder's assembly-files/*.lp), then by base name
// beside the .lp and in the capture's jpeg-exports/ and original-captures/.
fs::path resolveImage(const fs::path& lpFile, const std::string& name) {
  if (const auto found = formats::resolveLpImage(lpFile, name)) return *found;
  throwInputError(lpFile.string(), "fit",
                  "names the image \"" + name + "\", which was not found relative to the .lp file's "
                  "folder or the folder above it, nor by its name beside the .lp or in jpeg-exports/ or "
                  "original-captures/ there");
}

// A basis fits at least as many photographs as it has terms: checked before decoding, naming
// the basis as it came (given, or the default for the output's extension) and suggesting only
// a basis that fits, never the one refused.
void checkEnoughLights(fit::Basis basis, bool given, const std::string& ext, const std::string& lp, int lights) {
  const int terms = fit::basisTerms(basis);
  if (lights >= terms) return;
  const std::string name = fit::basisName(basis);
  const int hsh2 = fit::basisTerms(fit::Basis::Hsh2);
  const std::string fix =
      lights < hsh2 ? "no basis fits fewer than " + std::to_string(hsh2) + " photographs (hsh2 needs " +
                          std::to_string(hsh2) + "): add photographs to the .lp"
                  : "fit an .rti with --basis hsh2 (" + std::to_string(hsh2) + " coefficients), or add photographs to the .lp";
  throw Error(ErrorKind::Usage, given ? "--basis " + name : "the default basis " + name + " of a " + ext + " file (no --basis given)",
              "command line",
              "fits " + std::to_string(terms) + " coefficients per pixel and needs at least " + std::to_string(terms) +
                  " photographs; " + lp + " lists " + std::to_string(lights) + ". To fit these: " + fix);
}

}  // namespace

namespace {
// --verbose: what the summary line leaves out.
void printFitDetail(bool learned, const fit::FitStatistics& stats, const fit::LearnedStatistics& learnedStats,
                    const std::optional<stages::HeldOutQuality>& heldOut, const std::vector<std::filesystem::path>& files) {
  if (learned) {
    std::cout << "  explained variance " << fixedDecimals(learnedStats.explainedVariance, 4)
              << ", PSNR leaving each photograph out " << fixedDecimals(learnedStats.leaveOneOutPsnr, 2) << " dB\n";
  } else {
    std::cout << "  regularisation " << stats.regularisation << ", condition number of the lights "
              << (std::isfinite(stats.conditionNumber) ? fixedDecimals(stats.conditionNumber, 1) : std::string("not finite"))
              << ", damped terms " << (stats.dampedTerms.empty() ? std::string("none") : "");
    for (std::size_t i = 0; i < stats.dampedTerms.size(); ++i)
      std::cout << (i ? "," : "") << stats.dampedTerms[i];
    std::cout << "\n";
  }
  if (heldOut)
    for (std::size_t i = 0; i < heldOut->indices.size(); ++i)
      std::cout << "  left out " << files[heldOut->indices[i]].filename().string() << ": PSNR "
                << fixedDecimals(heldOut->perLight[i].psnr, 2) << " dB, SSIM " << fixedDecimals(heldOut->perLight[i].ssim, 3)
                << "\n";
}
}  // namespace

int runCommandFit(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"lp", true, false, "the light file naming the images and their light directions", "FILE.lp", OptionGroup::Input},
      {"basis", true, false, "ptm-lrgb, ptm-rgb (for .ptm), hsh2, hsh3 (for .rti), rbf, bln (learned: a folder)", "BASIS"},
      {"planes", true, false, "rbf, bln: coefficients per pixel, a multiple of 3 (default " + std::to_string(stages::kLearnedPlanes) + ")", "N"},
      {"resolution", true, false, "bln: the side of the grid over the light directions (default " + std::to_string(stages::kLearnedResolution) + ")", "R"},
      {"quality", true, false, "rbf, bln: JPEG quality of the planes, 1..100, or Q:LAST from the first plane to the last (default " +
                                   std::to_string(stages::kLearnedQuality) + ":" + std::to_string(stages::kLearnedLastQuality) + ")", "Q[:LAST]"},
      {"holdout", true, false, "also fit without K photographs and report PSNR/SSIM at their lights", "K"},
      {"threads", true, false, "worker threads (default: all cores)", "N"},
      {"memory", true, false, "memory budget (default 2G)", "SIZE"},
      {"o", true, false, "output: .ptm (PTM), .rti (HSH) or a folder (rbf, bln)", "OUT", OptionGroup::Output},
      {"output", true, false, "same as -o", "OUT", OptionGroup::Output},
      {"quiet", false, false, "no progress bar, and at most one summary line", "", OptionGroup::Output},
      {"verbose", false, false, "also the fit's detail: its conditioning and damped terms, and each photograph "
                                "left out by --holdout", "", OptionGroup::Output},
      {"json", false, false, "print the fit quality as JSON", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  const Verbosity verbosity = verbosityOf(args);
  if (helpShown(args, specs,
                {"surrogate fit --lp FILE.lp -o OUT.ptm|OUT.rti|DIR [--basis BASIS] [--holdout K]",
                 "Fit a PTM or HSH model to the images an .lp file names, with its light directions, "
                 "outside any capture and with no record. (surrogate run does this for a capture, with "
                 "provenance.)",
                 {{"surrogate fit --lp coin/lights.lp -o coin.ptm",
                   "fit a PTM (luminance and colour, as RTIViewer opens it) to the photographs lights.lp names"},
                  {"surrogate fit --lp coin/lights.lp -o coin-bln --basis bln --holdout 6",
                   "a learned bilinear basis as a web layout (OpenLIME, relight), with its quality at 6 lights left out"}},
                 commonExitCodes("the model is written")}))
    return 0;
  const auto lp = args.value("lp");
  const auto out = outputOption(args);
  if (!lp || !out)
    throw Error(ErrorKind::Usage, "", "command line", "give the light file and the output: --lp FILE.lp -o OUT.ptm");
  const std::string ext = lowerCase(fs::path(*out).extension().string());
  const std::string basisName = args.value("basis", ext == ".ptm" ? "ptm-lrgb" : ext == ".rti" ? "hsh2" : "");
  const bool learned = fit::isLearnedBasisName(basisName);
  if (basisName.empty()) {
    checkOutputFile("-o", *out, "model.ptm");  // a package or a bag's file is refused as such first
    throw Error(ErrorKind::Usage, "-o " + *out, "command line",
                "the output must end in .ptm or .rti, or be a folder with --basis rbf or --basis bln");
  }
  for (const char* option : {"planes", "resolution", "quality"})
    if (!learned && args.has(option))
      throw Error(ErrorKind::Usage, std::string("--") + option, "command line",
                  "applies to the learned bases only (--basis rbf or bln)");
  if (learned && (ext == ".ptm" || ext == ".rti"))
    throw Error(ErrorKind::Usage, *out, "command line",
                "basis " + basisName + " is written as a web layout: give a folder for -o (it must not exist or be empty)");
  fit::Basis basis = fit::Basis::PtmLrgb;
  if (!learned) {
    checkOutputFile("-o", *out, ext == ".ptm" ? "model.ptm" : "model.rti");
    if (ext != ".ptm" && ext != ".rti")
      throw Error(ErrorKind::Usage, "-o " + *out, "command line", "the output must end in .ptm or .rti");
    basis = fit::parseBasis(basisName);
    const bool ptm = fit::isPtm(basis);
    if (ptm != (ext == ".ptm"))
      throw Error(ErrorKind::Usage, *out, "command line",
                  std::string("basis ") + fit::basisName(basis) + " is written as " + (ptm ? ".ptm" : ".rti"));
  } else {
    // A new folder, never inside a package, a bag or a capture's own folders (as publish).
    capture::checkOutputTarget(*out, "-o", capture::ExistingOutput::ReplaceOutput);
  }
  if (learned && fs::exists(*out) && (!fs::is_directory(*out) || !fs::is_empty(*out))) {
    throw Error(ErrorKind::Usage, "-o " + *out, "command line",
                "the web layout goes into a new or empty folder; this one exists and is not empty: give another name");
  }
  const int threads = threadsOption(args);

  std::vector<fs::path> files;
  std::vector<std::array<double, 3>> lights;
  for (const formats::LightEntry& e : formats::readLp(*lp)) {
    files.push_back(resolveImage(*lp, e.filename));
    lights.push_back({e.x, e.y, e.z});
  }
  if (!learned) checkEnoughLights(basis, args.has("basis"), ext, *lp, static_cast<int>(lights.size()));
  // `surrogate lights -o FILE.lp` writes near lights' positions beside it (FILE.dome); this
  // command fits the .lp's directions as lights at infinity, and says so rather than differ
  // silently from the run that placed them.
  if (const fs::path dome = fs::path(*lp).replace_extension(".dome"); fs::exists(dome) && !args.has("json"))
    std::cerr << "warning: " << dome.string() << " gives the lights' positions, which fit does not use: it takes "
              << "the .lp's directions as lights at infinity. surrogate run on the capture, with the same "
                 "decisions, fits each pixel to its own light directions (the user guide, \"Lights at a known distance\")\n";
  stages::ModelRecipe recipe;
  recipe.basis = basisName;
  recipe.learned.planes = args.intValue("planes", stages::kLearnedPlanes);
  recipe.learned.resolution = args.intValue("resolution", stages::kLearnedResolution);
  if (const auto quality = args.value("quality")) {
    try {  // as a LearnedFit step records it
      const stages::LearnedFitOptions q = stages::LearnedFitOptions::fromParameters({{"quality", *quality}});
      recipe.web.quality = q.quality;
      recipe.web.lastQuality = q.lastQuality;
    } catch (const Error& e) {
      throw Error(ErrorKind::Usage, "--quality " + *quality, "command line", e.message());
    }
  } else {
    recipe.web.quality = stages::kLearnedQuality;
    recipe.web.lastQuality = stages::kLearnedLastQuality;
  }
  recipe.web.tiles = publish::TileLayout::None;
  // Everything the command line decides is checked before the photographs are decoded.
  if (learned) {
    recipe.learned.kind = fit::parseLearnedKind(basisName);
    fit::checkLearnedOptions(recipe.learned);
    publish::planeQualitiesOf(recipe.web, recipe.learned.planes / 3);
  }
  const int holdout = args.intValue("holdout", 0);
  if (args.has("holdout")) stages::checkHoldoutCount(holdout, static_cast<int>(lights.size()));
  ProgressBar bar(args.has("quiet") || args.has("json"));
  pipeline::RunSettings run;
  run.threads = threads;
  if (const auto m = args.value("memory")) run.memoryBudget = parseByteSize(*m, "--memory");
  run.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  // The output model is held besides the stacks: counted when deciding whether they stay in
  // memory, and the stacks held there leave the fit what remains of the budget.
  const stages::DecodedStacks decoded = stages::decodeImages(
      files, image::RawDecodeSettings(), run, {}, learned ? static_cast<std::uint64_t>(recipe.learned.planes)  // one byte a plane
                                                    : stages::modelBytesPerPixel(fit::basisName(basis)));
  run.heldBytes = decoded.bytesInMemory;

  recipe.threads = run.threads;
  std::optional<stages::HeldOutQuality> heldOut;
  if (args.has("holdout")) {
    bar.update("Fitting without the held-out photographs", 0);
    heldOut = stages::measureHeldOut(*decoded.rgb, lights, recipe, holdout);
  }

  fit::FitStatistics stats;
  fit::LearnedStatistics learnedStats;
  int fittedPlanes = 0;
  if (learned) {
    fit::LearnedOptions options = recipe.learned;
    options.kind = fit::parseLearnedKind(basisName);
    options.threads = run.threads;
    options.progress = [&bar](double f) { bar.update("Fitting", f); };
    const fit::LearnedModel model = fit::fitLearned(*decoded.rgb, lights, options, &learnedStats);
    fittedPlanes = model.planes;
    publish::writeWebLayoutFolder(publish::webLayoutOf(model, recipe.web), *out);
  } else {
    fit::FitOptions options;
    options.basis = basis;
    options.threads = run.threads;
    options.memoryBudgetBytes = run.fitBudget();
    options.progress = [&bar](double f) { bar.update("Fitting", f); };
    if (fit::isPtm(basis)) formats::writePtm(*out, fit::fitPtm(*decoded.rgb, lights, options, &stats));
    else formats::writeRti(*out, fit::fitHsh(*decoded.rgb, lights, options, &stats));
  }
  bar.finish();
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("basis").value(basisName)
        .key("images").value(static_cast<int>(files.size()));
    if (learned) {
      j.key("planes").value(fittedPlanes).key("psnr").value(learnedStats.psnr)
          .key("leaveOneOutPsnr").value(learnedStats.leaveOneOutPsnr)
          .key("explainedVariance").value(learnedStats.explainedVariance);
    } else {
      j.key("rmse").value(stats.rmse).key("psnr").value(stats.psnr).key("regularisation").value(stats.regularisation)
          .key("dampedTerms").beginArray();
      for (int k : stats.dampedTerms) j.value(k);
      j.endArray();
      if (std::isfinite(stats.conditionNumber)) j.key("conditionNumber").value(stats.conditionNumber);
    }
    if (heldOut) {
      j.key("heldOut").beginObject().key("psnr").value(heldOut->model.psnr).key("ssim").value(heldOut->model.ssim)
          .key("nearestBlendPsnr").value(heldOut->nearestBlend.psnr)
          .key("nearestBlendSsim").value(heldOut->nearestBlend.ssim).key("images").beginArray();
      for (std::size_t i = 0; i < heldOut->indices.size(); ++i)
        j.beginObject().key("image").value(files[heldOut->indices[i]].filename().string())
            .key("psnr").value(heldOut->perLight[i].psnr).key("ssim").value(heldOut->perLight[i].ssim).endObject();
      j.endArray().endObject();
    }
    j.endObject();
    std::cout << j.str() << "\n";
  } else {
    if (learned)
      std::cout << "wrote " << *out << "/ (" << basisName << ", " << fittedPlanes << " planes"
                << (fittedPlanes < recipe.learned.planes ? " (all the photographs hold)" : "") << ", " << files.size()
                << " images): PSNR " << fixedDecimals(learnedStats.psnr, 2) << " dB at the captured lights\n";
    else
      std::cout << "wrote " << *out << " (" << fit::basisName(basis) << ", " << files.size()
                << " images): RMSE " << stats.rmse << ", PSNR " << stats.psnr << " dB\n";
    if (verbosity == Verbosity::Verbose) printFitDetail(learned, stats, learnedStats, heldOut, files);
    if (heldOut && verbosity != Verbosity::Quiet)
      std::cout << "at " << heldOut->indices.size() << " lights left out of the fit: PSNR "
                << fixedDecimals(heldOut->model.psnr, 2) << " dB, SSIM " << fixedDecimals(heldOut->model.ssim, 3)
                << " (the 3 nearest photographs blended: " << fixedDecimals(heldOut->nearestBlend.psnr, 2) << " dB, SSIM "
                << fixedDecimals(heldOut->nearestBlend.ssim, 3) << ")\n";
    // The light set conditioned the fit (docs/hrti-math.md, "Conditioning on the light set").
    const std::string warning =
        learned ? "" : fit::conditioningWarning(basis, static_cast<int>(files.size()), stats);
    if (!warning.empty()) std::cerr << "warning: " << warning << "\n";
  }
  return 0;
}

}  // namespace surrogate::cli
