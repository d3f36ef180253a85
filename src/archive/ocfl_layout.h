// The package as an OCFL 1.1 object (https://ocfl.io/1.1/spec/): `pack --layout ocfl DIR`.
//
// The object holds the whole bag packCapture writes (bagit.txt, bag-info.txt, the manifests
// and tag manifests, data/, metadata/) as the logical state of each version, so that the bag
// a repository takes out of the head version is the bag `pack` would have written:
//
//   DIR/0=ocfl_object_1.1              "ocfl_object_1.1\n"
//   DIR/inventory.json                 digestAlgorithm sha512 (the bag's manifest-sha512.txt
//   DIR/inventory.json.sha512            gives the same digests), id, head, manifest, versions
//   DIR/v1/inventory.json (+ .sha512)  the inventory as it was when v1 was written
//   DIR/v1/content/bagit.txt, data/..., metadata/...
//   DIR/v2/content/bag-info.txt, ...   only what v1 does not already hold (the manifest points
//                                      unchanged files at their v1 copy)
//
// The object's id is the capture identifier (captureObjectId): packing the same capture again adds a
// version, packing another capture into DIR is refused. A version is written complete under a
// temporary name beside DIR, renamed to DIR/vN, and only then is the root inventory replaced
// (then its sidecar): the earlier versions are never touched, and a pack killed half-way
// leaves either the object as it was (plus a hidden temporary beside it that the next pack
// removes) or a finished vN whose root inventory the next pack completes.
//
//   OcflResult r = packOcfl("stela12", "repo/stela12", options);   // v1, then v2, ...
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "archive/package.h"

namespace surrogate::carrier {
struct Carrier;
}

namespace surrogate::archive {

// The capture identifier (captureIdentifier, package.h: "urn:surrogate:capture:<SHA-256 of the
// carrier's first file>"), which the bag holds in bag-info.txt (Surrogate-Capture-Identifier),
// README.txt, mets.xml, crm.rdf and the RO-Crate: every package of one capture is a version of
// one object, and another capture has another id. An object made by an earlier Surrogate, whose
// id is the SHA-256 of the list of the capture's evidence, keeps that id (OCFL ids never change).
std::string captureObjectId(const carrier::Carrier& c);

struct OcflResult {
  PackResult pack;           // the bag, as packed into the new version (before deduplication)
  std::string objectId;
  std::string version;       // "v1", "v2", ...; the head already there when `unchanged`
  bool created = false;      // a new object (v1)
  bool unchanged = false;    // the head version already holds this very bag: nothing written
  std::uint64_t newFiles = 0, newBytes = 0;  // content written into the new version
  std::uint64_t reusedFiles = 0;             // files of the state whose content an earlier version holds
  std::vector<std::string> notes;            // leftovers removed, an interrupted pack completed
};

// Packs the capture as a new version of the OCFL object at `dir` (created when `dir` does
// not exist or is an empty folder). An existing object is first checked as verify checks it
// (archive/ocfl_object.h: no link anywhere, safe paths, its sidecars, its versions, every
// content file's digest), so that a file reused from an earlier version is the object's own
// with the digest its manifest gives. Throws Error(Input) for a name no package can have
// (checkPackageName); Error(Usage) when `dir` holds something else than an OCFL 1.1 object, an
// object that fails those checks (the message names the first problem and the verify
// command; nothing is written), or the object of another capture (another id);
// PayloadChanged as packCapture. `options.replace` is not used (an object is only added to).
OcflResult packOcfl(const std::filesystem::path& capture, const std::filesystem::path& dir,
                    const PackOptions& options = {});

}  // namespace surrogate::archive
