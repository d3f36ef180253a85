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
// A failure of any of them is fixity (3) but for ocfl.read, ocfl.declaration and
// ocfl.inventory (invalid, 2). The bag is then put together from the head state (hard links
// where the temporary folder is on the object's file system, copies otherwise) and given to
// verifyBag: a Surrogate package in an object that is sound as OCFL is sound only if its
// bag is.
#include "verify/ocfl_checks.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "archive/bag_text.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "core/text.h"
#include "verify/checks.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace surrogate::verify {

namespace {

std::string readText(const fs::path& path) {
  try {
    return readFile(path, "verifying");
  } catch (const Error&) {
    return "";
  }
}

std::string digestOfText(const std::string& algorithm, const std::string& text) {
  MultiDigest d(std::vector<std::string>{algorithm});
  d.update(text.data(), text.size());
  return d.hex(algorithm);
}

// The digest a sidecar names ("<digest> inventory.json"), lower case; "" when not of that form.
std::string sidecarDigest(const std::string& text) {
  const auto space = text.find_first_of(" \t");
  if (space == std::string::npos) return "";
  const auto nameStart = text.find_first_not_of(" \t", space);
  if (nameStart == std::string::npos) return "";
  std::string name = text.substr(nameStart);
  while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
  if (name != "inventory.json") return "";
  std::string digest = text.substr(0, space);
  std::transform(digest.begin(), digest.end(), digest.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return digest;
}

int versionNumber(const std::string& name) {
  if (name.size() < 2 || name.size() > 10 || name[0] != 'v') return 0;
  int n = 0;
  for (std::size_t i = 1; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
    n = n * 10 + (name[i] - '0');
  }
  return n;
}

bool isLowerHex(const std::string& s, std::size_t length) {
  return s.size() == length &&
         std::all_of(s.begin(), s.end(), [](char ch) { return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f'); });
}

// A root inventory as the checks need it.
struct OcflInventory {
  std::string text, algorithm, head, contentDirectory = "content";
  std::vector<std::string> versions;                          // v1 .. vN, in order
  std::map<std::string, std::string> digestOfContent;         // content path -> digest
  std::map<std::string, std::vector<std::string>> manifest;   // digest -> content paths
  std::map<std::string, std::map<std::string, std::string>> states;  // version -> logical path -> digest
  json parsed;
};

std::optional<OcflInventory> parseRoot(const std::string& text, const std::string& declared,
                                   std::vector<std::string>& problems) {
  OcflInventory inv;
  inv.text = text;
  try {
    inv.parsed = json::parse(text);
  } catch (const json::exception& e) {
    problems.push_back(std::string("inventory.json: not valid JSON (") + e.what() + ")");
    return std::nullopt;
  }
  const json& j = inv.parsed;
  if (!j.is_object()) {
    problems.push_back("inventory.json: not a JSON object");
    return std::nullopt;
  }
  auto text_of = [&](const char* key) -> std::string {
    if (!j.contains(key) || !j[key].is_string() || j[key].get<std::string>().empty()) {
      problems.push_back(std::string("inventory.json: \"") + key + "\" is missing or not a non-empty string");
      return "";
    }
    return j[key].get<std::string>();
  };
  text_of("id");
  const std::string type = text_of("type");
  if (!type.empty() && type != "https://ocfl.io/" + declared + "/spec/#inventory")
    problems.push_back("inventory.json: type " + type + " is not that of an OCFL " + declared + " inventory");
  inv.algorithm = text_of("digestAlgorithm");
  if (!inv.algorithm.empty() && inv.algorithm != "sha512" && inv.algorithm != "sha256")
    problems.push_back("inventory.json: digestAlgorithm " + inv.algorithm + " is not sha512 or sha256");
  inv.head = text_of("head");
  if (j.contains("contentDirectory")) {
    const json& cd = j["contentDirectory"];
    if (!cd.is_string() || cd.get<std::string>().empty() || cd.get<std::string>().find('/') != std::string::npos ||
        cd == "." || cd == "..")
      problems.push_back("inventory.json: contentDirectory is not a folder name");
    else inv.contentDirectory = cd.get<std::string>();
  }
  if (!problems.empty()) return std::nullopt;
  const std::size_t hexLength = inv.algorithm == "sha512" ? 128 : 64;

  if (!j.contains("versions") || !j["versions"].is_object() || j["versions"].empty()) {
    problems.push_back("inventory.json: \"versions\" is missing or empty");
    return std::nullopt;
  }
  std::map<int, std::string> numbered;
  for (const auto& [name, v] : j["versions"].items()) {
    const int n = versionNumber(name);
    if (n == 0) problems.push_back("inventory.json: \"" + name + "\" is not a version name (v1, v2, ...)");
    else numbered[n] = name;
  }
  int expect = 1;
  for (const auto& [n, name] : numbered) {
    if (n != expect) problems.push_back("inventory.json: version v" + std::to_string(expect) + " is missing");
    expect = n + 1;
    if (name.size() != numbered.begin()->second.size() && name[1] == '0')
      problems.push_back("inventory.json: " + name + " is not zero-padded like " + numbered.begin()->second);
    inv.versions.push_back(name);
  }
  if (!inv.versions.empty() && inv.head != inv.versions.back())
    problems.push_back("inventory.json: head is " + inv.head + ", not the last version " + inv.versions.back());
  const std::set<std::string> versionSet(inv.versions.begin(), inv.versions.end());

  if (!j.contains("manifest") || !j["manifest"].is_object()) {
    problems.push_back("inventory.json: \"manifest\" is missing");
    return std::nullopt;
  }
  for (const auto& [digest, paths] : j["manifest"].items()) {
    std::string lower = digest;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (!isLowerHex(lower, hexLength)) problems.push_back("inventory.json: manifest key " + digest + " is not a " + inv.algorithm + " digest");
    if (inv.manifest.count(lower)) problems.push_back("inventory.json: manifest digest " + digest + " given twice");
    if (!paths.is_array() || paths.empty()) {
      problems.push_back("inventory.json: manifest entry " + digest + " lists no content path");
      continue;
    }
    for (const json& p : paths) {
      std::string why;
      const std::string raw = p.is_string() ? p.get<std::string>() : "";
      const auto safe = archive::safeBagPath(raw, &why);
      const auto slash = raw.find('/');
      const std::string version = raw.substr(0, slash);
      if (!safe || *safe != raw || slash == std::string::npos || !versionSet.count(version) ||
          raw.compare(slash + 1, inv.contentDirectory.size() + 1, inv.contentDirectory + "/") != 0) {
        problems.push_back("inventory.json: manifest content path \"" + raw +
                           "\" is not a safe path under a version's " + inv.contentDirectory + "/ folder");
        continue;
      }
      if (!inv.digestOfContent.emplace(raw, lower).second)
        problems.push_back("inventory.json: content path " + raw + " is listed twice in the manifest");
      inv.manifest[lower].push_back(raw);
    }
  }
  for (const std::string& name : inv.versions) {
    const json& v = j["versions"][name];
    if (!v.is_object() || !v.contains("created") || !v["created"].is_string() || !v.contains("state") ||
        !v["state"].is_object()) {
      problems.push_back("inventory.json: version " + name + " lacks created or state");
      continue;
    }
    auto& state = inv.states[name];
    for (const auto& [digest, paths] : v["state"].items()) {
      std::string lower = digest;
      std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
      if (!inv.manifest.count(lower))
        problems.push_back("inventory.json: version " + name + " names digest " + digest.substr(0, 16) +
                           "... which the manifest does not hold");
      if (!paths.is_array() || paths.empty()) {
        problems.push_back("inventory.json: version " + name + ": state entry " + digest.substr(0, 16) + "... lists no path");
        continue;
      }
      for (const json& p : paths) {
        std::string why;
        const std::string raw = p.is_string() ? p.get<std::string>() : "";
        const auto safe = archive::safeBagPath(raw, &why);
        if (!safe || *safe != raw) {
          problems.push_back("inventory.json: version " + name + ": logical path \"" + raw + "\" is not safe" +
                             (why.empty() ? "" : " (" + why + ")"));
          continue;
        }
        if (!state.emplace(raw, lower).second)
          problems.push_back("inventory.json: version " + name + " lists " + raw + " twice");
      }
    }
  }
  if (!problems.empty()) return std::nullopt;
  return inv;
}

void add(Report& report, const std::string& name, Severity severity, const std::string& passed,
         const std::string& failed, const std::vector<std::string>& problems) {
  report.checks.push_back(makeCheck(name, severity, passed, failed, problems));
}

// The head state as a bag folder in `into`: hard links to the object's content files, or
// copies where the file systems differ. Logical paths were checked safe (parseRoot).
void assembleHead(const fs::path& object, const OcflInventory& inv, const FolderWalk& walk, const fs::path& into) {
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
  const FolderWalk walk = walkFolder(object, "an OCFL object");
  std::string declared;
  for (const std::string& f : walk.files)
    if (f == "0=ocfl_object_1.1" || f == "0=ocfl_object_1.0") declared = f.substr(f.size() - 3);
  std::vector<std::string> problems = walk.problems;
  std::optional<OcflInventory> inv;
  if (declared.empty()) problems.push_back("no 0=ocfl_object_1.1 declaration at the object's root");
  else if (!walk.files.count("inventory.json")) problems.push_back("inventory.json: missing at the object's root");
  else inv = parseRoot(readText(object / "inventory.json"), declared, problems);
  if (!inv || !problems.empty())
    throw Error(ErrorKind::Usage, object.string(), "reading an OCFL object",
                "cannot be read as an OCFL object (" + (problems.empty() ? std::string("no usable inventory") : problems.front()) +
                    "); surrogate verify " + shellWord(object.string()) + " says what is wrong");
  fs::create_directories(into);
  assembleHead(object, *inv, walk, into);
  return inv->head;
}

Report verifyOcflObject(const fs::path& object, const VerifyOptions& options) {
  Report report;
  report.package = object.string();
  report.kind = "OCFL 1.1 object";
  const FolderWalk walk = walkFolder(object, "an OCFL object");
  add(report, "ocfl.read", Severity::Invalid, "the object holds files and folders only",
      "the object holds what an OCFL object may not", walk.problems);

  // The declaration: one 0= file at the root, naming itself.
  std::vector<std::string> declaration;
  std::string declared;
  for (const std::string& f : walk.files) {
    if (f.find('/') != std::string::npos || f.rfind("0=", 0) != 0) continue;
    const std::string what = f.substr(2);
    if (!declared.empty()) declaration.push_back(f + ": a second declaration");
    else if (what != "ocfl_object_1.1" && what != "ocfl_object_1.0") declaration.push_back(f + ": not an OCFL 1.0 or 1.1 object declaration");
    else if (readText(object / f) != what + "\n") declaration.push_back(f + ": does not hold \"" + what + "\" and a line end");
    else declared = what.substr(what.size() - 3);
  }
  if (declared.empty() && declaration.empty()) declaration.push_back("no 0=ocfl_object_1.1 declaration at the object's root");
  add(report, "ocfl.declaration", Severity::Invalid, "OCFL " + declared + " object", "not a declared OCFL object",
      declaration);
  if (declared.empty()) return report;
  report.kind = "OCFL " + declared + " object";

  std::vector<std::string> problems;
  std::optional<OcflInventory> inv;
  if (!walk.files.count("inventory.json")) problems.push_back("inventory.json: missing at the object's root");
  else inv = parseRoot(readText(object / "inventory.json"), declared, problems);
  add(report, "ocfl.inventory", walk.files.count("inventory.json") ? Severity::Invalid : Severity::Fixity,
      inv ? "inventory.json: " + std::to_string(inv->versions.size()) + " versions, head " + inv->head + ", " +
                std::to_string(inv->digestOfContent.size()) + " content files, " + inv->algorithm
          : "",
      "the root inventory is not a usable OCFL inventory", problems);
  if (!inv) return report;
  report.kind = "OCFL " + declared + " object, head " + inv->head;

  problems.clear();
  const std::string sidecarName = "inventory.json." + inv->algorithm;
  if (!walk.files.count(sidecarName)) problems.push_back(sidecarName + ": missing");
  else if (sidecarDigest(readText(object / sidecarName)) != digestOfText(inv->algorithm, inv->text))
    problems.push_back(sidecarName + ": does not name the digest of inventory.json (the inventory was changed)");
  add(report, "ocfl.sidecar", Severity::Fixity, sidecarName + " names the inventory's digest",
      "the root inventory does not match its sidecar", problems);

  // Versions: each folder with its inventory, the history they tell the same as the root's.
  problems.clear();
  const std::set<std::string> versionSet(inv->versions.begin(), inv->versions.end());
  for (const std::string& v : inv->versions) {
    if (!walk.folders.count(v)) {
      problems.push_back(v + "/: missing (a version was removed)");
      continue;
    }
    const std::string text = readText(object / v / "inventory.json");
    if (!walk.files.count(v + "/inventory.json")) {
      problems.push_back(v + "/inventory.json: missing");
      continue;
    }
    if (!walk.files.count(v + "/" + sidecarName) ||
        sidecarDigest(readText(object / v / sidecarName)) != digestOfText(inv->algorithm, text)) {
      problems.push_back(v + "/" + sidecarName + ": missing or not the digest of " + v + "/inventory.json");
      continue;
    }
    if (v == inv->head) {
      if (text != inv->text) problems.push_back(v + "/inventory.json: not identical to the root inventory of head " + v);
      continue;
    }
    json earlier;
    try {
      earlier = json::parse(text);
    } catch (const json::exception&) {
      problems.push_back(v + "/inventory.json: not valid JSON");
      continue;
    }
    if (!earlier.is_object() || earlier.value("head", "") != v || earlier.value("id", "") != inv->parsed["id"] ||
        !earlier.contains("versions") || !earlier["versions"].is_object()) {
      problems.push_back(v + "/inventory.json: not the inventory of " + v + " of this object");
      continue;
    }
    for (const std::string& w : inv->versions) {
      if (w == v) break;
      if (!earlier["versions"].contains(w) || earlier["versions"][w] != inv->parsed["versions"][w])
        problems.push_back(v + "/inventory.json: says version " + w + " was other than the root inventory says");
    }
    if (!earlier["versions"].contains(v) || earlier["versions"][v] != inv->parsed["versions"][v])
      problems.push_back(v + "/inventory.json: says version " + v + " was other than the root inventory says");
  }
  static const std::set<std::string> rootFiles = {"inventory.json", "0=ocfl_object_" + declared};
  for (const std::string& f : walk.files)
    if (f.find('/') == std::string::npos && !rootFiles.count(f) && f != sidecarName)
      problems.push_back(f + ": a file at the object's root that OCFL does not place there" +
                         (f.rfind(".inventory.json", 0) == 0 && f.find(".part-") != std::string::npos
                              ? std::string(" (left by a pack that did not finish: the next pack into the object removes it)")
                              : std::string()));
  for (const std::string& d : walk.folders)
    if (d.find('/') == std::string::npos && !versionSet.count(d) && d != "extensions")
      problems.push_back(d + "/: a folder at the object's root that is no version of its inventory");
  add(report, "ocfl.versions", Severity::Fixity,
      "every version " + inv->versions.front() + ".." + inv->head + " is there, with the history the root inventory gives",
      "the object's versions are not those its inventory records", problems);

  // Content: every manifest path a file, every content file in the manifest, each digest right.
  problems.clear();
  for (const auto& [path, digest] : inv->digestOfContent)
    if (!walk.files.count(path)) problems.push_back(path + ": listed in the manifest, missing");
  for (const std::string& f : walk.files) {
    const auto slash = f.find('/');
    if (slash == std::string::npos || !versionSet.count(f.substr(0, slash))) continue;
    const std::string rest = f.substr(slash + 1);
    if (rest == "inventory.json" || rest == sidecarName) continue;
    if (!inv->digestOfContent.count(f)) problems.push_back(f + ": in the object, in no manifest entry");
  }
  add(report, "ocfl.complete", Severity::Fixity,
      "every content file of the manifest is there, and nothing else", "the object's content is not what its manifest lists",
      problems);

  problems.clear();
  std::size_t done = 0;
  for (const auto& [path, digest] : inv->digestOfContent) {
    if (!walk.files.count(path)) continue;
    if (options.progress) options.progress("checking the object's content", double(done++) / double(inv->digestOfContent.size()));
    std::string actual;
    try {
      const FileDigests d = digestFile(object / path, inv->algorithm == "sha512");
      actual = inv->algorithm == "sha512" ? d.sha512 : d.sha256;
    } catch (const Error& e) {
      problems.push_back(path + ": cannot be read (" + e.text() + ")");
      continue;
    }
    if (actual != digest) problems.push_back(path + ": its " + inv->algorithm + " is not the manifest's");
  }
  add(report, "ocfl.fixity-" + inv->algorithm, Severity::Fixity,
      std::to_string(inv->digestOfContent.size()) + " content files match the manifest's " + inv->algorithm,
      "content files differ from the manifest", problems);

  // The head version's bag, verified as a bag folder.
  TempDir temp("verify-ocfl");
  const fs::path bag = temp.path() / object.filename();
  fs::create_directory(bag);
  assembleHead(object, *inv, walk, bag);
  Report held = verifyBag(bag, options);
  const std::string tempText = bag.string(), shown = (object / (inv->head + " (state)")).string();
  for (Check& c : held.checks) {
    for (std::string& w : c.where)
      for (auto at = w.find(tempText); at != std::string::npos; at = w.find(tempText, at + shown.size()))
        w.replace(at, tempText.size(), shown);
    report.checks.push_back(std::move(c));
  }
  for (std::string& w : held.warnings) report.warnings.push_back(inv->head + ": " + w);
  report.surrogatePackage = held.surrogatePackage;
  report.holderFields = std::move(held.holderFields);
  report.reexecuted = held.reexecuted;
  report.softwareDifferences = std::move(held.softwareDifferences);
  return report;
}

}  // namespace surrogate::verify
