// Test support: reading a bag (folder, .tar or .zip) into memory and checking it the way
// bagit-python's --validate does, from RFC 8493: bagit.txt exact, every manifest entry present
// and matching (digests recomputed here with OpenSSL, independently of src/archive), no
// unlisted payload file, Payload-Oxum right, tag manifests complete and matching.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace bagcheck {

// Bag path -> content. For an archive, the single top-level folder is removed from the names
// (and reported in `top`).
struct BagFiles {
  std::map<std::string, std::string> files;
  std::string top;
  std::vector<std::string> order;  // archive members in the order stored (archives only)
};
BagFiles readBag(const std::filesystem::path& bag);

std::string sha256(const std::string& bytes);
std::string sha512(const std::string& bytes);

// Problems found, empty when the bag is valid.
std::vector<std::string> validate(const BagFiles& bag);

// The lines of a manifest as (hex, decoded path).
std::vector<std::pair<std::string, std::string>> parseManifest(const std::string& text);
// bag-info.txt label -> values.
std::multimap<std::string, std::string> parseBagInfo(const std::string& text);

}  // namespace bagcheck
