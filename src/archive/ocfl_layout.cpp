// The package as an OCFL 1.1 object: a bag packed into a new version folder, deduplicated
// against the object's manifest, then put in place (ocfl_layout.h says in what order and why).
// nlohmann's JSON reads and writes the inventories (sorted keys: the same object gives the
// same bytes).
#include "archive/ocfl_layout.h"

#include <algorithm>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "archive/ocfl_object.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/text.h"
#include "core/version.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace surrogate::archive {

namespace {

constexpr const char* kStep = "packing (OCFL)";
constexpr const char* kNamaste = "0=ocfl_object_1.1";
constexpr const char* kInventoryType = "https://ocfl.io/1.1/spec/#inventory";

std::string sha512Of(const std::string& bytes) {
  MultiDigest d({DigestAlgorithm::Sha512});
  d.update(bytes.data(), bytes.size());
  return d.hex(DigestAlgorithm::Sha512);
}

std::string sidecarText(const std::string& inventory) { return sha512Of(inventory) + " inventory.json\n"; }

// An object pack does not add to: damaged, edited, or holding what could make pack reuse a file
// that is not the object's own (a link, a path out of it). Exit 2, as verify's refusal of an
// invalid package, with the command that lists every problem; nothing has been written.
[[noreturn]] void refuseObject(const fs::path& dir, const std::string& why) {
  throw Error(ErrorKind::Usage, escapedText(dir.string()), kStep,
              escapedText(why) + "; pack adds a version only to a sound object and wrote nothing: run `surrogate verify " +
                  shellWord(dir.string()) + "` to see every problem, then restore the object from a copy or pack into a new folder");
}

// Refuses an inventory text whose paths or structure verify would refuse, before pack writes
// anything from it (the root inventory or its sidecar, completing a killed pack).
void requireSafeInventory(const fs::path& dir, const std::string& text) {
  std::vector<std::string> problems;
  if (!parseOcflInventory(text, "1.1", problems))
    refuseObject(dir, problems.empty() ? "its inventory cannot be read" : problems.front());
}

// The whole object checked as verify checks it, every content file's digest included: after
// this, every copy pack may reuse is the object's own file with the digest its manifest gives.
void requireSoundObject(const fs::path& dir) {
  const OcflObjectCheck c = checkOcflObject(dir);
  const std::vector<std::string> problems = c.problems();
  if (!problems.empty())
    refuseObject(dir, problems.front() +
                          (problems.size() == 2 ? std::string(" (and one more problem)")
                           : problems.size() > 2 ? " (and " + std::to_string(problems.size() - 1) + " more problems)"
                                                 : std::string()));
  if (c.inventory->contentDirectory != "content")
    throw Error(ErrorKind::Usage, escapedText(dir.string()), kStep,
                "keeps its content in \"" + escapedText(c.inventory->contentDirectory) +
                    "\" folders; Surrogate adds versions to objects that use content/ only: pack into a new folder");
}

// A regular file (not a link) no larger than an inventory may be (kMaxOcflInventoryBytes), read.
bool readIfFile(const fs::path& path, std::string& out) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec)) || fs::file_size(path, ec) > kMaxOcflInventoryBytes || ec)
    return false;
  out = readFile(path, kStep);
  return true;
}

// A folder, not a link to one: what completing a killed pack may read an inventory from.
bool isRealFolder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(fs::symlink_status(path, ec));
}

// An inventory's text whose sidecar names its digest; false when either is missing or they
// differ.
bool matchedInventory(const fs::path& folder, std::string& text) {
  std::string sidecar;
  return readIfFile(folder / "inventory.json", text) &&
         readIfFile(folder / "inventory.json.sha512", sidecar) && ocflSidecarDigest(sidecar) == sha512Of(text);
}

// "vN" with the zero padding of `like` ("v003" -> "v004"; "v3" -> "v4").
std::string versionName(int n, const std::string& like) {
  std::string digits = std::to_string(n);
  if (like.size() > 2 && like[1] == '0' && digits.size() < like.size() - 1)
    digits.insert(0, like.size() - 1 - digits.size(), '0');
  return "v" + digits;
}

json parseInventory(const std::string& text, const fs::path& file) {
  json inv;
  try {
    inv = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(ErrorKind::Usage, escapedText(file.string()), kStep,
                std::string("is not valid JSON (") + e.what() + "); run `surrogate verify` on the object");
  }
  const bool shaped = inv.is_object() && inv.contains("id") && inv["id"].is_string() &&
                      inv.contains("head") && inv["head"].is_string() &&
                      inv.contains("manifest") && inv["manifest"].is_object() &&
                      inv.contains("versions") && inv["versions"].is_object() &&
                      inv.contains("digestAlgorithm") && inv["digestAlgorithm"].is_string() &&
                      ocflVersionNumber(inv["head"].get<std::string>()) > 0;
  if (!shaped)
    throw Error(ErrorKind::Usage, escapedText(file.string()), kStep,
                "is not an OCFL inventory (id, head, digestAlgorithm, manifest and versions are "
                "required); run `surrogate verify` on the object");
  if (inv["digestAlgorithm"] != "sha512")
    throw Error(ErrorKind::Usage, escapedText(file.string()), kStep,
                "uses digestAlgorithm " + inv["digestAlgorithm"].get<std::string>() +
                    "; Surrogate adds versions to sha512 objects only: pack into a new folder");
  return inv;
}

std::string dump(const json& j) {
  try {
    return j.dump(2) + "\n";
  } catch (const json::exception& e) {
    throw Error(ErrorKind::Internal, "inventory.json", kStep, std::string("cannot be written: ") + e.what());
  }
}

// Folders left empty by deduplication (OCFL forbids empty folders in content), deepest first;
// `root` itself too when nothing is left in it.
void removeEmptyFolders(const fs::path& root) {
  std::vector<fs::path> folders;
  for (fs::recursive_directory_iterator it(root), end; it != end; ++it)
    if (it->is_directory() && !it->is_symlink()) folders.push_back(it->path());
  std::sort(folders.begin(), folders.end(), [](const fs::path& a, const fs::path& b) {
    return a.string().size() > b.string().size();
  });
  folders.push_back(root);
  for (const fs::path& f : folders)
    if (fs::is_empty(f)) fs::remove(f);
}

// The object at `dir` as it stands: its root inventory (parsed and as text), after completing
// a pack that was killed between putting vN in place and replacing the root inventory or its
// sidecar. Throws Error when `dir` is not an OCFL 1.1 object Surrogate can add to.
struct Existing {
  json inventory;
  std::string text;
};

Existing openObject(const fs::path& dir, std::vector<std::string>& notes) {
  std::string namaste;
  if (!readIfFile(dir / kNamaste, namaste) || namaste != "ocfl_object_1.1\n") {
    std::error_code ec;
    const bool older = fs::exists(dir / "0=ocfl_object_1.0", ec);
    throw Error(ErrorKind::Usage, escapedText(dir.string()), kStep,
                older ? "is an OCFL 1.0 object; Surrogate adds versions to OCFL 1.1 objects only: pack into a new folder"
                      : "exists and is not an OCFL object (no 0=ocfl_object_1.1 file); give an empty "
                        "or new folder, or an OCFL object made by an earlier `surrogate pack --layout ocfl`");
  }
  Existing e;
  if (!readIfFile(dir / "inventory.json", e.text)) refuseObject(dir, "its inventory.json is missing, not a regular file, or larger than an inventory may be");
  std::string sidecar;
  readIfFile(dir / "inventory.json.sha512", sidecar);
  e.inventory = parseInventory(e.text, dir / "inventory.json");
  requireSafeInventory(dir, e.text);
  const std::string head = e.inventory["head"];
  if (ocflSidecarDigest(sidecar) != sha512Of(e.text)) {
    // Killed between replacing the root inventory and its sidecar: the head version holds
    // the same inventory with its own sidecar.
    std::string copy;
    if (!isRealFolder(dir / head) || !matchedInventory(dir / head, copy) || copy != e.text)
      refuseObject(dir, "inventory.json.sha512 does not name the digest of inventory.json (the inventory was edited)");
    writeFileAtomically(dir / "inventory.json.sha512", sidecarText(e.text));
    notes.push_back("completed " + (dir / "inventory.json.sha512").string() +
                    ", which a pack that did not finish left unwritten");
  }
  // Killed between putting the next version in place and replacing the root inventory.
  const std::string next = versionName(ocflVersionNumber(head) + 1, head);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir / next, ec))) {
    std::string text;
    json later;
    bool extends = isRealFolder(dir / next) && matchedInventory(dir / next, text);
    if (extends) {
      later = parseInventory(text, dir / next / "inventory.json");
      requireSafeInventory(dir, text);
      extends = later["id"] == e.inventory["id"] && later["head"] == next;
      for (const auto& [name, version] : e.inventory["versions"].items())
        extends = extends && later["versions"].contains(name) && later["versions"][name] == version;
      for (const auto& [digest, paths] : e.inventory["manifest"].items())
        extends = extends && later["manifest"].contains(digest) && later["manifest"][digest] == paths;
    }
    if (!extends) refuseObject(dir, next + "/ is a version folder the object's inventory does not list");
    writeFileAtomically(dir / "inventory.json", text);
    writeFileAtomically(dir / "inventory.json.sha512", sidecarText(text));
    notes.push_back("completed version " + next + " of " + dir.string() +
                    ", which a pack that did not finish had put in place");
    e.text = text;
    e.inventory = later;
  }
  requireSoundObject(dir);
  return e;
}

}  // namespace

std::string captureObjectId(const carrier::Carrier& c) { return captureIdentifier(c); }

namespace {
// The id objects made before the capture identifier became the object's: the SHA-256 of the
// list of the capture's evidence. Such an object keeps it (an OCFL object's id never changes).
std::string evidenceListId(const carrier::Carrier& c) {
  std::vector<std::pair<std::string, std::string>> evidence;
  for (const carrier::FileRecord& f : c.files)
    if (carrier::isEvidenceRole(f.role)) evidence.emplace_back(f.path, f.sha256);
  std::sort(evidence.begin(), evidence.end());
  std::string list;
  for (const auto& [path, sha256] : evidence) list += sha256 + "  " + path + "\n";
  return "urn:sha256:" + sha256Hex(list);
}
}  // namespace

OcflResult packOcfl(const fs::path& capture, const fs::path& given, const PackOptions& options) {
  checkPackageName(given);
  fs::path dir = given.lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  OcflResult result;
  const carrier::Carrier recorded = carrier::loadCarrier(capture / capture::kCarrierPath);
  result.objectId = captureObjectId(recorded);
  result.notes = removeStaleParts(dir);
  // A pack killed while replacing the root inventory or its sidecar leaves its temporary at
  // the object's root (".inventory.json.part-PID-N"), which OCFL does not allow there.
  for (const char* file : {"inventory.json", "inventory.json.sha512"})
    for (std::string& note : removeStaleParts(dir / file)) result.notes.push_back(std::move(note));

  std::error_code ec;
  const bool exists = fs::exists(fs::symlink_status(dir, ec));
  if (exists && !fs::is_directory(fs::symlink_status(dir, ec)))
    throw Error(ErrorKind::Usage, escapedText(dir.string()), kStep,
                "is not a folder; --layout ocfl writes an OCFL object into a folder");
  result.created = !exists || fs::is_empty(dir, ec);

  json inventory;
  int number = 1;
  std::string like = "v1";
  if (!result.created) {
    Existing e = openObject(dir, result.notes);
    inventory = std::move(e.inventory);
    if (inventory["id"] != result.objectId && inventory["id"] == evidenceListId(recorded)) {
      result.objectId = evidenceListId(recorded);
      result.notes.push_back("kept the object's id " + result.objectId + ", given by an earlier Surrogate (an OCFL "
                             "object's id never changes); objects made now take the capture identifier " +
                             captureIdentifier(recorded));
    }
    if (inventory["id"] != result.objectId)
      throw Error(ErrorKind::Usage, escapedText(dir.string()), kStep,
                  "is the OCFL object of another capture (its id is " + inventory["id"].get<std::string>() +
                      ", this capture's is " + result.objectId +
                      ": the id is the capture identifier, named from its first photograph); give another folder for this capture");
    like = inventory["head"];
    number = ocflVersionNumber(like) + 1;
  } else {
    inventory = {{"digestAlgorithm", "sha512"}, {"id", result.objectId}, {"manifest", json::object()},
                 {"type", kInventoryType}, {"versions", json::object()}};
  }
  const std::string version = versionName(number, like);
  result.version = version;

  // The new object, or the new version, under a hidden temporary name beside DIR.
  AtomicFile stage(dir);
  fs::create_directory(stage.tempPath());
  const fs::path versionFolder = result.created ? stage.tempPath() / version : stage.tempPath();
  if (result.created) fs::create_directory(versionFolder);
  PackOptions bagOptions = options;
  bagOptions.replace = false;
  result.pack = packCapture(capture, versionFolder / "content", bagOptions);

  // The version's state: every file of the bag by its SHA-512 (the payload's from packing).
  std::map<std::string, std::string> state;  // logical path -> digest
  std::map<std::string, std::uint64_t> sizes;
  for (const PayloadDigest& p : result.pack.bag.payload) {
    state[p.bagPath] = p.sha512;
    sizes[p.bagPath] = p.size;
  }
  for (const std::string& t : result.pack.bag.tagFiles) {
    const FileDigests d = digestFile(versionFolder / "content" / t, true);
    state[t] = d.sha512;
    sizes[t] = d.size;
  }

  if (!result.created) {
    std::map<std::string, std::string> head;
    for (const auto& [digest, paths] : inventory["versions"][like]["state"].items())
      for (const auto& p : paths) head[p.get<std::string>()] = digest;
    if (head == state) {
      result.unchanged = true;
      result.version = like;
      return result;  // the stage is removed with its AtomicFile
    }
  }

  json& manifest = inventory["manifest"];
  json stateJson = json::object();
  for (const auto& [path, digest] : state) {
    stateJson[digest].push_back(path);
    if (manifest.contains(digest) && !manifest[digest].empty() &&
        std::none_of(manifest[digest].begin(), manifest[digest].end(), [&](const json& p) {
          return p.get<std::string>().rfind(version + "/", 0) == 0;
        })) {
      // Held by an earlier version: that copy serves this state too.
      const std::string earlier = manifest[digest][0];
      if (!fs::is_regular_file(fs::symlink_status(dir / earlier, ec)))  // checked sound: gone since
        refuseObject(dir, earlier + " is missing, though the object's inventory lists it");
      fs::remove(versionFolder / "content" / path);
      ++result.reusedFiles;
      continue;
    }
    manifest[digest].push_back(version + "/content/" + path);
    ++result.newFiles;
    result.newBytes += sizes[path];
  }
  if (fs::is_directory(versionFolder / "content")) removeEmptyFolders(versionFolder / "content");

  json v = {{"created", result.pack.packagingTime},
            {"message", "Packed by Surrogate " + std::string(surrogateVersion()) + ": package " +
                            result.pack.packageId},
            {"state", stateJson}};
  if (!recorded.header.creators.empty()) v["user"] = {{"name", recorded.header.creators.front().name}};
  inventory["versions"][version] = v;
  inventory["head"] = version;
  const std::string text = dump(inventory);
  writeFileAtomically(versionFolder / "inventory.json", text);
  writeFileAtomically(versionFolder / "inventory.json.sha512", sidecarText(text));

  if (result.created) {
    writeFileAtomically(stage.tempPath() / kNamaste, "ocfl_object_1.1\n");
    writeFileAtomically(stage.tempPath() / "inventory.json", text);
    writeFileAtomically(stage.tempPath() / "inventory.json.sha512", sidecarText(text));
    stage.commitWithoutReplacing();
    return result;
  }
  // The version in place first, then the root inventory, then its sidecar (the order
  // openObject completes from).
  if (fs::exists(fs::symlink_status(dir / version, ec)))
    throw Error(ErrorKind::Input, (dir / version).string(), kStep,
                "appeared while this version was being written (another pack into the same object?); "
                "nothing was changed: run the pack again");
  fs::rename(stage.tempPath(), dir / version, ec);
  if (ec) throw writeError(dir / version, kStep, ec.value());
  writeFileAtomically(dir / "inventory.json", text);
  writeFileAtomically(dir / "inventory.json.sha512", sidecarText(text));
  return result;
}

}  // namespace surrogate::archive
