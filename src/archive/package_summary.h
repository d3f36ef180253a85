// PackageSummary: what a package (a bag folder, .tar or .zip) holds, by role, as plain data
// for `surrogate info` and any page that shows a package.
//
//   const archive::PackageSummary s = archive::describePackage("stela.zip");
//   for (const archive::RoleTotal& r : s.roles) std::cout << r.role << " " << r.files << "\n";
//
// The package is read as the verifier reads it (readPackage: no trust in the archive), but
// nothing is verified: the sizes are those the package declares.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "archive/package_reader.h"
#include "carrier/carrier.h"

namespace surrogate::archive {

struct RoleTotal {
  std::string role;  // "originals", "exports", "assembly", "carrier", "results", "prior work",
                     // "other payload", "RO-Crate metadata" (data/ro-crate-metadata.json);
                     // in another tool's bag "payload"; "metadata", "bag files"
  std::size_t files = 0;
  std::uint64_t bytes = 0;
};

struct PackageSummary {
  std::string format;      // "directory", "tar", "zip" (readPackage's Inventory::kind)
  bool surrogate = false;  // a Surrogate package (its identifier in bag-info.txt, or a carrier)
  std::vector<std::pair<std::string, std::string>> bagInfo;  // in order, labels as written
  std::vector<std::string> manifests;                        // manifest-sha256.txt, ...
  std::vector<RoleTotal> roles;                              // those present, in the order above
  std::vector<std::pair<std::string, std::uint64_t>> results;  // finished files (path in data/)
  std::size_t files = 0;
  std::uint64_t bytes = 0;
  std::optional<carrier::Carrier> carrier;  // data/assembly-files/carrier.xml, when readable
  std::string carrierProblem;              // why it is not, when the package has one

  // The first value of a bag-info.txt label (case-insensitive), "" when absent.
  std::string bagInfoValue(const std::string& label) const;
};

// Throws Error as readPackage does for a package it refuses.
PackageSummary describePackage(const std::filesystem::path& package, const Limits& limits = Limits{});

// What a package's file (a path relative to the bag root) is for: in a Surrogate package the
// carrier's role for the files it records (`carrierRoles`: carrier path -> role), else the
// package's layout (docs/package.md); in another tool's bag, "payload" or "bag files".
std::string packageRole(const std::string& path, const std::map<std::string, std::string>& carrierRoles,
                        bool surrogate);

}  // namespace surrogate::archive
