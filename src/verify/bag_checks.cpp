#include <algorithm>
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
  static const std::string none;
  if (algorithm == "sha256") return f.sha256;
  if (algorithm == "sha512") return f.sha512;
  const auto it = f.otherDigests.find(algorithm);
  return it == f.otherDigests.end() ? none : it->second;
}

// What RFC 8493 allows or advises against and bagit-python accepts (whitespace before a
// bag-info colon, a reserved label repeated, md5sum's '*' marker, a 0.97 manifest listing a
// file twice with the same checksum): a warning in a bag another tool made, a problem in a
// Surrogate package, which is held to what `surrogate pack` writes.
void latitude(const std::string& file, const std::vector<std::string>& departures,
              bool surrogatePackage, std::vector<std::string>& problems,
              std::vector<std::string>& warnings) {
  for (const std::string& d : departures) {
    if (surrogatePackage)
      problems.push_back(file + ": " + d + "; `surrogate pack` never writes this");
    else
      warnings.push_back(file + ": " + d + "; accepted in a bag another tool made");
  }
}

// The parsed manifests and tag manifests of a bag.
struct Manifests {
  std::vector<Manifest> payload, tags;
};

// What bagit.txt declares: the version (1.0 when it names none) and the tag files' encoding
// (UTF-8 when it names none).
struct Declared {
  std::string version, encoding;
};

// bagit.declaration.
Declared checkDeclaration(const Inventory& inv, std::vector<Check>& checks) {
  std::vector<std::string> problems;
  std::string version = "1.0", encoding = "UTF-8";
  const std::string* text = contentOf(inv, "bagit.txt");
  if (!text) {
    problems.push_back("bagit.txt: missing; this is not a BagIt bag");
  } else {
    const Declaration d = parseDeclaration(*text);
    for (const std::string& p : d.problems) problems.push_back("bagit.txt: " + p);
    if (!d.version.empty()) version = d.version;
    if (!d.encoding.empty() && tagEncodingSupported(d.encoding)) encoding = d.encoding;
  }
  checks.push_back(makeCheck("bagit.declaration", Severity::Invalid,
                             "bagit.txt declares BagIt " + version + " with " + encoding +
                                 " tag files",
                             "bagit.txt is missing or malformed", problems));
  return {version, encoding};
}

// A tag file's text in UTF-8 (RFC 8493: tag files are in the encoding bagit.txt names), or
// nullopt with a problem when it cannot be decoded.
std::optional<std::string> tagText(const std::string& path, const std::string& bytes,
                                   const std::string& encoding, std::vector<std::string>& problems) {
  std::string why;
  std::optional<std::string> text = decodeTagText(bytes, encoding, &why);
  if (!text) problems.push_back(path + ": cannot be read as " + encoding + ": " + why);
  return text;
}

// Where a manifest's entries may point: payload manifests list payload only, tag manifests
// tag files only and never a tag manifest.
void checkEntryKinds(const std::string& path, const std::string& kind, const Manifest& m,
                     std::vector<std::string>& structure) {
  for (const ManifestEntry& e : m.entries) {
    const std::string where = path + " line " + std::to_string(e.line) + ": " + e.path;
    if (kind == "manifest" && !isPayload(e.path))
      structure.push_back(where + " is outside data/; a payload manifest lists payload only");
    if (kind == "tagmanifest" && isPayload(e.path))
      structure.push_back(where + " is payload; a tagmanifest lists tag files only");
    if (kind == "tagmanifest" && manifestName(e.path) && manifestName(e.path)->first == "tagmanifest")
      structure.push_back(where + ": a tagmanifest must not list a tagmanifest");
  }
}

// Parses every manifest and tag manifest; what is malformed goes to `structure`, md5 and sha1
// manifests to `warnings`, and what RFC 8493 leaves latitude for to either (`latitude`). A path
// listed twice with the same checksum is a problem in BagIt 1.0 (RFC 8493) and latitude in
// 0.97, whose tools wrote such manifests.
Manifests parseManifests(const Inventory& inv, const Declared& declared, bool surrogatePackage,
                         std::vector<std::string>& structure, std::vector<std::string>& warnings) {
  const std::string& encoding = declared.encoding;
  Manifests out;
  for (const auto& [path, file] : inv.files) {
    const auto name = manifestName(path);
    if (!name) continue;
    const std::size_t hex = digestHexLength(name->second);
    if (hex == 0) {
      structure.push_back(path + ": algorithm \"" + name->second.substr(0, 40) +
                          "\" is not one this verifier accepts (sha256, sha512, and in bags "
                          "made by other tools any other digest OpenSSL offers: sha224, sha384, "
                          "md5, sha1, ...)");
      continue;
    }
    // A Surrogate package is held to what `pack` writes: the other digests OpenSSL offers are
    // for bags other tools made (md5 and sha1 were accepted in any bag before, and still are).
    if (surrogatePackage && name->second != "sha256" && name->second != "sha512" &&
        name->second != "md5" && name->second != "sha1") {
      structure.push_back(path + ": algorithm \"" + name->second + "\" in a Surrogate package, "
                          "whose manifests `surrogate pack` writes in sha256 and sha512");
      continue;
    }
    if (!file.content) {
      structure.push_back(path + ": too large to be a manifest");
      continue;
    }
    if (isLegacyAlgorithm(name->second))
      warnings.push_back(path + ": " + name->second + " is accepted for a bag made by another "
                         "tool (RFC 8493 section 2.4), but it no longer resists a deliberate "
                         "change; when the bag is next re-made, use sha256 or sha512");
    const std::optional<std::string> text = tagText(path, *file.content, encoding, structure);
    if (!text) continue;
    Manifest m = parseManifest(*text, name->second, hex);
    for (const std::string& p : m.problems) structure.push_back(path + ": " + p);
    latitude(path, m.departures, surrogatePackage, structure, warnings);
    if (declared.version == "1.0") {
      for (const std::string& r : m.repeats)
        structure.push_back(path + ": " + r + " (invalid in BagIt 1.0, RFC 8493)");
    } else {
      latitude(path, m.repeats, surrogatePackage, structure, warnings);
    }
    checkEntryKinds(path, name->first, m, structure);
    (name->first == "manifest" ? out.payload : out.tags).push_back(std::move(m));
  }
  if (out.payload.empty())
    structure.push_back("no payload manifest (manifest-<algorithm>.txt, e.g. manifest-sha256.txt)");
  return out;
}

// fetch.txt: its lines go to `structure` when malformed; the files it names must already be
// in the bag (this verifier never fetches), else bagit.fetch fails: the bag is incomplete.
// Returns the paths fetch.txt names.
std::set<std::string> checkFetch(const Inventory& inv, const std::string& encoding,
                                 const Manifests& manifests, std::vector<std::string>& structure,
                                 std::vector<Check>& checks) {
  std::set<std::string> named;
  const auto file = inv.files.find("fetch.txt");
  if (file == inv.files.end()) return named;
  if (!file->second.content) {
    structure.push_back("fetch.txt: too large to be a fetch file");
    return named;
  }
  const std::optional<std::string> text = tagText("fetch.txt", *file->second.content, encoding, structure);
  if (!text) return named;
  const archive::Fetch fetch = archive::parseFetch(*text);
  for (const std::string& p : fetch.problems) structure.push_back("fetch.txt: " + p);
  std::vector<std::string> absent;
  for (const archive::FetchEntry& e : fetch.entries) {
    const std::string where = "fetch.txt line " + std::to_string(e.line) + ": " + e.path;
    if (!isPayload(e.path)) {
      structure.push_back(where + " is outside data/");
      continue;
    }
    named.insert(e.path);
    for (const Manifest& m : manifests.payload) {
      const bool listed = std::any_of(m.entries.begin(), m.entries.end(),
                                      [&](const ManifestEntry& x) { return x.path == e.path; });
      if (!listed)
        structure.push_back(where + " is not listed in manifest-" + m.algorithm +
                            ".txt; every file to fetch must be");
    }
    if (!inv.files.count(e.path))
      absent.push_back(e.path + ": to be fetched from " + e.url.substr(0, 200) +
                       (e.length ? " (" + std::to_string(*e.length) + " bytes)" : std::string()));
  }
  if (!absent.empty())
    absent.push_back("this verifier never fetches: fetch the files into the bag, then verify it again");
  checks.push_back(makeCheck("bagit.fetch", Severity::Fixity,
                             "every file fetch.txt names is already in the bag",
                             "the bag is incomplete: files fetch.txt names are not in it", absent));
  return named;
}

// bagit.complete: every payload file in every payload manifest, every listed file present
// (files still to be fetched are bagit.fetch's). For a Surrogate package, package.tags-listed:
// every tag file in every tag manifest (RFC 8493 lets a bag leave tag files out, but `surrogate
// pack` lists every one, metadata/ included, so an unlisted tag file was added after packing).
void checkListed(const Inventory& inv, const Manifests& manifests,
                 const std::set<std::string>& toFetch, bool surrogatePackage,
                 std::vector<Check>& checks) {
  std::vector<std::string> problems, unlistedTags;
  for (const Manifest& m : manifests.payload) {
    std::set<std::string> listed;
    const std::string file = "manifest-" + m.algorithm + ".txt";
    for (const ManifestEntry& e : m.entries) {
      listed.insert(e.path);
      if (isPayload(e.path) && !inv.files.count(e.path) && !toFetch.count(e.path))
        problems.push_back(e.path + ": listed in " + file + " but missing from the bag");
    }
    for (const auto& [path, f] : inv.files)
      if (isPayload(path) && !listed.count(path))
        problems.push_back(path + ": in the payload but not listed in " + file);
  }
  for (const Manifest& m : manifests.tags) {
    std::set<std::string> listed;
    for (const ManifestEntry& e : m.entries) {
      listed.insert(e.path);
      if (!isPayload(e.path) && !inv.files.count(e.path))
        problems.push_back(e.path + ": listed in tagmanifest-" + m.algorithm +
                           ".txt but missing from the bag");
    }
    for (const auto& [path, f] : inv.files) {
      const auto name = manifestName(path);
      if (!isPayload(path) && !(name && name->first == "tagmanifest") && !listed.count(path))
        unlistedTags.push_back(path + ": a tag file not listed in tagmanifest-" + m.algorithm + ".txt");
    }
  }
  checks.push_back(makeCheck("bagit.complete", Severity::Fixity,
                             "every payload file is listed and every listed file is present",
                             "files are missing or not listed in the manifests", problems));
  if (surrogatePackage)
    checks.push_back(makeCheck("package.tags-listed", Severity::Fixity,
                               "every tag file is listed in every tag manifest",
                               "tag files are not listed in the tag manifests (added after packing?)",
                               unlistedTags));
}

// bagit.fixity-<algorithm> and bagit.tagfixity-<algorithm>: one check per manifest.
void checkFixity(const Inventory& inv, const Manifests& manifests, std::vector<Check>& checks) {
  for (const std::vector<Manifest>* group : {&manifests.payload, &manifests.tags}) {
    const bool tags = group == &manifests.tags;
    for (const Manifest& m : *group) {
      std::vector<std::string> problems;
      std::size_t checked = 0;
      for (const ManifestEntry& e : m.entries) {
        const auto it = inv.files.find(e.path);
        if (it == inv.files.end() || isPayload(e.path) == tags) continue;
        ++checked;
        const std::string& actual = digestOf(it->second, m.algorithm);
        if (actual != e.checksum)
          problems.push_back(e.path + ": " + m.algorithm + " is " + actual.substr(0, 16) +
                             "..., the manifest says " + e.checksum.substr(0, 16) + "...");
      }
      const std::string file = (tags ? "tagmanifest-" : "manifest-") + m.algorithm + ".txt";
      checks.push_back(makeCheck(
          std::string(tags ? "bagit.tagfixity-" : "bagit.fixity-") + m.algorithm, Severity::Fixity,
          std::to_string(checked) + " files match " + file,
          "files differ from " + file + " (changed since packaging)", problems));
    }
  }
}

// bagit.info (bag-info.txt well-formed) and bagit.payload-oxum.
void checkBagInfo(const Inventory& inv, const std::string& encoding, bool surrogatePackage,
                  std::vector<Check>& checks, std::vector<std::string>& warnings) {
  const std::string* bytes = contentOf(inv, "bag-info.txt");
  if (!bytes) return;
  std::vector<std::string> problems;
  const std::optional<std::string> text = tagText("bag-info.txt", *bytes, encoding, problems);
  const BagInfo info = parseBagInfo(text.value_or(""));
  if (text) {
    for (const std::string& p : info.problems) problems.push_back("bag-info.txt: " + p);
    latitude("bag-info.txt", info.departures, surrogatePackage, problems, warnings);
  }
  checks.push_back(makeCheck("bagit.info", Severity::Invalid, "bag-info.txt is well-formed",
                             "bag-info.txt is malformed", problems));
  const auto oxum = info.values("Payload-Oxum");
  if (oxum.empty()) return;
  std::vector<std::string> oxumProblems;
  Severity severity = Severity::Fixity;
  std::uint64_t octets = 0, streams = 0;
  for (const auto& [path, f] : inv.files)
    if (isPayload(path)) { octets += f.size; ++streams; }
  // Given more than once (a warning above, or a problem in a Surrogate package), the first
  // is the one checked.
  const std::string& value = oxum.front();
  const auto parsed = parseOxum(value);
  if (!parsed) {
    severity = Severity::Invalid;
    oxumProblems.push_back("bag-info.txt: Payload-Oxum \"" + value + "\" is not <bytes>.<files>");
  } else if (parsed->first != octets || parsed->second != streams) {
    oxumProblems.push_back("bag-info.txt: Payload-Oxum says " + value + ", the payload holds " +
                           std::to_string(octets) + "." + std::to_string(streams));
  }
  checks.push_back(makeCheck("bagit.payload-oxum", severity,
                             "the payload's size and file count match Payload-Oxum " + oxum.front(),
                             "the payload's size or file count differ from Payload-Oxum",
                             oxumProblems));
}

}  // namespace

std::vector<std::string> otherDigestsNeeded(const Inventory& inv) {
  std::set<std::string> names;
  for (const auto& [path, file] : inv.files) {
    const auto name = manifestName(path);
    if (name && name->second != "sha256" && name->second != "sha512" &&
        digestHexLength(name->second) != 0)
      names.insert(name->second);
  }
  return {names.begin(), names.end()};
}

void checkBag(const Inventory& inv, bool surrogatePackage, std::vector<Check>& checks,
              std::vector<std::string>& warnings) {
  const Declared declared = checkDeclaration(inv, checks);
  const std::string& encoding = declared.encoding;
  std::vector<std::string> structure;
  const Manifests manifests = parseManifests(inv, declared, surrogatePackage, structure, warnings);
  // bagit.fetch follows bagit.manifests, which holds the malformed lines of fetch.txt.
  std::vector<Check> fetchCheck;
  const std::set<std::string> toFetch = checkFetch(inv, encoding, manifests, structure, fetchCheck);
  checks.push_back(makeCheck("bagit.manifests", Severity::Invalid,
                             "manifests and tagmanifests are well-formed and name only safe paths",
                             "a manifest or tagmanifest is malformed", structure));
  for (Check& c : fetchCheck) checks.push_back(std::move(c));
  checkListed(inv, manifests, toFetch, surrogatePackage, checks);
  checkFixity(inv, manifests, checks);
  checkBagInfo(inv, encoding, surrogatePackage, checks, warnings);
}

}  // namespace surrogate::verify
