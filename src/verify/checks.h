// Private to src/verify: the verifier's groups of checks, each appending to a report.
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "archive/bag_text.h"
#include "archive/folder_walk.h"
#include "archive/package_reader.h"
#include "carrier/carrier.h"
#include "verify/verify.h"

namespace surrogate::verify {

// What a folder package (an OCFL object, an E-ARK SIP) holds, walked without following links
// (archive/folder_walk.h, shared with pack --layout ocfl).
using archive::FolderWalk;
using archive::walkFolder;

// The package reader and the BagIt text formats live in src/archive; the checks use them.
using archive::extractFiles;
using archive::readBagFile;
using archive::readPackage;
using archive::BagInfo;
using archive::Declaration;
using archive::decodeTagText;
using archive::isLegacyAlgorithm;
using archive::tagEncodingSupported;
using archive::digestHexLength;
using archive::Manifest;
using archive::ManifestEntry;
using archive::manifestName;
using archive::parseBagInfo;
using archive::parseDeclaration;
using archive::parseManifest;
using archive::parseOxum;
using archive::percentDecode;
using archive::safeBagPath;
using archive::splitLines;

// At most this many "where" lines per check; the rest are counted.
constexpr std::size_t kMaxWhere = 20;

// Builds a check; `problems` empty means passed.
Check makeCheck(const std::string& name, Severity severity, const std::string& passedText,
                const std::string& failedText, const std::vector<std::string>& problems);

// The content of a file the inventory holds in memory (tag files, the carrier), or null when
// it is absent or was only hashed.
const std::string* contentOf(const Inventory& inventory, const std::string& path);

// bagit.*: RFC 8493 structure, manifests, tagmanifests, fetch.txt, Payload-Oxum,
// completeness, fixity, for any bag (tag files in the encoding bagit.txt names, manifests in
// any digest OpenSSL offers, md5 and sha1 with a warning, and what RFC 8493 tolerates with a
// warning: bag_checks.cpp, `latitude`). A Surrogate package is held to more: none of that
// latitude, and package.tags-listed.
void checkBag(const Inventory& inventory, bool surrogatePackage, std::vector<Check>& checks,
              std::vector<std::string>& warnings);

// The algorithms of the bag's manifests other than sha256 and sha512 that OpenSSL offers
// (md5, sha1, sha224, ...), whose digests readPackage computes only when asked.
std::vector<std::string> otherDigestsNeeded(const Inventory& inventory);

// carrier.*: schema and files; returns the parsed carrier when it is valid.
std::optional<carrier::Carrier> checkCarrier(const Inventory& inventory, std::vector<Check>& checks);

// Whether the bag is a Surrogate package: bag-info.txt has Surrogate-Package-Identifier, or
// the bag has data/assembly-files/carrier.xml, a file of metadata/ that packing writes, or a
// README.txt that says it was packed by Surrogate. Such a package is held to what `surrogate pack`
// writes (package.*).
bool isSurrogatePackage(const Inventory& inventory);

// The first difference between two texts, as "line N: derived \"...\", the bag has \"...\"".
std::string firstDifference(const std::string& expected, const std::string& found);

// package.readme: README.txt is the text packing writes from the carrier (archive
// package_readme.h), with the packing facts of bag-info.txt.
void checkReadme(const Inventory& inventory, const carrier::Carrier& recorded, std::vector<Check>& checks);

// metadata.ro-crate: data/ro-crate-metadata.json is what the bundled stylesheet derives from
// the carrier with the packing facts of bag-info.txt (mapping::deriveRoCrate).
void checkRoCrate(const std::filesystem::path& package, const Inventory& inventory,
                  const std::string& carrierXml, const Limits& limits, std::vector<Check>& checks);

// One warning for each document of metadata/docs/ that differs from this verifier's copy.
std::vector<std::string> documentWarnings(const Inventory& inventory);

// package.complete (every file of a Surrogate package present: fixity) and package.bundled
// (metadata/ stylesheets, schemas and tables byte-identical to this verifier's, no other tag
// file: invalid; the documents in metadata/docs/ only present, see package_checks.cpp).
void checkCompleteness(const Inventory& inventory, std::vector<Check>& checks);

// package.info: the fields of bag-info.txt that Surrogate writes are what packing the carrier
// gives (identifier = urn:sha256 of the carrier, its header metadata, dates, Bag-Size); any
// other field is the holder's, appended to `holderFields` (Report::holderFields).
void checkPackageInfo(const Inventory& inventory, const std::optional<carrier::Carrier>& recorded,
                      std::vector<Check>& checks,
                      std::vector<std::pair<std::string, std::string>>& holderFields);

// carrier.steps: every recorded step can run in this build as recorded (known component and
// version, parameters its parser accepts, outputs inside assembly-files/ or finished-files/).
// Returns whether they all can.
bool checkSteps(const carrier::Carrier& recorded, std::vector<Check>& checks);

// metadata.*: METS, CRM, and re-derivation from the carrier (compared by digest; the bag's
// texts are read again from `package` only when a check needs them). With
// `dropPayloadEntries` (nothing after it needs them: no re-execution), the inventory's entries
// under data/ but the carrier are erased, and the texts of the payload manifests and of the
// carrier let go, as soon as what the stylesheets need is taken from them (see
// carrier_checks.cpp): the inventory is then no longer complete.
void checkMetadata(const std::filesystem::path& package, Inventory& inventory,
                   const std::string* carrierXml, const Limits& limits, std::vector<Check>& checks,
                   bool dropPayloadEntries = false);

// reexecute.*: extract, replay the process list, compare.
void checkReexecution(const std::filesystem::path& package, const Inventory& inventory,
                      const carrier::Carrier& recorded, const VerifyOptions& options,
                      Report& report);

inline constexpr const char* kCarrierPath = "data/assembly-files/carrier.xml";

}  // namespace surrogate::verify
