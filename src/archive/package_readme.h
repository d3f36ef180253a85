// README.txt at the root of a package: the package explained to someone who has never heard of
// Surrogate (what the object is, who made it, what each folder holds, which program opens each
// result, how to check the package with sha256sum). Written from the carrier by packCapture and
// written again by the verifier, which compares it with the package's, so that it can never say
// something the carrier does not.
#pragma once

#include <string>

#include "carrier/carrier.h"

namespace surrogate::archive {

// Its path in the bag (a tag file, listed in the tag manifests).
inline constexpr const char* kReadmePath = "README.txt";

// What the README says besides the carrier: what bag-info.txt records of the packing, and
// whether the payload holds the HTML report (the one payload file the carrier does not list).
struct ReadmeFacts {
  std::string packageId;      // Surrogate-Package-Identifier
  std::string packagingTime;  // Surrogate-Packaging-Time
  std::string softwareAgent;  // Bag-Software-Agent
  std::string previousPackageId;  // Surrogate-Previous-Package-Identifier, or ""
  std::string baseUri;            // Surrogate-Base-URI, or ""
  bool hasReport = false;
};

// The README's text: UTF-8, lines of at most 78 characters where words allow, LF line ends.
// Deterministic: the same carrier and facts give the same bytes.
std::string packageReadme(const carrier::Carrier& c, const ReadmeFacts& facts);

// The documents packCapture bundles in metadata/docs/ ("docs/formats.md", ...: paths under
// the resource folder, core/resources.h): the file formats of the results, the mathematics,
// the carrier and the package explained.
std::vector<std::string> bundledDocuments();

}  // namespace surrogate::archive
