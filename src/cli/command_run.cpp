// surrogate run CAPTURE [options]
#include <iostream>

#include "capture/capture.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "stages/plan.h"

namespace surrogate::cli {

namespace {

std::vector<OptionSpec> runOptions() {
  return {
      {"title", true, false, "title of the project (default: the folder name)", "TEXT"},
      {"creator", true, true, "a creator, e.g. \"Ana Silva\" or \"Ana Silva:photographer\"", "NAME"},
      {"meta", true, true, "user metadata recorded in the carrier and the bag", "KEY=VALUE"},
      {"exclude", true, true, "leave an image out (needs --reason after it)", "IMAGE"},
      {"reason", true, true, "why the preceding --exclude image is left out", "TEXT"},
      {"operator", true, false, "who runs this (recorded with interventions; default $USER)", "NAME"},
      {"source", true, false, "images to use: auto (raw if present), original, export", "WHICH"},
      {"raw", true, true, "LibRaw setting, e.g. demosaic=AHD, whiteBalance=camera", "NAME=VALUE"},
      {"threads", true, false, "worker threads (default: all cores); results do not depend on it", "N"},
      {"memory", true, false, "memory budget for streaming work (default 2G)", "SIZE"},
      {"quiet", false, false, "no progress bar"},
      {"json", false, false, "print the summary as JSON"},
  };
}

std::pair<std::string, std::string> splitKeyValue(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(ErrorKind::Usage, option + " " + text, "command line", "needs the form KEY=VALUE");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

stages::RunRequest requestFrom(const Args& args) {
  stages::RunRequest r;
  r.title = args.value("title", "");
  for (const std::string& c : args.values("creator")) {
    const auto colon = c.rfind(':');
    if (colon != std::string::npos && colon > 0 && colon + 1 < c.size())
      r.creators.push_back({c.substr(0, colon), c.substr(colon + 1)});
    else
      r.creators.push_back({c, "creator"});
  }
  for (const std::string& m : args.values("meta")) r.meta.push_back(splitKeyValue(m, "--meta"));
  r.who = args.value("operator", "");
  r.source = args.value("source", "auto");
  for (const std::string& s : args.values("raw")) r.decodeSettings.push_back(splitKeyValue(s, "--raw"));
  // --exclude X --reason Y: a reason belongs to the --exclude just before it.
  for (const auto& [name, value] : args.ordered()) {
    if (name == "exclude") {
      r.exclusions.push_back({value, ""});
    } else if (name == "reason") {
      if (r.exclusions.empty() || !r.exclusions.back().reason.empty())
        throw Error(ErrorKind::Usage, "--reason", "command line",
                    "must follow the --exclude IMAGE it explains");
      r.exclusions.back().reason = value;
    }
  }
  for (const stages::Exclusion& e : r.exclusions)
    if (e.reason.empty())
      throw Error(ErrorKind::Usage, "--exclude " + e.image, "command line",
                  "every excluded image needs a reason: add --reason \"why\" after it; the "
                  "reason is recorded as a human intervention");
  return r;
}

}  // namespace

int runCommandRun(int argc, char** argv) {
  const std::vector<OptionSpec> specs = runOptions();
  Args args(argc, argv, 1, specs);
  if (args.helpRequested()) {
    std::cout << usageHeader("surrogate run CAPTURE [options]",
                             "Run the HRTI pipeline on a capture folder: ingest (hash, EXIF/XMP), "
                             "decode, and every processing stage, recording all of it in "
                             "CAPTURE/assembly-files/carrier.xml.")
              << Args::describe(specs);
    return 0;
  }
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line",
                "give exactly one capture folder: surrogate run CAPTURE (see --help)");
  const std::string capture = args.positional()[0];
  const stages::RunRequest request = requestFrom(args);

  ProgressBar bar(args.has("quiet") || args.has("json"));
  pipeline::RunSettings settings;
  settings.threads = args.intValue("threads", 0);
  if (settings.threads < 0)
    throw Error(ErrorKind::Usage, "--threads", "command line", "needs a number >= 0");
  if (const auto m = args.value("memory")) settings.memoryBudget = parseByteSize(*m, "--memory");
  settings.progress = [&bar](const std::string& label, double f) { bar.update(label, f); };
  const carrier::Carrier c = stages::runCapture(capture, request, settings);
  bar.finish();

  const std::string carrierPath = capture + "/" + capture::kAssemblyDir + "/carrier.xml";
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("capture").value(capture).key("carrier").value(carrierPath);
    j.key("steps").beginArray();
    for (const carrier::Step& s : c.process) {
      const carrier::Result* r = c.findResult(s.id);
      j.beginObject().key("id").value(s.id).key("component").value(s.component)
          .key("status").value(r ? r->status : "not run")
          .key("seconds").value(r ? r->seconds : 0.0).endObject();
    }
    j.endArray().key("outputs").beginArray();
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "assembly" || f.role == "result") j.value(f.path);
    j.endArray().endObject();
    std::cout << j.str() << "\n";
  } else {
    std::cout << "Processed " << capture << " (" << c.process.size() << " steps).\n"
              << "  carrier (provenance): " << carrierPath << "\n";
    for (const carrier::FileRecord& f : c.files)
      if (f.role == "assembly" || f.role == "result")
        std::cout << "  " << f.role << ": " << capture << "/" << f.path << "\n";
    int warnings = 0;
    for (const carrier::LogEntry& e : c.log) warnings += e.level == "warning";
    if (warnings > 0)
      std::cout << "  " << warnings << " warning(s) in the carrier's log\n";
  }
  return 0;
}

}  // namespace surrogate::cli
