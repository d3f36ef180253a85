#include "cli/commands.h"

#include <algorithm>
#include <iostream>
#include <set>

#include "core/text.h"
#include "stages/rti_fit_stage.h"
#include "stages/highlight_detection_stage.h"
#include "stages/light_directions_stage.h"
#include "stages/sphere_detection_stage.h"

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
      {"verify", "check a package: fixity, schemas, metadata; --reexecute re-runs its steps", runCommandVerify},
      {"audit", "audit another tool's RTI (RTIBuilder's .lp, .ptm, .rti, log) read-only, in a work folder", runCommandAudit},
      {"batch", "process, pack and verify a list of captures (or verify packages), one job each, with a ledger", runCommandBatch},
  };
  return list;
}

void printStageWarnings(const carrier::Carrier& c, std::size_t most) {
  std::set<std::string> lightSteps;
  for (const carrier::Step& s : c.process)
    if (s.component == stages::SphereDetectionStage::kComponent ||
        s.component == stages::HighlightDetectionStage::kComponent ||
        s.component == stages::LightDirectionsStage::kComponent || s.component == stages::RtiFitStage::kComponent)
      lightSteps.insert(s.id);
  std::size_t shown = 0, more = 0;
  for (const carrier::LogEntry& e : c.log) {
    if (e.level != "warning" || !lightSteps.count(e.step)) continue;
    if (shown == most) {
      ++more;
      continue;
    }
    std::string text = e.text;
    // Names from the card may hold control characters: never sent raw to the terminal.
    for (char& ch : text)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '?';
    std::cout << "  warning: " << text << "\n";
    ++shown;
  }
  if (more) std::cout << "  and " << more << " more warning(s) on the lights and fits in the carrier's log\n";
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

std::string usageHeader(const std::string& synopsis, const std::string& description) {
  return "usage: " + synopsis + "\n\n" + description + "\n\noptions:\n";
}

bool helpShown(const Args& args, const std::vector<OptionSpec>& specs, const std::string& synopsis,
               const std::string& description) {
  if (!args.helpRequested()) return false;
  std::cout << usageHeader(synopsis, description) << Args::describe(specs);
  return true;
}

std::optional<std::string> outputOption(const Args& args) {
  return args.has("o") ? args.value("o") : args.value("output");
}

}  // namespace surrogate::cli
