// surrogate lights CAPTURE -o FILE.lp: light estimation only (ingest, decode, spheres,
// highlights, light directions), recorded in the capture's carrier like a run.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <iostream>

#include "capture/capture.h"
#include "capture/lock.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/pipeline_options.h"
#include "cli/progress.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "formats/lp.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// "images": each light of FILE.lp, named as FILE.lp names its image, with its direction and
// uncertaintyDegrees (the 95 % bound in degrees on its angle from the true direction,
// hrti/light_uncertainty.h; null for a light read from the capture's own .lp file), from the
// carrier's light items, matched to the .lp's lines by the image file they name; and where the
// light was, position and distance (nearLight), null for a light at infinity.
void writeLightImages(JsonWriter& j, const carrier::Carrier& c, const fs::path& capture, const fs::path& written,
                      const std::vector<formats::LightEntry>& entries) {
  const std::vector<formats::LightEntry> lines = formats::readLp(written);
  const carrier::Result* result = c.lastResultWith("light");
  auto same = [](const fs::path& a, const fs::path& b) {
    std::error_code ea, eb;
    return fs::weakly_canonical(a, ea) == fs::weakly_canonical(b, eb);
  };
  j.key("images").beginArray();
  for (std::size_t n = 0; n < entries.size() && n < lines.size(); ++n) {
    const auto image = formats::resolveLpImage(written, lines[n].filename);
    const carrier::DataItem* item = nullptr;
    for (const carrier::DataItem* l : result ? result->itemsOf("light") : std::vector<const carrier::DataItem*>{}) {
      const carrier::FileRecord* f = c.findFile(l->get("image").value_or(""));
      if (f && image && same(capture / f->path, *image)) item = l;
    }
    j.beginObject().key("image").value(entries[n].filename).key("x").value(entries[n].x)
        .key("y").value(entries[n].y).key("z").value(entries[n].z).key("uncertaintyDegrees");
    if (item && item->get("uncertaintyDegrees")) j.value(item->number("uncertaintyDegrees"));
    else j.null();
    // Where the light was (nearLight): its position in frame coordinates (pixels, origin at the
    // frame's centre, y up) and distance in frame widths; null for a light at infinity.
    const carrier::DataItem* place = nullptr;
    for (const carrier::DataItem* p : result && item ? result->itemsOf("nearLight") : std::vector<const carrier::DataItem*>{})
      if (p->get("image") == item->get("image")) place = p;
    j.key("position");
    if (place)
      j.beginArray().value(place->number("x")).value(place->number("y")).value(place->number("z")).endArray();
    else j.null();
    j.key("distance");
    if (place) j.value(place->number("distance"));
    else j.null();
    j.endObject();
  }
  j.endArray();
}

}  // namespace

int runCommandLights(int argc, char** argv) {
  std::vector<OptionSpec> specs = pipelineOptions(false);
  specs.push_back({"o", true, false, "the .lp file to write", "FILE.lp", OptionGroup::Output});
  specs.push_back({"output", true, false, "same as -o", "FILE.lp", OptionGroup::Output});
  for (const OptionSpec& o : runtimeOptions()) specs.push_back(o);
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate lights CAPTURE -o FILE.lp [options]",
                 "Estimate the light direction of every image from the highlights on the spheres and write "
                 "them as an .lp file, which names the images relative to its own folder. Also writes the "
                 "sphere overlay, the highlight overviews and the carrier in CAPTURE/assembly-files/ (a run "
                 "that stops after the lights: it is recorded like any other).",
                 {{"surrogate lights stela12 -o stela12.lp", "the light directions of the capture stela12"},
                  {"surrogate lights stela12 --sphere 412,300,88 --reason \"detection missed the sphere\" -o stela12.lp",
                   "the same with the sphere's circle given by hand"}},
                 commonExitCodes("the .lp file is written", {{3, kChangedOriginal}})}))
    return 0;
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out)
    throw Error(ErrorKind::Usage, "", "command line", "give the capture and the output: surrogate lights CAPTURE -o FILE.lp");
  const fs::path capture = args.positional()[0];
  refuseCaptureSubfolder(capture, "lights");
  checkOutputFile("-o", *out, "lights.lp");  // before the run, not after it
  // Near lights' positions go beside it, in relight's dome file (stages/light_estimation.h).
  const fs::path dome = fs::path(*out).replace_extension(".dome");
  checkOutputFile("-o", dome, "lights.dome");
  run::RunRequest request = requestFrom(args);
  request.lightsOnly = true;
  request.command = "lights";
  ProgressBar bar(args.has("quiet") || args.has("json"));
  const pipeline::RunSettings settings = settingsFrom(args, bar);
  capture::requireCaptureFolder(capture);  // before anything is written in it
  // Held until the capture's lights.lp is copied: a run meanwhile would replace it.
  capture::CaptureLock lock(capture, "lights");
  const carrier::Carrier c = run::runCapture(capture, request, settings, /*takeLock=*/false);
  bar.finish();

  // The capture's lights.lp names the images relative to assembly-files/; FILE.lp names them
  // relative to its own folder, wherever it is and whatever the working directory.
  const fs::path written = capture / capture::kAssemblyDir / "lights.lp";
  std::vector<formats::LightEntry> entries = formats::readLp(written);
  for (formats::LightEntry& e : entries) {
    const auto image = formats::resolveLpImage(written, e.filename);
    e.filename = formats::lpImageName(*out, image ? *image : written.parent_path() / e.filename);
  }
  formats::writeLp(*out, entries);
  bool near = false;
  if (const carrier::Result* r = c.lastResultWith("light")) near = !r->itemsOf("nearLight").empty();
  if (near) {
    std::ifstream in(capture / capture::kAssemblyDir / "lights.dome", std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    writeFileAtomically(dome, bytes.str());
  }
  int lights = 0, flagged = 0;
  for (const carrier::Result& r : c.data) {
    lights += static_cast<int>(r.itemsOf("light").size());
    for (const carrier::DataItem* h : r.itemsOf("highlight")) flagged += h->get("flag") != "ok";
  }
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("positions");
    if (near) j.value(dome.string());
    else j.null();
    j.key("lights").value(lights)
        .key("flaggedHighlights").value(flagged)
        .key("carrier").value((capture / capture::kAssemblyDir / "carrier.xml").string());
    writeLightImages(j, c, capture, written, entries);
    j.endObject();
    std::cout << j.str() << "\n";
  } else {
    const Verbosity verbosity = verbosityOf(args);
    const carrier::CarrierSummary summary = carrier::describeCarrier(c);
    std::cout << "wrote " << *out << " (" << lights << " lights";
    if (near) std::cout << "; their positions in " << dome.string();
    if (flagged) std::cout << ", " << flagged << " highlight(s) flagged";
    if (!summary.warnings.empty())
      std::cout << ", " << summary.warnings.size() << (summary.warnings.size() == 1 ? " warning" : " warnings");
    std::cout << ")\n";
    if (verbosity == Verbosity::Quiet) return 0;
    std::cout << "  sphere overlay and highlight overviews: " << (capture / capture::kAssemblyDir).string() << "/\n";
    // As `run` prints them: grouped by step, a screenful unless --verbose.
    printWarnings(summary, verbosity == Verbosity::Verbose ? 0 : kWarningLines,
                  "surrogate info " + escapedText(capture.string()) + " lists them all");
  }
  return 0;
}

}  // namespace surrogate::cli
