#include "cli/commands.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include "core/text.h"

namespace surrogate::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"run", "run the HRTI pipeline on a capture folder, recording everything", runCommandRun},
      {"pack", "write the archival package (BagIt folder, .tar or .zip) of a capture", runCommandPack},
      {"lights", "estimate the light directions of a capture and write an .lp file", runCommandLights},
      {"fit", "fit a PTM or HSH model to the images of an .lp file", runCommandFit},
      {"render", "relight a .ptm or .rti under a chosen light and save a PNG", runCommandRender},
      {"publish", "write a .ptm, .rti or capture's results in the web layout (info.json, JPEG planes)", runCommandPublish},
      {"info", "describe a package, carrier, capture, image, .xmp sidecar, .ptm, .rti or .lp file", runCommandInfo},
      {"report", "write the HTML report of a capture or package", runCommandReport},
      {"review", "review a capture in a local browser page: spheres, highlights, frames left out, checks, description", runCommandReview},
      {"verify", "check a package: fixity, schemas, metadata; --reexecute re-runs its steps", runCommandVerify},
      {"audit", "audit another tool's RTI (RTIBuilder's .lp, .ptm, .rti, log) read-only, in a work folder", runCommandAudit},
      {"batch", "process, pack and verify a list of captures (or verify packages), one job each, with a ledger", runCommandBatch},
  };
  return list;
}

void printWarnings(const carrier::CarrierSummary& s, std::size_t mostLines, const std::string& more) {
  if (s.warnings.empty()) return;
  // The steps in the order their first warning comes, each with its warnings in log order.
  std::vector<std::pair<std::string, std::vector<const carrier::WarningSummary*>>> groups;
  for (const carrier::WarningSummary& w : s.warnings) {
    const std::string heading = w.step.empty() ? "(no step)" : w.step + (w.component.empty() ? "" : " " + w.component);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == heading; });
    if (it == groups.end()) it = groups.insert(groups.end(), {heading, {}});
    it->second.push_back(&w);
  }
  // The lines in full: a heading, then its warnings (nullptr marks a heading).
  std::vector<std::pair<std::string, const carrier::WarningSummary*>> lines;
  for (const auto& [heading, warnings] : groups) {
    lines.emplace_back(heading, nullptr);
    for (const carrier::WarningSummary* w : warnings) lines.emplace_back(w->text, w);
  }
  std::size_t keep = lines.size();
  if (mostLines != 0 && lines.size() > mostLines) {
    keep = mostLines - 1;  // the last line counts the rest
    while (keep > 0 && !lines[keep - 1].second) --keep;  // never a heading over nothing
  }
  std::size_t shown = 0;
  std::cout << "  " << s.warnings.size() << (s.warnings.size() == 1 ? " warning" : " warnings")
            << " in the carrier's log:\n";
  for (std::size_t i = 0; i < keep; ++i) {
    // Names from the card may hold control characters: never sent raw to the terminal.
    std::cout << (lines[i].second ? "      " : "    ") << escapedText(lines[i].first) << (lines[i].second ? "\n" : ":\n");
    shown += lines[i].second != nullptr;
  }
  if (shown < s.warnings.size()) std::cout << "    and " << (s.warnings.size() - shown) << " more: " << more << "\n";
}

void printFileList(const std::vector<ListedFile>& files, Verbosity verbosity) {
  // The folders of `path` two or more levels deep, shallowest first: "a/b/c/f" -> "a/b/", "a/b/c/".
  const auto foldable = [](const std::string& path) {
    std::vector<std::string> folders;
    for (std::size_t slash = path.find('/'); slash != std::string::npos; slash = path.find('/', slash + 1))
      if (slash != path.find('/')) folders.push_back(path.substr(0, slash + 1));
    return folders;
  };
  using Key = std::pair<std::string, std::string>;  // (label, root + folder)
  std::map<Key, std::size_t> count;
  for (const ListedFile& f : files)
    for (const std::string& folder : foldable(f.path)) ++count[{f.label, f.root + "/" + folder}];
  std::set<Key> shown;
  for (const ListedFile& f : files) {
    std::optional<Key> fold;
    if (verbosity != Verbosity::Verbose)
      for (const std::string& folder : foldable(f.path))
        if (const Key key{f.label, f.root + "/" + folder}; count[key] > kFilesListedPerFolder) {
          fold = key;
          break;
        }
    // Names from the card may hold control characters: never sent raw to the terminal.
    if (!fold)
      std::cout << "  " << f.label << ": " << escapedText(f.root + "/" + f.path) << "\n";
    else if (shown.insert(*fold).second)
      std::cout << "  " << f.label << ": " << escapedText(fold->second) << " (" << count[*fold]
                << " files; --verbose lists them)\n";
  }
}

bool helpShown(const Args& args, const std::vector<OptionSpec>& specs, const CommandHelp& help) {
  if (!args.helpRequested()) return false;
  std::cout << Args::describe(help, specs);
  return true;
}

std::vector<std::pair<int, std::string>> commonExitCodes(const std::string& success,
                                                         std::vector<std::pair<int, std::string>> more) {
  std::vector<std::pair<int, std::string>> codes = {
      {0, success},
      {1, "bad input: a file that cannot be read or processed, or " + std::string(kWriteRefused) +
              "; the message names the file"},
      {2, "bad usage: an unknown option, a missing or malformed value"},
      {5, kInternalError}};
  codes.insert(codes.end(), more.begin(), more.end());
  std::stable_sort(codes.begin(), codes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return codes;
}

std::optional<std::string> outputOption(const Args& args) {
  return args.has("o") ? args.value("o") : args.value("output");
}

}  // namespace surrogate::cli
