// The checks of an OCFL object (ocfl_object.h says each), shared by verify and
// pack --layout ocfl; nlohmann's JSON reads the inventories.
#include "archive/ocfl_object.h"

#include <algorithm>
#include <set>

#include <nlohmann/json.hpp>

#include "archive/bag_text.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace surrogate::archive {

namespace {

// The text of an inventory, sidecar or declaration; "" when it cannot be read or is larger
// than kMaxOcflInventoryBytes (the checks then find it wrong: tooLarge says why for an inventory).
std::string readText(const fs::path& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > kMaxOcflInventoryBytes) return "";
  try {
    return readFile(path, "reading an OCFL object");
  } catch (const Error&) {
    return "";
  }
}

// "NAME: larger than ..." when the file at `path` is too large to be read as an inventory; "" otherwise.
std::string tooLarge(const fs::path& path, const std::string& name) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size <= kMaxOcflInventoryBytes) return "";
  return name + ": " + std::to_string(size) + " bytes, more than the " + std::to_string(kMaxOcflInventoryBytes >> 20) +
         " MiB an inventory may have here (not read)";
}

std::string digestOfText(const std::string& algorithm, const std::string& text) {
  MultiDigest d(std::vector<std::string>{algorithm});
  d.update(text.data(), text.size());
  return d.hex(algorithm);
}

bool isLowerHex(const std::string& s, std::size_t length) {
  return s.size() == length &&
         std::all_of(s.begin(), s.end(), [](char ch) { return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f'); });
}

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return s;
}

// How deeply `text` nests arrays and objects (brackets inside strings not counted). An OCFL
// inventory nests six levels (versions, a version, its state, a digest's paths; the fixity
// block); pack writes an inventory it read back out, and nlohmann's writer recurses once per
// level and indents each line by its depth: 100,000 levels took minutes and gigabytes.
std::size_t nestingDepth(const std::string& text) {
  std::size_t depth = 0, deepest = 0;
  bool inString = false, escaped = false;
  for (const char ch : text) {
    if (inString) {
      if (escaped) escaped = false;
      else if (ch == '\\') escaped = true;
      else if (ch == '"') inString = false;
    } else if (ch == '"') {
      inString = true;
    } else if (ch == '[' || ch == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((ch == ']' || ch == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}
constexpr std::size_t kMaxInventoryDepth = 16;

// The parsed root inventory beside what parseOcflInventory gives: the versions check compares
// earlier inventories with its "versions" as JSON.
struct ParsedInventory {
  OcflInventory inv;
  json parsed;
};

std::optional<ParsedInventory> parseRoot(const std::string& text, const std::string& declared,
                                         std::vector<std::string>& problems) {
  ParsedInventory r;
  OcflInventory& inv = r.inv;
  inv.text = text;
  if (nestingDepth(text) > kMaxInventoryDepth) {
    problems.push_back("inventory.json: nests arrays and objects more than " + std::to_string(kMaxInventoryDepth) +
                       " levels deep, which no OCFL inventory does");
    return std::nullopt;
  }
  try {
    r.parsed = json::parse(text);
  } catch (const json::exception& e) {
    problems.push_back(std::string("inventory.json: not valid JSON (") + e.what() + ")");
    return std::nullopt;
  }
  const json& j = r.parsed;
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
  inv.id = text_of("id");
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
    const int n = ocflVersionNumber(name);
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
    const std::string lower = lowerCase(digest);
    if (!isLowerHex(lower, hexLength)) problems.push_back("inventory.json: manifest key " + digest + " is not a " + inv.algorithm + " digest");
    if (inv.manifest.count(lower)) problems.push_back("inventory.json: manifest digest " + digest + " given twice");
    if (!paths.is_array() || paths.empty()) {
      problems.push_back("inventory.json: manifest entry " + digest + " lists no content path");
      continue;
    }
    for (const json& p : paths) {
      std::string why;
      const std::string raw = p.is_string() ? p.get<std::string>() : "";
      const auto safe = safeBagPath(raw, &why);
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
      const std::string lower = lowerCase(digest);
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
        const auto safe = safeBagPath(raw, &why);
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
  return r;
}

// The declaration: one 0= file at the root, naming itself. Sets c.declared when sound.
void checkDeclaration(const fs::path& object, OcflObjectCheck& c) {
  for (const std::string& f : c.walk.files) {
    if (f.find('/') != std::string::npos || f.rfind("0=", 0) != 0) continue;
    const std::string what = f.substr(2);
    if (!c.declared.empty()) c.declaration.push_back(f + ": a second declaration");
    else if (what != "ocfl_object_1.1" && what != "ocfl_object_1.0") c.declaration.push_back(f + ": not an OCFL 1.0 or 1.1 object declaration");
    else if (readText(object / f) != what + "\n") c.declaration.push_back(f + ": does not hold \"" + what + "\" and a line end");
    else c.declared = what.substr(what.size() - 3);
  }
  if (c.declared.empty() && c.declaration.empty())
    c.declaration.push_back("no 0=ocfl_object_1.1 declaration at the object's root");
}

// Each version folder with its inventory, the history they tell the same as the root's; no
// other file or folder at the root.
void checkVersions(const fs::path& object, const ParsedInventory& root, OcflObjectCheck& c) {
  const OcflInventory& inv = root.inv;
  const FolderWalk& walk = c.walk;
  const std::string sidecarName = "inventory.json." + inv.algorithm;
  const std::set<std::string> versionSet(inv.versions.begin(), inv.versions.end());
  for (const std::string& v : inv.versions) {
    if (!walk.folders.count(v)) {
      c.versions.push_back(v + "/: missing (a version was removed)");
      continue;
    }
    if (!walk.files.count(v + "/inventory.json")) {
      c.versions.push_back(v + "/inventory.json: missing");
      continue;
    }
    if (const std::string big = tooLarge(object / v / "inventory.json", v + "/inventory.json"); !big.empty()) {
      c.versions.push_back(big);
      continue;
    }
    const std::string text = readText(object / v / "inventory.json");
    if (!walk.files.count(v + "/" + sidecarName) ||
        ocflSidecarDigest(readText(object / v / sidecarName)) != digestOfText(inv.algorithm, text)) {
      c.versions.push_back(v + "/" + sidecarName + ": missing or not the digest of " + v + "/inventory.json");
      continue;
    }
    if (v == inv.head) {
      if (text != inv.text) c.versions.push_back(v + "/inventory.json: not identical to the root inventory of head " + v);
      continue;
    }
    json earlier;
    try {
      earlier = json::parse(text);
    } catch (const json::exception&) {
      c.versions.push_back(v + "/inventory.json: not valid JSON");
      continue;
    }
    if (!earlier.is_object() || !earlier.contains("head") || earlier["head"] != v || !earlier.contains("id") ||
        earlier["id"] != root.parsed["id"] || !earlier.contains("versions") || !earlier["versions"].is_object()) {
      c.versions.push_back(v + "/inventory.json: not the inventory of " + v + " of this object");
      continue;
    }
    for (const std::string& w : inv.versions) {
      if (!earlier["versions"].contains(w) || earlier["versions"][w] != root.parsed["versions"][w])
        c.versions.push_back(v + "/inventory.json: says version " + w + " was other than the root inventory says");
      if (w == v) break;
    }
  }
  const std::set<std::string> rootFiles = {"inventory.json", "0=ocfl_object_" + c.declared, sidecarName};
  for (const std::string& f : walk.files)
    if (f.find('/') == std::string::npos && !rootFiles.count(f))
      c.versions.push_back(f + ": a file at the object's root that OCFL does not place there" +
                           (f.rfind(".inventory.json", 0) == 0 && f.find(".part-") != std::string::npos
                                ? std::string(" (left by a pack that did not finish: the next pack into the object removes it)")
                                : std::string()));
  for (const std::string& d : walk.folders)
    if (d.find('/') == std::string::npos && !versionSet.count(d) && d != "extensions")
      c.versions.push_back(d + "/: a folder at the object's root that is no version of its inventory");
}

// Every manifest path a file, every content file in the manifest.
void checkComplete(const OcflInventory& inv, OcflObjectCheck& c) {
  const std::string sidecarName = "inventory.json." + inv.algorithm;
  const std::set<std::string> versionSet(inv.versions.begin(), inv.versions.end());
  for (const auto& [path, digest] : inv.digestOfContent)
    if (!c.walk.files.count(path)) c.complete.push_back(path + ": listed in the manifest, missing");
  for (const std::string& f : c.walk.files) {
    const auto slash = f.find('/');
    if (slash == std::string::npos || !versionSet.count(f.substr(0, slash))) continue;
    const std::string rest = f.substr(slash + 1);
    if (rest == "inventory.json" || rest == sidecarName) continue;
    if (!inv.digestOfContent.count(f)) c.complete.push_back(f + ": in the object, in no manifest entry");
  }
}

// Each content file's digest against the manifest's.
void checkFixity(const fs::path& object, const OcflInventory& inv, const OcflCheckOptions& options,
                 OcflObjectCheck& c) {
  std::size_t done = 0;
  for (const auto& [path, digest] : inv.digestOfContent) {
    if (!c.walk.files.count(path)) continue;
    if (options.progress) options.progress(double(done++) / double(inv.digestOfContent.size()));
    std::string actual;
    try {
      const FileDigests d = digestFile(object / path, inv.algorithm == "sha512");
      actual = inv.algorithm == "sha512" ? d.sha512 : d.sha256;
    } catch (const Error& e) {
      c.fixity.push_back(path + ": cannot be read (" + e.text() + ")");
      continue;
    }
    if (actual != digest) c.fixity.push_back(path + ": its " + inv.algorithm + " is not the manifest's");
  }
}

}  // namespace

std::string ocflSidecarDigest(const std::string& text) {
  const auto space = text.find_first_of(" \t");
  if (space == std::string::npos) return "";
  const auto nameStart = text.find_first_not_of(" \t", space);
  if (nameStart == std::string::npos) return "";
  std::string name = text.substr(nameStart);
  while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
  if (name != "inventory.json") return "";
  return lowerCase(text.substr(0, space));
}

int ocflVersionNumber(const std::string& name) {
  if (name.size() < 2 || name.size() > 10 || name[0] != 'v') return 0;
  int n = 0;
  for (std::size_t i = 1; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
    n = n * 10 + (name[i] - '0');
  }
  return n;
}

std::optional<OcflInventory> parseOcflInventory(const std::string& text, const std::string& declared,
                                                std::vector<std::string>& problems) {
  std::optional<ParsedInventory> r = parseRoot(text, declared, problems);
  if (!r) return std::nullopt;
  return std::move(r->inv);
}

std::vector<std::string> OcflObjectCheck::problems() const {
  std::vector<std::string> all;
  for (const std::vector<std::string>* list :
       {&walk.problems, &declaration, &inventoryProblems, &sidecar, &versions, &complete, &fixity})
    all.insert(all.end(), list->begin(), list->end());
  return all;
}

OcflObjectCheck checkOcflObject(const fs::path& object, const OcflCheckOptions& options) {
  OcflObjectCheck c;
  c.walk = walkFolder(object, "an OCFL object");
  checkDeclaration(object, c);
  if (c.declared.empty()) return c;

  std::optional<ParsedInventory> root;
  if (!c.walk.files.count("inventory.json")) {
    c.inventoryMissing = true;
    c.inventoryProblems.push_back("inventory.json: missing at the object's root");
  } else if (const std::string big = tooLarge(object / "inventory.json", "inventory.json"); !big.empty()) {
    c.inventoryProblems.push_back(big);
  } else {
    root = parseRoot(readText(object / "inventory.json"), c.declared, c.inventoryProblems);
  }
  if (!root) return c;
  c.inventory = root->inv;
  const OcflInventory& inv = *c.inventory;

  const std::string sidecarName = "inventory.json." + inv.algorithm;
  if (!c.walk.files.count(sidecarName)) c.sidecar.push_back(sidecarName + ": missing");
  else if (ocflSidecarDigest(readText(object / sidecarName)) != digestOfText(inv.algorithm, inv.text))
    c.sidecar.push_back(sidecarName + ": does not name the digest of inventory.json (the inventory was changed)");

  checkVersions(object, *root, c);
  checkComplete(inv, c);
  if (options.contentDigests) checkFixity(object, inv, options, c);
  return c;
}

}  // namespace surrogate::archive
