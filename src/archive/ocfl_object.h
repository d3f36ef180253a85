// An OCFL 1.1 object (https://ocfl.io/1.1/spec/) checked without trusting it: the checks
// `verify` reports as ocfl.* (verify/ocfl_checks.h) and the ones `pack --layout ocfl` makes
// before it adds a version to an object (ocfl_layout.h), so that pack never builds on an
// object verify would refuse: never reuses a content file whose digest it has not checked, nor
// one that a symbolic link or a path like "../../etc/passwd" places outside the object.
//
//   read          the object's folder holds regular files and folders only (no link)
//   declaration   one declaration, 0=ocfl_object_1.1 (or 1.0) holding its own name
//   inventory     the root inventory.json is an OCFL inventory: id, type, digestAlgorithm
//                 sha512 or sha256, head the last of versions v1..vN, a manifest of safe
//                 content paths under those versions, each version's created and state, every
//                 state digest in the manifest, safe logical paths
//   sidecar       inventory.json.<algorithm> names the root inventory's digest
//   versions      every version folder is there with an inventory its sidecar names, the
//                 head's identical to the root's, each earlier one saying of the versions up to
//                 it what the root says; no other file or folder at the root
//   complete      every content path of the manifest is a file, every file of a version's
//                 content is in the manifest
//   fixity        every content file has the digest the manifest gives it
//
//   const OcflObjectCheck c = checkOcflObject("repo/stela12");
//   if (!c.sound()) refuse(c.firstProblem());
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "archive/folder_walk.h"

namespace surrogate::archive {

// The largest inventory, sidecar or declaration file the checks read, in bytes: a file larger
// than this is a problem, never read whole (an inventory of 10,000 versions of a Surrogate bag
// is about 2 MB; parsed, JSON takes several times its size in memory).
inline constexpr std::uintmax_t kMaxOcflInventoryBytes = 64u << 20;

// A root inventory as read (parseOcflInventory): what the checks, verify's assembly of the
// head version's bag and pack's reuse of content need. Paths are as the inventory gives them,
// each checked safe (archive::safeBagPath) and, for content paths, under a listed version.
struct OcflInventory {
  std::string text, id, algorithm, head, contentDirectory = "content";
  std::vector<std::string> versions;                                 // v1 .. vN, in order
  std::map<std::string, std::string> digestOfContent;                // content path -> digest
  std::map<std::string, std::vector<std::string>> manifest;          // digest -> content paths
  std::map<std::string, std::map<std::string, std::string>> states;  // version -> logical path -> digest
};

// The inventory in `text` of an object declared OCFL `declared` ("1.1" or "1.0"), or nothing
// with one sentence per problem appended to `problems` ("inventory.json: ...").
std::optional<OcflInventory> parseOcflInventory(const std::string& text, const std::string& declared,
                                                std::vector<std::string>& problems);

// The digest a sidecar file names ("<digest> inventory.json"), lower case; "" when not of that form.
std::string ocflSidecarDigest(const std::string& text);
// The number of a version folder's name "vN" or zero-padded "v00N"; 0 when not of that form.
int ocflVersionNumber(const std::string& name);

// The checks above, each with its problems (empty: passed), in the order they are made. A
// check that cannot be made leaves the later ones unmade: no declaration, no inventory.
struct OcflObjectCheck {
  FolderWalk walk;                        // its problems are the read check's
  std::string declared;                   // "1.1" or "1.0"; "" when the object declares neither
  std::vector<std::string> declaration;
  bool inventoryMissing = false;          // no root inventory.json (a damaged object, not a malformed one)
  std::vector<std::string> inventoryProblems;
  std::optional<OcflInventory> inventory;
  std::vector<std::string> sidecar, versions, complete, fixity;

  // Every problem of every check, in order.
  std::vector<std::string> problems() const;
  bool sound() const { return problems().empty(); }
};

struct OcflCheckOptions {
  bool contentDigests = true;  // the fixity check (reads every content file once)
  // While digesting: a fraction of the content files done.
  std::function<void(double)> progress;
};

OcflObjectCheck checkOcflObject(const std::filesystem::path& object, const OcflCheckOptions& options = {});

}  // namespace surrogate::archive
