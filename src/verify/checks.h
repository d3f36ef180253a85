// The verifier's groups of checks, each appending to a report (internal to src/verify).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "verify/package.h"
#include "verify/verify.h"

namespace surrogate::verify::internal {

// At most this many "where" lines per check; the rest are counted.
constexpr std::size_t kMaxWhere = 20;

// Builds a check; `problems` empty means passed.
Check makeCheck(const std::string& name, Severity severity, const std::string& passedText,
                const std::string& failedText, const std::vector<std::string>& problems);

// bagit.*: RFC 8493 structure, manifests, tagmanifests, Payload-Oxum, completeness, fixity.
void checkBag(const Inventory& inventory, std::vector<Check>& checks);

// carrier.*: schema and files; returns the parsed carrier when it is valid.
std::optional<carrier::Carrier> checkCarrier(const Inventory& inventory, std::vector<Check>& checks);

// metadata.*: METS, CRM, and re-derivation from the carrier.
void checkMetadata(const Inventory& inventory, const std::string* carrierXml,
                   std::vector<Check>& checks);

// reexecute.*: extract, replay the process list, compare.
void checkReexecution(const std::filesystem::path& package, const Inventory& inventory,
                      const carrier::Carrier& recorded, const VerifyOptions& options,
                      Report& report);

inline constexpr const char* kCarrierPath = "data/assembly-files/carrier.xml";

}  // namespace surrogate::verify::internal
