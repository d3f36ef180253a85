// surrogate fit --lp FILE.lp -o OUT.ptm|OUT.rti [--basis B]: fit a model from a light file and
// its images, outside any capture folder or carrier (a tool for people who already have an
// .lp from elsewhere, e.g. a dome).
#include <cmath>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "fit/fit.h"
#include "formats/lp.h"
#include "stages/decode_images.h"

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

int runCommandFit(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"lp", true, false, "the light file naming the images and their light directions", "FILE.lp", OptionGroup::Input},
      {"basis", true, false, "ptm-lrgb, ptm-rgb (for .ptm), hsh2, hsh3 (for .rti)", "BASIS"},
      {"threads", true, false, "worker threads (default: all cores)", "N"},
      {"memory", true, false, "memory budget (default 2G)", "SIZE"},
      {"o", true, false, "output: .ptm (PTM) or .rti (HSH)", "OUT", OptionGroup::Output},
      {"output", true, false, "same as -o", "OUT", OptionGroup::Output},
      {"quiet", false, false, "no progress bar, and at most one summary line", "", OptionGroup::Output},
      {"json", false, false, "print the fit quality as JSON", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate fit --lp FILE.lp -o OUT.ptm|OUT.rti [--basis BASIS]",
                 "Fit a PTM or HSH model to the images an .lp file names, with its light directions, "
                 "outside any capture and with no record. (surrogate run does this for a capture, with "
                 "provenance.)",
                 {{"surrogate fit --lp coin/lights.lp -o coin.ptm",
                   "fit a PTM (luminance and colour, as RTIViewer opens it) to the photographs lights.lp names"},
                  {"surrogate fit --lp coin/lights.lp -o coin.rti --basis hsh3",
                   "fit third-order hemispherical harmonics"}},
                 commonExitCodes("the model is written")}))
    return 0;
  const auto lp = args.value("lp");
  const auto out = outputOption(args);
  if (!lp || !out)
    throw Error(ErrorKind::Usage, "", "command line", "give the light file and the output: --lp FILE.lp -o OUT.ptm");
  const std::string ext = lowerCase(fs::path(*out).extension().string());
  checkOutputFile("-o", *out, ext == ".ptm" ? "model.ptm" : "model.rti");
  if (ext != ".ptm" && ext != ".rti")
    throw Error(ErrorKind::Usage, "-o " + *out, "command line", "the output must end in .ptm or .rti");
  const int threads = threadsOption(args);
  const fit::Basis basis = fit::parseBasis(args.value("basis", ext == ".ptm" ? "ptm-lrgb" : "hsh2"));
  const bool ptm = basis == fit::Basis::PtmLrgb || basis == fit::Basis::PtmRgb;
  if (ptm != (ext == ".ptm"))
    throw Error(ErrorKind::Usage, *out, "command line",
                std::string("basis ") + fit::basisName(basis) + " is written as " + (ptm ? ".ptm" : ".rti"));

  std::vector<fs::path> files;
  std::vector<std::array<double, 3>> lights;
  for (const formats::LightEntry& e : formats::readLp(*lp)) {
    files.push_back(resolveImage(*lp, e.filename));
    lights.push_back({e.x, e.y, e.z});
  }
  checkEnoughLights(basis, args.has("basis"), ext, *lp, static_cast<int>(lights.size()));
  // `surrogate lights -o FILE.lp` writes near lights' positions beside it (FILE.dome); this
  // command fits the .lp's directions as lights at infinity, and says so rather than differ
  // silently from the run that placed them.
  if (const fs::path dome = fs::path(*lp).replace_extension(".dome"); fs::exists(dome) && !args.has("json"))
    std::cerr << "warning: " << dome.string() << " gives the lights' positions, which fit does not use: it takes "
              << "the .lp's directions as lights at infinity. surrogate run on the capture, with the same "
                 "decisions, fits each pixel to its own light directions (the user guide, \"Lights at a known distance\")\n";
  ProgressBar bar(args.has("quiet") || args.has("json"));
  pipeline::RunSettings run;
  run.threads = threads;
  if (const auto m = args.value("memory")) run.memoryBudget = parseByteSize(*m, "--memory");
  run.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  // The output model is held besides the stacks: counted when deciding whether they stay in
  // memory, and the stacks held there leave the fit what remains of the budget.
  const stages::DecodedStacks decoded = stages::decodeImages(files, image::RawDecodeSettings(), run, {},
                                                             stages::modelBytesPerPixel(fit::basisName(basis)));
  run.heldBytes = decoded.bytesInMemory;

  fit::FitOptions options;
  options.basis = basis;
  options.threads = run.threads;
  options.memoryBudgetBytes = run.fitBudget();
  options.progress = [&bar](double f) { bar.update("Fitting", f); };
  fit::FitStatistics stats;
  if (ptm) formats::writePtm(*out, fit::fitPtm(*decoded.rgb, lights, options, &stats));
  else formats::writeRti(*out, fit::fitHsh(*decoded.rgb, lights, options, &stats));
  bar.finish();
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("basis").value(fit::basisName(basis))
        .key("images").value(static_cast<int>(files.size())).key("rmse").value(stats.rmse)
        .key("psnr").value(stats.psnr).key("regularisation").value(stats.regularisation)
        .key("dampedTerms").beginArray();
    for (int k : stats.dampedTerms) j.value(k);
    j.endArray();
    if (std::isfinite(stats.conditionNumber)) j.key("conditionNumber").value(stats.conditionNumber);
    j.endObject();
    std::cout << j.str() << "\n";
  } else {
    std::cout << "wrote " << *out << " (" << fit::basisName(basis) << ", " << files.size()
              << " images): RMSE " << stats.rmse << ", PSNR " << stats.psnr << " dB\n";
    // The light set conditioned the fit (docs/hrti-math.md, "Conditioning on the light set").
    const std::string warning = fit::conditioningWarning(basis, static_cast<int>(files.size()), stats);
    if (!warning.empty()) std::cerr << "warning: " << warning << "\n";
  }
  return 0;
}

}  // namespace surrogate::cli
