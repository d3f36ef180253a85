// What `surrogate --version` prints and `surrogate info --json` carries as "version": Surrogate's
// version, where its data files are, and the libraries that decide its results, the same list
// (names, versions, roles) every run records in the carrier's header (run::softwareVersions).
#pragma once

#include <string>

namespace surrogate::cli {

// The lines of `surrogate --version`.
std::string versionText();

// {"surrogate":"0.1.0","dataFolder":"/usr/share/surrogate",
//  "libraries":[{"name":"LibRaw","version":"0.20.2","role":"camera raw decoding"},...]}
std::string versionJson();

// `objectJson` (one JSON object, as info prints) with "version": versionJson() as its last key
// (its first keys stay what scripts read first: "kind", ...).
std::string withVersion(const std::string& objectJson);

}  // namespace surrogate::cli
