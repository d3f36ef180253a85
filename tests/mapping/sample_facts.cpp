#include "sample_facts.h"

#include <algorithm>
#include <vector>

#include "core/digest.h"

namespace fs = std::filesystem;

namespace samplefacts {

surrogate::mapping::PackageFacts of(const fs::path& capture, const std::string& carrierXml) {
  surrogate::mapping::PackageFacts facts;
  facts.packageId = "urn:sha256:" + surrogate::sha256Hex(carrierXml);
  facts.packagingTime = "2026-01-03T00:00:00Z";
  facts.softwareAgent = "Surrogate 0.1.0";
  std::vector<std::string> paths;
  for (auto it = fs::recursive_directory_iterator(capture); it != fs::recursive_directory_iterator(); ++it)
    if (it->is_regular_file()) paths.push_back(it->path().lexically_relative(capture).generic_string());
  std::sort(paths.begin(), paths.end());
  for (const std::string& p : paths) {
    const surrogate::FileDigests d = surrogate::digestFile(capture / p, true);
    facts.payload.push_back({"data/" + p, d.size, d.sha256, d.sha512});
  }
  return facts;
}

}  // namespace samplefacts
