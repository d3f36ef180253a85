// A capture folder packed as an archival package: a BagIt bag (bag.h) whose payload is the
// capture (originals, exports, assembly files with the carrier, finished files) and whose tag
// files carry the standard metadata derived from the carrier (metadata/crm.rdf, mets.xml) and
// the stylesheets, schemas and mapping tables that derive and explain it.
//
//   Bag layout (DESIGN.md):
//     data/original-captures/...   data/jpeg-exports/...   data/<name>.lp
//     data/assembly-files/carrier.xml, lights.lp, overlays
//     data/finished-files/...      (.ptm, .rti, normals, previews, report.html, ...)
//     metadata/crm.rdf  metadata/mets.xml
//     metadata/xslt/*.xsl  metadata/xsd/*.xsd  metadata/mappings/*.md
//
//   CarrierState s = checkCarrier(capture);       // cheap: no file is hashed
//   if (!s.complete) runThePipeline();
//   PackResult r = packCapture(capture, "stela.zip", {});
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "archive/bag.h"

namespace surrogate::archive {

// Whether a capture has a carrier that can be packed as it is: assembly-files/carrier.xml
// exists and is valid, every step has a completed result, and every recorded file exists with
// its recorded size. (Hashes are compared while packing, where every file is read anyway.)
struct CarrierState {
  bool complete = false;
  std::string reason;  // why not, in a sentence
};
CarrierState checkCarrier(const std::filesystem::path& capture);

// The payload of a capture: every file under original-captures/, raw-images/, jpeg-exports/,
// assembly-files/ and finished-files/, the .lp files at its top, and every file the carrier
// lists; with the carrier's SHA-256 as the expected digest where it has one.
std::vector<PayloadSource> capturePayload(const std::filesystem::path& capture);

struct PackOptions {
  std::function<void(std::uint64_t, std::uint64_t)> progress;  // payload bytes done, in all
};

struct PackResult {
  BagResult bag;
  std::string packageId;      // "urn:sha256:<SHA-256 of the carrier>"
  std::string packagingTime;  // xs:dateTime
};

// Packs the capture into `out` (folder, .tar or .zip by its name). Throws PayloadChanged if a
// file no longer matches the carrier (run the pipeline again), Error otherwise.
PackResult packCapture(const std::filesystem::path& capture, const std::filesystem::path& out,
                       const PackOptions& options = {});

}  // namespace surrogate::archive
