#include <map>
#include <set>

#include "archive/bag_text.h"
#include "verify/checks.h"

namespace surrogate::verify {

Check makeCheck(const std::string& name, Severity severity, const std::string& passedText,
                const std::string& failedText, const std::vector<std::string>& problems) {
  Check c;
  c.name = name;
  c.severity = severity;
  c.passed = problems.empty();
  c.what = c.passed ? passedText : failedText;
  for (std::size_t i = 0; i < problems.size() && i < kMaxWhere; ++i) c.where.push_back(problems[i]);
  if (problems.size() > kMaxWhere)
    c.where.push_back("... and " + std::to_string(problems.size() - kMaxWhere) + " more");
  return c;
}

const std::string* contentOf(const Inventory& inv, const std::string& path) {
  const auto it = inv.files.find(path);
  if (it == inv.files.end() || !it->second.content) return nullptr;
  return &*it->second.content;
}

namespace {

bool isPayload(const std::string& path) { return path.compare(0, 5, "data/") == 0; }

const std::string& digestOf(const InventoryFile& f, const std::string& algorithm) {
  return algorithm == "sha512" ? f.sha512 : f.sha256;
}

}  // namespace

void checkBag(const Inventory& inv, std::vector<Check>& checks) {
  // bagit.txt
  {
    std::vector<std::string> problems;
    const std::string* text = contentOf(inv, "bagit.txt");
    if (!text) {
      problems.push_back("bagit.txt: missing; this is not a BagIt bag");
    } else {
      for (const std::string& p : parseDeclaration(*text).problems) problems.push_back("bagit.txt: " + p);
    }
    checks.push_back(makeCheck("bagit.declaration", Severity::Invalid,
                               "bagit.txt declares BagIt 1.0 with UTF-8 tag files",
                               "bagit.txt is missing or malformed", problems));
  }

  // Parse every manifest and tagmanifest.
  std::vector<Manifest> payloadManifests, tagManifests;
  std::vector<std::string> structure;
  for (const auto& [path, file] : inv.files) {
    const auto name = manifestName(path);
    if (!name) continue;
    const std::size_t hex = digestHexLength(name->second);
    if (hex == 0) {
      structure.push_back(path + ": algorithm \"" + name->second +
                          "\" is not one this verifier accepts (sha256, sha512)");
      continue;
    }
    if (!file.content) {
      structure.push_back(path + ": too large to be a manifest");
      continue;
    }
    Manifest m = parseManifest(*file.content, name->second, hex);
    for (const std::string& p : m.problems) structure.push_back(path + ": " + p);
    for (const ManifestEntry& e : m.entries) {
      const std::string where = path + " line " + std::to_string(e.line) + ": " + e.path;
      if (name->first == "manifest" && !isPayload(e.path))
        structure.push_back(where + " is outside data/; a payload manifest lists payload only");
      if (name->first == "tagmanifest" && isPayload(e.path))
        structure.push_back(where + " is payload; a tagmanifest lists tag files only");
      if (name->first == "tagmanifest" && manifestName(e.path) &&
          manifestName(e.path)->first == "tagmanifest")
        structure.push_back(where + ": a tagmanifest must not list a tagmanifest");
    }
    (name->first == "manifest" ? payloadManifests : tagManifests).push_back(std::move(m));
  }
  if (payloadManifests.empty())
    structure.push_back("no payload manifest (manifest-sha256.txt or manifest-sha512.txt)");
  // fetch.txt: this verifier never fetches; every file it names must already be in the bag.
  if (const std::string* fetch = contentOf(inv, "fetch.txt")) {
    int number = 0;
    for (const std::string& line : splitLines(*fetch)) {
      ++number;
      const std::size_t last = line.find_last_of(" \t");
      if (line.empty()) continue;
      std::string why;
      const auto path = last == std::string::npos ? std::nullopt
                                                  : safeBagPath(percentDecode(line.substr(last + 1)), &why);
      const std::string where = "fetch.txt line " + std::to_string(number);
      if (!path) structure.push_back(where + ": " + (why.empty() ? "not <url> <length> <path>" : why));
      else if (!isPayload(*path)) structure.push_back(where + ": " + *path + " is outside data/");
      else if (!inv.files.count(*path))
        structure.push_back(where + ": " + *path + " is to be fetched; Surrogate never fetches, "
                            "so the bag is incomplete");
    }
  }
  checks.push_back(makeCheck("bagit.manifests", Severity::Invalid,
                             "manifests and tagmanifests are well-formed and name only safe paths",
                             "a manifest or tagmanifest is malformed", structure));

  // Completeness: every payload file in every manifest; every listed file present.
  {
    std::vector<std::string> problems;
    for (const Manifest& m : payloadManifests) {
      std::set<std::string> listed;
      const std::string file = "manifest-" + m.algorithm + ".txt";
      for (const ManifestEntry& e : m.entries) {
        listed.insert(e.path);
        if (isPayload(e.path) && !inv.files.count(e.path))
          problems.push_back(e.path + ": listed in " + file + " but missing from the bag");
      }
      for (const auto& [path, f] : inv.files)
        if (isPayload(path) && !listed.count(path))
          problems.push_back(path + ": in the payload but not listed in " + file);
    }
    for (const Manifest& m : tagManifests) {
      std::set<std::string> listed;
      for (const ManifestEntry& e : m.entries) {
        listed.insert(e.path);
        if (!isPayload(e.path) && !inv.files.count(e.path))
          problems.push_back(e.path + ": listed in tagmanifest-" + m.algorithm +
                             ".txt but missing from the bag");
      }
      // RFC 8493 lets a tagmanifest leave tag files out, but a Surrogate package lists every
      // one (metadata/ included), so an unlisted tag file was added after packaging.
      for (const auto& [path, f] : inv.files) {
        const auto name = manifestName(path);
        if (!isPayload(path) && !(name && name->first == "tagmanifest") && !listed.count(path))
          problems.push_back(path + ": a tag file not listed in tagmanifest-" + m.algorithm + ".txt");
      }
    }
    checks.push_back(makeCheck("bagit.complete", Severity::Fixity,
                               "every payload file is listed and every listed file is present",
                               "files are missing or not listed in the manifests", problems));
  }

  // Fixity per manifest.
  for (const std::vector<Manifest>* group : {&payloadManifests, &tagManifests}) {
    const bool tags = group == &tagManifests;
    for (const Manifest& m : *group) {
      std::vector<std::string> problems;
      std::size_t checked = 0;
      for (const ManifestEntry& e : m.entries) {
        const auto it = inv.files.find(e.path);
        if (it == inv.files.end() || isPayload(e.path) == tags) continue;
        ++checked;
        if (digestOf(it->second, m.algorithm) != e.checksum)
          problems.push_back(e.path + ": " + m.algorithm + " is " +
                             digestOf(it->second, m.algorithm).substr(0, 16) +
                             "..., the manifest says " + e.checksum.substr(0, 16) + "...");
      }
      const std::string file = (tags ? "tagmanifest-" : "manifest-") + m.algorithm + ".txt";
      checks.push_back(makeCheck(
          std::string(tags ? "bagit.tagfixity-" : "bagit.fixity-") + m.algorithm, Severity::Fixity,
          std::to_string(checked) + " files match " + file,
          "files differ from " + file + " (changed since packaging)", problems));
    }
  }

  // bag-info.txt and Payload-Oxum.
  if (const std::string* text = contentOf(inv, "bag-info.txt")) {
    const BagInfo info = parseBagInfo(*text);
    std::vector<std::string> problems;
    for (const std::string& p : info.problems) problems.push_back("bag-info.txt: " + p);
    checks.push_back(makeCheck("bagit.info", Severity::Invalid, "bag-info.txt is well-formed",
                               "bag-info.txt is malformed", problems));
    const auto oxum = info.values("Payload-Oxum");
    if (!oxum.empty()) {
      std::vector<std::string> oxumProblems;
      Severity severity = Severity::Fixity;
      std::uint64_t octets = 0, streams = 0;
      for (const auto& [path, f] : inv.files)
        if (isPayload(path)) { octets += f.size; ++streams; }
      const auto parsed = parseOxum(oxum.front());
      if (!parsed) {
        severity = Severity::Invalid;
        oxumProblems.push_back("bag-info.txt: Payload-Oxum \"" + oxum.front() +
                               "\" is not <bytes>.<files>");
      } else if (parsed->first != octets || parsed->second != streams) {
        oxumProblems.push_back("bag-info.txt: Payload-Oxum says " + oxum.front() +
                               ", the payload holds " + std::to_string(octets) + "." +
                               std::to_string(streams));
      }
      checks.push_back(makeCheck("bagit.payload-oxum", severity,
                                 "the payload's size and file count match Payload-Oxum " + oxum.front(),
                                 "the payload's size or file count differ from Payload-Oxum",
                                 oxumProblems));
    }
  }
}

}  // namespace surrogate::verify
