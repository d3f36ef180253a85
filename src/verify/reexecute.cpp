// --reexecute: extract the bag's payload safely, run the recorded process list again on the
// bagged originals, and compare every recorded result.
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"
#include "core/temp_dir.h"
#include "mapping/mapping.h"
#include "pipeline/stage.h"
#include "run/plan.h"
#include "verify/checks.h"
#include "verify/model_difference.h"

namespace fs = std::filesystem;

namespace surrogate::verify {

namespace {

// Whether a payload file is an output of the recorded steps (extracted aside, to compare with)
// rather than an input; `outputs` holds the paths of the carrier's assembly and result files.
bool isOutputPath(const std::string& relative, const std::unordered_set<std::string>& outputs) {
  if (relative.compare(0, 15, "assembly-files/") == 0 || relative.compare(0, 15, "finished-files/") == 0)
    return true;
  return outputs.count(relative) > 0;
}

// The extracted inputs are made read-only, so that no step can change an original by
// accident. Folders stay writable for their owner: what a killed verifier leaves in $TMPDIR
// can be removed with `rm -rf` (TempDir removes it on every other way out).
void makeReadOnly(const fs::path& root) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, ec);
    else fs::permissions(it->path(), fs::perms::owner_read | fs::perms::group_read, ec);
  }
}

std::optional<double> asNumber(const std::string& s) {
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE) return std::nullopt;
  return v;
}

bool sameNumber(double a, double b, double tolerance) {
  if (a == b) return true;
  return tolerance > 0 && std::fabs(a - b) <= tolerance * std::max(std::fabs(a), std::fabs(b));
}

std::string pathOfId(const carrier::Carrier& c, const std::string& id) {
  const carrier::FileRecord* f = c.findFile(id);
  return f ? f->path : "(unknown file " + id + ")";
}

struct StepComparison {
  std::vector<std::string> differences;
  std::size_t compared = 0;
};

// What a result item is about (element, image, name, sphere, index, kind): items are matched
// by it, not by position, so one extra or missing result does not shift every other one.
std::string itemKey(const carrier::Carrier& c, const carrier::DataItem& item) {
  std::string key = item.element;
  for (const char* attr : {"image", "name", "sphere", "index", "kind"}) {
    if (auto v = item.get(attr))
      key += std::string(" ") + attr + "=" + (std::string(attr) == "image" ? pathOfId(c, *v) : *v);
  }
  return key;
}

using ItemPair = std::pair<const carrier::DataItem*, const carrier::DataItem*>;

// Pairs each recorded item with a reproduced one of the same key; what is left on either side
// is a difference.
std::vector<ItemPair> matchItems(const carrier::Carrier& recorded, const carrier::Result& a,
                                 const carrier::Carrier& fresh, const carrier::Result& b,
                                 StepComparison& out) {
  std::map<std::string, std::vector<const carrier::DataItem*>> fresher;
  for (const carrier::DataItem& y : b.items) fresher[itemKey(fresh, y)].push_back(&y);
  std::map<std::string, std::size_t> used;
  std::vector<ItemPair> pairs;
  for (const carrier::DataItem& x : a.items) {
    const std::string key = itemKey(recorded, x);
    auto& list = fresher[key];
    std::size_t& n = used[key];
    if (n < list.size()) {
      pairs.emplace_back(&x, list[n++]);
    } else {
      out.differences.push_back("recorded <" + key + "> was not reproduced");
    }
  }
  for (const auto& [key, list] : fresher)
    for (std::size_t i = used[key]; i < list.size(); ++i)
      out.differences.push_back("reproduced <" + key + ">, which was not recorded");
  return pairs;
}

// Every attribute of a pair of items: numbers within the tolerance, files by path, the rest
// as text.
void compareAttributes(const carrier::DataItem& x, const carrier::DataItem& y,
                       const carrier::Carrier& recorded, const carrier::Carrier& fresh,
                       double tolerance, StepComparison& out) {
  const std::string label = itemKey(recorded, x);
  std::set<std::string> names;
  for (const auto& [k, v] : x.attributes) names.insert(k);
  for (const auto& [k, v] : y.attributes) names.insert(k);
  for (const std::string& name : names) {
    std::string u = x.get(name).value_or("(absent)"), v = y.get(name).value_or("(absent)");
    ++out.compared;
    if (name == "file" || name == "image") {
      u = pathOfId(recorded, u);
      v = pathOfId(fresh, v);
    }
    const auto nu = asNumber(u), nv = asNumber(v);
    const bool same = (nu && nv) ? sameNumber(*nu, *nv, tolerance) : u == v;
    if (!same)
      out.differences.push_back(label + " @" + name + ": recorded " + u + ", reproduced " + v);
  }
}

// An output file: by hash, then, when it differs, by how much.
void compareOutputFile(const carrier::DataItem& x, const carrier::DataItem& y,
                       const carrier::Carrier& recorded, const carrier::Carrier& fresh,
                       const fs::path& recordedRoot, const fs::path& freshRoot,
                       StepComparison& out) {
  const carrier::FileRecord* fa = recorded.findFile(x.get("file").value_or(""));
  const carrier::FileRecord* fb = fresh.findFile(y.get("file").value_or(""));
  if (!fa || !fb) {
    out.differences.push_back("output " + (fa ? fa->path : std::string("?")) +
                              ": not recorded in both carriers");
    return;
  }
  if (fa->sha256 == fb->sha256) return;
  std::string how = "differs (SHA-256 " + fa->sha256.substr(0, 12) + "... recorded, " +
                    fb->sha256.substr(0, 12) + "... reproduced)";
  const std::string ext = fs::path(fa->path).extension().string();
  try {
    if (ext == ".ptm" || ext == ".rti")
      how += "; " + compareModels(recordedRoot / fa->path, freshRoot / fb->path).describe();
    else if (ext == ".png" || ext == ".jpg" || ext == ".tif" || ext == ".tiff")
      how += "; " + compareImages(recordedRoot / fa->path, freshRoot / fb->path);
  } catch (const Error& e) {
    how += "; cannot compare them (" + e.text() + ")";
  }
  out.differences.push_back("output file " + fa->path + " " + how);
}

// Packages made before text had PUIDs (mappings/pronom.md, "Text, JSON and JavaScript")
// record none for their .lp, JSON and JavaScript files; the bytes are compared by their hash,
// so the identification a later release gives them is not a different result.
bool laterTextIdentification(const std::string& recorded, const std::string& reproduced) {
  return recorded.empty() && (reproduced == "x-fmt/111" || reproduced == "fmt/817" || reproduced == "x-fmt/423");
}

// The carrier's description of every file, as the re-executed steps record it again: what a
// file is (role, format, media type, PRONOM id, what prior work says of its making), its camera
// metadata, XMP, size in pixels and pairing. Bytes (size, SHA-256) of inputs are compared too;
// those of outputs are the steps' comparisons (which may allow a tolerance). Without this, a
// carrier whose descriptions were rewritten, then packed again, would re-execute as sound.
StepComparison compareFileRecords(const carrier::Carrier& recorded, const carrier::Carrier& fresh) {
  StepComparison out;
  std::map<std::string, const carrier::FileRecord*> freshByPath;
  for (const carrier::FileRecord& f : fresh.files) freshByPath.emplace(f.path, &f);
  // Pairings compared by path (ids may be numbered otherwise): each carrier's ids looked up
  // once, not by a search of its whole list per file.
  auto pathsById = [](const carrier::Carrier& c) {
    std::unordered_map<std::string, std::string> out;
    for (const carrier::FileRecord& f : c.files) out.emplace(f.id, f.path);
    return out;
  };
  const auto recordedPaths = pathsById(recorded), freshPaths = pathsById(fresh);
  auto pairedPath = [](const std::unordered_map<std::string, std::string>& paths, const carrier::FileRecord& f) {
    if (f.pairedWith.empty()) return std::string();
    const auto it = paths.find(f.pairedWith);
    return it != paths.end() ? it->second : "(unknown file " + f.pairedWith + ")";
  };
  auto cameraText = [](const carrier::Attributes& a) {
    std::string t;
    for (const auto& [k, v] : a) t += k + "=" + v + ";";
    return t;
  };
  auto sizeText = [](const std::optional<std::pair<int, int>>& s) {
    return s ? std::to_string(s->first) + "x" + std::to_string(s->second) : std::string("(absent)");
  };
  for (const carrier::FileRecord& a : recorded.files) {
    const auto it = freshByPath.find(a.path);
    if (it == freshByPath.end()) {
      out.differences.push_back("file " + a.path + ": recorded, not recorded again");
      continue;
    }
    const carrier::FileRecord& b = *it->second;
    freshByPath.erase(it);
    const bool output = a.role == "assembly" || a.role == "result";
    std::vector<std::tuple<const char*, std::string, std::string>> fields = {
        {"role", a.role, b.role},
        {"format", a.format, b.format},
        {"mediaType", a.mediaType, b.mediaType},
        {"puid", a.puid, b.puid},
        {"createdBy", a.createdBy, b.createdBy},
        {"pairedWith", pairedPath(recordedPaths, a), pairedPath(freshPaths, b)},
        {"unrecordedProcessing", a.unrecordedProcessing ? "true" : "false", b.unrecordedProcessing ? "true" : "false"},
        {"image size", sizeText(a.imageSize), sizeText(b.imageSize)},
        {"camera", cameraText(a.camera), cameraText(b.camera)},
        {"xmp", a.xmp, b.xmp},
        {"priorKind", a.priorKind, b.priorKind},
        {"madeBy", a.madeBy, b.madeBy}};
    if (!output) {
      fields.emplace_back("size", std::to_string(a.size), std::to_string(b.size));
      fields.emplace_back("sha256", a.sha256, b.sha256);
    }
    for (const auto& [name, u, v] : fields) {
      ++out.compared;
      if (u != v && !(std::string(name) == "puid" && laterTextIdentification(u, v)))
        out.differences.push_back("file " + a.path + " @" + name + ": recorded \"" + u.substr(0, 120) +
                                  "\", reproduced \"" + v.substr(0, 120) + "\"");
    }
  }
  for (const auto& [path, f] : freshByPath)
    out.differences.push_back("file " + path + ": recorded again, but not in the recorded carrier");
  return out;
}

StepComparison compareStep(const carrier::Step& step, const carrier::Carrier& recorded,
                           const carrier::Carrier& fresh, const fs::path& recordedRoot,
                           const fs::path& freshRoot, double tolerance) {
  StepComparison out;
  const carrier::Result* a = recorded.findResult(step.id);
  const carrier::Result* b = fresh.findResult(step.id);
  if (!a) return out;  // nothing recorded: nothing to reproduce
  if (!b) {
    out.differences.push_back("the step did not run again (an earlier step failed)");
    return out;
  }
  if (a->status != b->status)
    out.differences.push_back("status: recorded " + a->status + ", reproduced " + b->status);
  for (const auto& [x, y] : matchItems(recorded, *a, fresh, *b, out)) {
    compareAttributes(*x, *y, recorded, fresh, tolerance, out);
    if (x->element == "output") compareOutputFile(*x, *y, recorded, fresh, recordedRoot, freshRoot, out);
  }
  return out;
}

std::vector<std::string> softwareDifferences(const carrier::Carrier& recorded,
                                             const carrier::Carrier& fresh) {
  std::vector<std::string> out;
  std::map<std::string, std::string> now;
  for (const carrier::Software& s : fresh.header.software) now[s.name] = s.version;
  for (const carrier::Software& s : recorded.header.software) {
    const auto it = now.find(s.name);
    if (it == now.end()) out.push_back(s.name + " " + s.version + " -> absent in this build");
    else if (it->second != s.version) out.push_back(s.name + " " + s.version + " -> " + it->second);
  }
  return out;
}

// Extracts the payload into `root`: inputs (originals, exports, a given .lp, and prior work,
// which lies in the output folders but is an input: the run records it again, and a step may
// read it) to replay/, made read-only, recorded outputs to recorded/ to compare with.
void extractForReplay(const fs::path& package, const Inventory& inventory,
                      const carrier::Carrier& recorded, const VerifyOptions& options,
                      const fs::path& root) {
  const fs::path replayRoot = root / "replay";
  fs::create_directory(replayRoot);
  fs::create_directory(root / "recorded");
  std::unordered_set<std::string> outputs, prior;
  for (const carrier::FileRecord& f : recorded.files) {
    if (f.role == "assembly" || f.role == "result") outputs.insert(f.path);
    if (f.role == "prior") prior.insert(f.path);
  }
  extractFiles(
      package, inventory, root,
      [&](const std::string& path) -> fs::path {
        // The RO-Crate's metadata is the package's, derived from the carrier (metadata.ro-crate),
        // not a file of the capture: the run would record it as a new input.
        if (path.compare(0, 5, "data/") != 0 || path == mapping::kRoCratePath) return {};
        const std::string relative = path.substr(5);
        const bool output = !prior.count(relative) && isOutputPath(relative, outputs);
        return fs::path(output ? "recorded" : "replay") / relative;
      },
      options.limits, options.progress);
  makeReadOnly(replayRoot);
  // Outputs are written into fresh folders of the copy; the originals stay read-only.
  for (const char* dir : {"assembly-files", "finished-files"}) {
    std::error_code ec;
    fs::create_directory(replayRoot / dir, ec);
  }
}

// Runs the recorded process list again in `replayRoot`; returns the fresh carrier (as far as
// it got) and what stopped it in `problems`.
carrier::Carrier replay(const fs::path& replayRoot, const carrier::Carrier& recorded,
                        const VerifyOptions& options, const fs::path& freshCarrierPath,
                        std::vector<std::string>& problems) {
  pipeline::RunSettings settings;
  settings.threads = options.threads;
  settings.who = "surrogate verify";
  if (options.progress)
    settings.progress = [&](const std::string& label, double f) {
      options.progress("re-executing: " + label, f);
    };
  carrier::Carrier fresh;
  try {
    fresh = run::replayCarrier(replayRoot, recorded, settings, freshCarrierPath);
  } catch (const Error& e) {
    problems.push_back(e.text());
    std::error_code ec;
    if (fs::exists(freshCarrierPath, ec)) {
      try {
        fresh = carrier::loadCarrier(freshCarrierPath);
      } catch (const Error&) {
      }
    }
    if (fresh.header.software.empty()) fresh.header.software = run::softwareVersions();
  } catch (const std::exception& e) {
    // A library failing on a bagged file (a decoder exception) is a failure to reproduce,
    // not a crash of the verifier.
    problems.push_back(std::string("a step failed: ") + e.what());
    fresh.header.software = run::softwareVersions();
  }
  return fresh;
}

}  // namespace

void checkReexecution(const fs::path& package, const Inventory& inventory,
                      const carrier::Carrier& recorded, const VerifyOptions& options,
                      Report& report) {
  report.reexecuted = true;
  TempDir temp("verify");
  const fs::path replayRoot = temp.path() / "replay", recordedRoot = temp.path() / "recorded";
  extractForReplay(package, inventory, recorded, options, temp.path());
  std::vector<std::string> runProblems;
  const carrier::Carrier fresh =
      replay(replayRoot, recorded, options, temp.path() / "reexecuted-carrier.xml", runProblems);
  report.softwareDifferences = softwareDifferences(recorded, fresh);
  std::vector<Check> found;
  found.push_back(makeCheck("reexecute.run", Severity::NotReproduced,
                            "the recorded process list ran again (" +
                                std::to_string(recorded.process.size()) + " steps)",
                            "the recorded process list could not be run again", runProblems));
  for (const carrier::Step& step : recorded.process) {
    const StepComparison cmp =
        compareStep(step, recorded, fresh, recordedRoot, replayRoot, options.tolerance);
    const std::string exactness = options.tolerance > 0
        ? "within a relative tolerance of " + std::to_string(options.tolerance)
        : "exactly";
    found.push_back(makeCheck(
        "reexecute." + step.id + "." + step.component, Severity::NotReproduced,
        "reproduced " + exactness + " (" + std::to_string(cmp.compared) + " recorded values)",
        "re-running the step gave other results than those recorded", cmp.differences));
  }
  const StepComparison files = compareFileRecords(recorded, fresh);
  found.push_back(makeCheck("reexecute.files", Severity::NotReproduced,
                            "the files are described as recorded (" + std::to_string(files.compared) +
                                " recorded values)",
                            "re-running the steps described the files otherwise than recorded",
                            files.differences));
  for (Check& c : found) {
    if (!c.passed && !report.softwareDifferences.empty())
      for (const std::string& s : report.softwareDifferences)
        c.where.push_back("software differs: " + s);
    report.checks.push_back(std::move(c));
  }
}

}  // namespace surrogate::verify
