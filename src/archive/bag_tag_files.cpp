// The tag files of a bag: the manifests (RFC 8493 2.1.3, with its path encoding), the
// caller's tag files checked against the names BagIt reserves, and each written into the
// output with the digests its tag manifests list. The order of the whole bag is writeBag's
// (bag.cpp).
#include "archive/bag_tag_files.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "archive/bag_output.h"
#include "archive/bag_payload.h"
#include "core/error.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

std::string escapeManifestPath(const std::string& path) {
  std::string out;
  out.reserve(path.size());
  for (const char c : path) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else out.push_back(c);
  }
  return out;
}

std::string manifestText(const std::vector<PayloadDigest>& items, DigestAlgorithm algorithm) {
  std::string text;
  for (const PayloadDigest& d : items) {
    text += (algorithm == DigestAlgorithm::Sha256 ? d.sha256 : d.sha512);
    text += "  ";
    text += escapeManifestPath(d.bagPath);
    text += "\n";
  }
  return text;
}

std::vector<TagFile> sortedTagFiles(const BagInput& input, const std::vector<PayloadDigest>& payload) {
  std::vector<TagFile> tags;
  tags.push_back({"manifest-sha256.txt", manifestText(payload, DigestAlgorithm::Sha256), {}});
  tags.push_back({"manifest-sha512.txt", manifestText(payload, DigestAlgorithm::Sha512), {}});
  if (input.tagFiles) {
    for (TagFile& t : input.tagFiles(payload)) {
      const bool reserved = t.bagPath == "bagit.txt" || t.bagPath == "bag-info.txt" ||
                            t.bagPath.rfind("manifest-", 0) == 0 ||
                            t.bagPath.rfind("tagmanifest-", 0) == 0 || t.bagPath == "fetch.txt";
      if (!safeRelative(t.bagPath) || t.bagPath.rfind("data/", 0) == 0 || reserved) {
        throw Error(ErrorKind::Internal, t.bagPath, "packing", "is not a valid tag file path");
      }
      tags.push_back(std::move(t));
    }
  }
  std::sort(tags.begin(), tags.end(),
            [](const TagFile& a, const TagFile& b) { return a.bagPath < b.bagPath; });
  for (std::size_t i = 1; i < tags.size(); ++i) {
    if (tags[i].bagPath == tags[i - 1].bagPath)
      throw Error(ErrorKind::Internal, tags[i].bagPath, "packing", "is given twice");
  }
  return tags;
}

void putTag(Sink& sink, const std::string& bagPath, const std::string& content) {
  sink.begin(bagPath, content.size());
  sink.write(content.data(), content.size());
  sink.end();
}

PayloadDigest putTagFile(Sink& sink, const TagFile& tag) {
  if (tag.file.empty()) {
    putTag(sink, tag.bagPath, tag.content);
    MultiDigest d({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
    d.update(tag.content.data(), tag.content.size());
    return {tag.bagPath, tag.content.size(), d.hex(DigestAlgorithm::Sha256),
            d.hex(DigestAlgorithm::Sha512)};
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(tag.file.c_str(), "rb"), &std::fclose);
  std::error_code ec;
  const std::uint64_t size = fs::file_size(tag.file, ec);
  if (!in || ec)
    throw Error(ErrorKind::Internal, tag.file.string(), "packing", "cannot read a derived tag file");
  MultiDigest digest({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
  std::vector<char> buffer(kBufferSize);
  sink.begin(tag.bagPath, size);
  std::uint64_t copied = 0;
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), in.get())) > 0; copied += n) {
    sink.write(buffer.data(), n);
    digest.update(buffer.data(), n);
  }
  if (std::ferror(in.get()) || copied != size)
    throw Error(ErrorKind::Internal, tag.file.string(), "packing", "cannot read a derived tag file");
  sink.end();
  return {tag.bagPath, size, digest.hex(DigestAlgorithm::Sha256), digest.hex(DigestAlgorithm::Sha512)};
}

}  // namespace surrogate::archive
