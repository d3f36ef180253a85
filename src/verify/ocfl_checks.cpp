// An OCFL 1.1 object (https://ocfl.io/1.1/spec/, what pack --layout ocfl writes) verified as
// such, then the bag its head version holds verified as any bag folder:
//
//   ocfl.read         the object's folder holds regular files and folders only (no link)
//   ocfl.declaration  one declaration, 0=ocfl_object_1.1 (or 1.0) holding its own name
//   ocfl.inventory    the root inventory.json is an OCFL inventory: id, type, digestAlgorithm
//                     sha512 or sha256, head the last of versions v1..vN, a manifest of safe
//                     content paths under those versions, each version's created and state,
//                     every state digest in the manifest, safe logical paths
//   ocfl.sidecar      inventory.json.<algorithm> names the root inventory's digest
//   ocfl.versions     every version folder is there with an inventory its sidecar names, the
//                     head's identical to the root's, each earlier one saying of the versions
//                     up to it what the root says (a version removed or rewritten fails); no
//                     other file or folder at the root
//   ocfl.complete     every content path of the manifest is a file, every file of a version's
//                     content is in the manifest
//   ocfl.fixity-ALG   every content file has the digest the manifest gives it
//
// The checks themselves are archive's (archive/ocfl_object.h), which pack --layout ocfl makes
// too before adding a version. A failure of any of them is fixity (3) but for ocfl.read,
// ocfl.declaration and ocfl.inventory (invalid, 2). The bag is then put together from the head state (hard links
// where the temporary folder is on the object's file system, copies otherwise) and given to
// verifyBag: a Surrogate package in an object that is sound as OCFL is sound only if its
// bag is.
#include "verify/ocfl_checks.h"

#include <algorithm>

#include "archive/ocfl_object.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "core/text.h"
#include "verify/checks.h"

namespace fs = std::filesystem;

namespace surrogate::verify {

namespace {

void add(Report& report, const std::string& name, Severity severity, const std::string& passed,
         const std::string& failed, const std::vector<std::string>& problems) {
  report.checks.push_back(makeCheck(name, severity, passed, failed, problems));
}

// The head state as a bag folder in `into`: hard links to the object's content files, or
// copies where the file systems differ. Logical paths were checked safe (archive::parseOcflInventory).
void assembleHead(const fs::path& object, const archive::OcflInventory& inv, const FolderWalk& walk,
                  const fs::path& into) {
  for (const auto& [logical, digest] : inv.states.at(inv.head)) {
    const std::vector<std::string>& sources = inv.manifest.at(digest);
    const auto present = std::find_if(sources.begin(), sources.end(),
                                      [&](const std::string& s) { return walk.files.count(s) > 0; });
    if (present == sources.end()) continue;  // ocfl.complete says so; the bag checks will too
    const fs::path target = into / fs::path(logical);
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    fs::create_hard_link(object / *present, target, ec);
    if (ec) {
      ec.clear();
      fs::copy_file(object / *present, target, ec);
      if (ec)
        throw Error(ErrorKind::Internal, target.string(), "verifying",
                    "cannot put the head version's bag together in a temporary folder (" + ec.message() +
                        "): free space in the temporary folder (TMPDIR) and verify again");
    }
  }
}

}  // namespace

bool isOcflObject(const fs::path& package) {
  std::error_code ec;
  if (!fs::is_directory(package, ec)) return false;
  for (const fs::directory_entry& e : fs::directory_iterator(package, ec))
    if (e.path().filename().string().rfind("0=ocfl_object_", 0) == 0) return true;
  return false;
}

std::string assembleOcflHead(const fs::path& object, const fs::path& into) {
  archive::OcflCheckOptions structureOnly;
  structureOnly.contentDigests = false;
  const archive::OcflObjectCheck c = archive::checkOcflObject(object, structureOnly);
  std::vector<std::string> problems = c.walk.problems;
  if (c.declared.empty()) problems.push_back("no 0=ocfl_object_1.1 declaration at the object's root");
  problems.insert(problems.end(), c.inventoryProblems.begin(), c.inventoryProblems.end());
  if (!c.inventory || !problems.empty())
    throw Error(ErrorKind::Usage, object.string(), "reading an OCFL object",
                "cannot be read as an OCFL object (" + (problems.empty() ? std::string("no usable inventory") : problems.front()) +
                    "); surrogate verify " + shellWord(object.string()) + " says what is wrong");
  fs::create_directories(into);
  assembleHead(object, *c.inventory, c.walk, into);
  return c.inventory->head;
}

Report verifyOcflObject(const fs::path& object, const VerifyOptions& options) {
  Report report;
  report.package = object.string();
  report.kind = "OCFL 1.1 object";
  archive::OcflCheckOptions checkOptions;
  if (options.progress)
    checkOptions.progress = [&](double done) { options.progress("checking the object's content", done); };
  const archive::OcflObjectCheck c = archive::checkOcflObject(object, checkOptions);
  add(report, "ocfl.read", Severity::Invalid, "the object holds files and folders only",
      "the object holds what an OCFL object may not", c.walk.problems);
  add(report, "ocfl.declaration", Severity::Invalid, "OCFL " + c.declared + " object", "not a declared OCFL object",
      c.declaration);
  if (c.declared.empty()) return report;
  report.kind = "OCFL " + c.declared + " object";

  const std::optional<archive::OcflInventory>& inv = c.inventory;
  add(report, "ocfl.inventory", c.inventoryMissing ? Severity::Fixity : Severity::Invalid,
      inv ? "inventory.json: " + std::to_string(inv->versions.size()) + " versions, head " + inv->head + ", " +
                std::to_string(inv->digestOfContent.size()) + " content files, " + inv->algorithm
          : "",
      "the root inventory is not a usable OCFL inventory", c.inventoryProblems);
  if (!inv) return report;
  report.kind = "OCFL " + c.declared + " object, head " + inv->head;

  const std::string sidecarName = "inventory.json." + inv->algorithm;
  add(report, "ocfl.sidecar", Severity::Fixity, sidecarName + " names the inventory's digest",
      "the root inventory does not match its sidecar", c.sidecar);
  add(report, "ocfl.versions", Severity::Fixity,
      "every version " + inv->versions.front() + ".." + inv->head + " is there, with the history the root inventory gives",
      "the object's versions are not those its inventory records", c.versions);
  add(report, "ocfl.complete", Severity::Fixity,
      "every content file of the manifest is there, and nothing else", "the object's content is not what its manifest lists",
      c.complete);
  add(report, "ocfl.fixity-" + inv->algorithm, Severity::Fixity,
      std::to_string(inv->digestOfContent.size()) + " content files match the manifest's " + inv->algorithm,
      "content files differ from the manifest", c.fixity);

  // The head version's bag, verified as a bag folder.
  TempDir temp("verify-ocfl");
  const fs::path bag = temp.path() / object.filename();
  fs::create_directory(bag);
  assembleHead(object, *inv, c.walk, bag);
  Report held = verifyBag(bag, options);
  const std::string tempText = bag.string(), shown = (object / (inv->head + " (state)")).string();
  for (Check& check : held.checks) {
    for (std::string& w : check.where)
      for (auto at = w.find(tempText); at != std::string::npos; at = w.find(tempText, at + shown.size()))
        w.replace(at, tempText.size(), shown);
    report.checks.push_back(std::move(check));
  }
  for (std::string& w : held.warnings) report.warnings.push_back(inv->head + ": " + w);
  report.surrogatePackage = held.surrogatePackage;
  report.holderFields = std::move(held.holderFields);
  report.reexecuted = held.reexecuted;
  report.softwareDifferences = std::move(held.softwareDifferences);
  return report;
}

}  // namespace surrogate::verify
