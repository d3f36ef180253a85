// Private to src/archive: the tag files of a bag (bag_tag_files.cpp): manifests, the caller's
// tag files, and writing one into the output with its digests.
#pragma once

#include <string>
#include <vector>

#include "archive/bag.h"
#include "core/digest.h"

namespace surrogate::archive {

class Sink;  // bag_output.h

// A manifest: "<hex>  <path>" for every item, its path escaped (escapeManifestPath).
std::string manifestText(const std::vector<PayloadDigest>& items, DigestAlgorithm algorithm);

// The payload manifests and the caller's tag files (BagInput::tagFiles, checked: no reserved
// name, nothing in data/, no duplicate; else Error(Internal)), in path order.
std::vector<TagFile> sortedTagFiles(const BagInput& input, const std::vector<PayloadDigest>& payload);

// Writes one entry of `content` into the sink.
void putTag(Sink& sink, const std::string& bagPath, const std::string& content);
// Writes a tag file into the sink, its content or its file copied in pieces (Error(Internal)
// when that file cannot be read whole), and returns its digests for the tag manifests.
PayloadDigest putTagFile(Sink& sink, const TagFile& tag);

}  // namespace surrogate::archive
