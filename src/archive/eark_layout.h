// The package as an E-ARK SIP 2.2 (https://earksip.dilcis.eu/, on CSIP 2.2,
// https://earkcsip.dilcis.eu/): `pack --layout eark DIR`.
//
// Every file of the bag packCapture writes is in the SIP, moved to the place CSIP gives it
// (sipPathOf), so that the bag can be put together again from the SIP (bagPathOf) and verified
// as any bag:
//
//   DIR/METS.xml                              the package METS (CSIP + SIP profile 2.2)
//   DIR/representations/rep1/METS.xml         the representation's METS
//   DIR/representations/rep1/data/...         the bag's data/: originals, exports, assembly
//                                             files with the carrier, finished files
//   DIR/metadata/descriptive/crm.rdf          CIDOC-CRM (the bag's metadata/crm.rdf)
//   DIR/metadata/preservation/mets.xml        METS + PREMIS (the bag's metadata/mets.xml)
//   DIR/metadata/other/bagit/...              bagit.txt, bag-info.txt, the manifests and tag
//                                             manifests, and any other tag file at the bag's root
//   DIR/schemas/...                           the bag's metadata/xsd/ (carrier, METS, PREMIS, xlink)
//   DIR/documentation/...                     the bag's metadata/mappings/ and metadata/xslt/
//                                             (mappings/, xslt/), and any other file of metadata/
//
// Each METS lists its files with MIME type, size, creation time (the packaging time) and
// SHA-256. The SIP is written under a hidden temporary name beside DIR and renamed when whole.
//
//   EarkResult r = packEark("stela12", "out/stela12", options);
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "archive/package.h"

namespace surrogate::archive {

// The SIP's METS files, which are not files of the bag.
inline constexpr const char* kSipMets = "METS.xml";
inline constexpr const char* kRepresentationMets = "representations/rep1/METS.xml";

// Where a file of the bag ("data/...", "metadata/...", "bagit.txt") is in the SIP.
std::string sipPathOf(const std::string& bagPath);
// Where a file of the SIP was in the bag; nullopt for the METS files and any path no bag file
// maps to (sipPathOf's inverse).
std::optional<std::string> bagPathOf(const std::string& sipPath);

struct EarkResult {
  PackResult pack;       // the bag the SIP was made from
  std::string objectId;  // the root METS's OBJID: DIR's folder name
  std::uint64_t files = 0;  // files in the SIP, the two METS files included
};

// Packs the capture as an E-ARK SIP in the folder `dir` (which must not exist, or be empty).
// Throws as packCapture; Error(Usage) when `dir` exists and is not an empty folder.
EarkResult packEark(const std::filesystem::path& capture, const std::filesystem::path& dir,
                    const PackOptions& options = {});

}  // namespace surrogate::archive
