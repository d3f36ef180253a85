// surrogate publish FILE.ptm|FILE.rti|CAPTURE -o DIR [--quality Q] [--tiles LAYOUT] [--tile-size N]:
// the web layout that OpenLIME and Relight's web viewer read, with a viewer (publish/web_layout.h).
#include <cctype>
#include <filesystem>
#include <iostream>

#include "capture/output_rule.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "publish/web_layout.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {
// The index page publish() writes beside the model folders of a capture (publish/web_layout.h),
// relative to the output folder; "" for a single model, whose folder is the output itself.
std::string indexPageOf(const std::vector<publish::PublishedModel>& models) {
  return !models.empty() && !models.front().folder.empty() ? "index.html" : "";
}

void printJson(const std::string& out, const publish::PublishOptions& options,
               const std::vector<publish::PublishedModel>& models, const std::vector<std::string>& removed) {
  JsonWriter j;
  j.beginObject().key("output").value(out).key("quality").value(options.quality).key("models").beginArray();
  for (const publish::PublishedModel& m : models) {
    j.beginObject().key("source").value(m.source).key("folder").value(m.folder).key("type").value(m.type)
        .key("tiles").value(m.tiles.empty() ? "none" : m.tiles).key("levels").value(m.levels)
        .key("colorspace").value(m.colorspace).key("width").value(m.width).key("height").value(m.height)
        .key("nplanes").value(m.nplanes).key("files").beginArray();
    for (const std::string& f : m.files) j.value(f);
    j.endArray().endObject();
  }
  j.endArray().key("index");
  if (indexPageOf(models).empty()) j.null();
  else j.value(indexPageOf(models));
  j.key("removedLeftovers").beginArray();
  for (const std::string& r : removed) j.value(r);
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}
}  // namespace

int runCommandPublish(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"memory", true, false, "memory budget (default 2G): a larger model is refused from its header", "SIZE"},
      {"o", true, false, "the folder to write (new, or empty)", "DIR", OptionGroup::Output},
      {"output", true, false, "same as -o", "DIR", OptionGroup::Output},
      {"quality", true, false, "JPEG quality 1..100 of the coefficient planes (default 95)", "Q", OptionGroup::Output},
      {"tiles", true, false,
       "auto (default: Deep Zoom tiles when a side exceeds 4096 texels), none (whole plane images) or "
       "deepzoom (always tiles)", "LAYOUT", OptionGroup::Output},
      {"tile-size", true, false, "side of a Deep Zoom tile in texels, 16..4096 (default 256)", "N", OptionGroup::Output},
      {"quiet", false, false, "at most one summary line", "", OptionGroup::Output},
      {"verbose", false, false, "list every file written", "", OptionGroup::Output},
      {"json", false, false, "print what was written as JSON", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate publish FILE.ptm|FILE.rti|CAPTURE -o DIR [--quality Q] [--tiles LAYOUT] [--tile-size N]",
                 "Write a PTM or HSH model, or every one a capture's carrier records in finished-files/, in the "
                 "web layout OpenLIME and Relight's web viewer read: info.json and JPEG coefficient planes "
                 "(Deep Zoom tiles for a model larger than a screen), with index.html, a viewer that relights "
                 "the model in a browser, also from a local folder.",
                 {{"surrogate publish stela12 -o web/stela12",
                   "every model of the capture stela12, with an index page linking them"},
                  {"surrogate publish coin.ptm -o web/coin --tiles deepzoom --quality 90",
                   "one model as Deep Zoom tiles, for a web server"}},
                 commonExitCodes("the web layout is written",
                                 {{3, "a capture's result no longer matches the SHA-256 the carrier records: run "
                                      "the capture again, or restore the file"}})}))
    return 0;
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out)
    throw Error(ErrorKind::Usage, "", "command line",
                "give the model or capture and the folder to write: surrogate publish FILE.ptm -o DIR");
  // A new folder (publish refuses one that is not empty), never in a capture's own folders.
  capture::checkOutputTarget(*out, "-o", capture::ExistingOutput::ReplaceOutput);
  publish::PublishOptions options;
  if (const auto q = args.value("quality")) {
    options.quality = args.intValue("quality", 95);
    if (options.quality < 1 || options.quality > 100)
      throw Error(ErrorKind::Usage, "--quality " + *q, "command line", "needs a JPEG quality from 1 to 100");
  }
  if (const auto t = args.value("tiles")) options.tiles = publish::parseTileLayout(*t);
  if (args.value("tile-size")) options.tileSize = args.intValue("tile-size", 256);
  if (const auto m = args.value("memory")) options.memoryBudget = parseByteSize(*m, "--memory");
  std::vector<std::string> removed;
  const auto models = publish::publish(args.positional()[0], *out, options, &removed);
  if (args.has("json")) {
    printJson(*out, options, models, removed);
    return 0;
  }
  const Verbosity verbosity = verbosityOf(args);
  const std::string index = indexPageOf(models);
  if (verbosity == Verbosity::Quiet) {
    std::cout << "wrote " << *out << " (" << models.size() << (models.size() == 1 ? " model" : " models")
              << "; open " << (fs::path(*out) / (index.empty() ? "index.html" : index)).generic_string() << ")\n";
    return 0;
  }
  for (const std::string& r : removed)
    std::cout << char(std::toupper(static_cast<unsigned char>(r[0]))) << r.substr(1) << ".\n";
  for (const publish::PublishedModel& m : models) {
    std::string folder = (std::filesystem::path(*out) / m.folder).generic_string();
    if (folder.back() != '/') folder += '/';  // out / "" already ends with one
    std::cout << "wrote " << folder << " (" << m.type << " "
              << m.colorspace << ", " << m.width << "x" << m.height << ", " << (m.nplanes + 2) / 3
              << " JPEG planes" << (m.tiles.empty() ? "" : " as Deep Zoom tiles (" + std::to_string(options.tileSize) +
                                    " texels, " + std::to_string(m.levels) + " levels)")
              << ", quality " << options.quality << ", viewer index.html) from " << m.source << "\n";
    if (verbosity == Verbosity::Verbose)
      for (const std::string& f : m.files) std::cout << "  " << escapedText(folder + f) << "\n";
  }
  if (!index.empty())
    std::cout << "wrote " << (fs::path(*out) / index).generic_string() << " (the page linking every model)\n";
  return 0;
}

}  // namespace surrogate::cli
