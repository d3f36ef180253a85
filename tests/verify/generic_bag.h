// Test support: BagIt bags as other tools make them (md5 or sha1 manifests, tag files in
// UTF-16 or ISO-8859-1, fetch.txt), written file by file so that each test can break one
// thing. Header-only: the fixture library does not link what these use.
#pragma once

#include <iconv.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "bag_fixture.h"
#include "core/digest.h"

namespace verify_test {

// `utf8` in `encoding` (glibc iconv, as any tool writing such a bag would; "UTF-16" writes a
// byte-order mark).
inline std::string encodeAs(const std::string& utf8, const std::string& encoding) {
  if (encoding == "UTF-8") return utf8;
  iconv_t cd = iconv_open(encoding.c_str(), "UTF-8");
  if (cd == reinterpret_cast<iconv_t>(-1)) throw std::runtime_error("iconv cannot write " + encoding);
  std::string out(utf8.size() * 4 + 16, '\0');
  char* in = const_cast<char*>(utf8.data());
  std::size_t inLeft = utf8.size(), outLeft = out.size();
  char* outPtr = out.data();
  const std::size_t r = iconv(cd, &in, &inLeft, &outPtr, &outLeft);
  iconv_close(cd);
  if (r == static_cast<std::size_t>(-1)) throw std::runtime_error("iconv cannot encode the text as " + encoding);
  out.resize(out.size() - outLeft);
  return out;
}

inline std::string hexDigest(const std::string& bytes, surrogate::DigestAlgorithm algorithm) {
  surrogate::MultiDigest d({algorithm});
  d.update(bytes.data(), bytes.size());
  return d.hex(algorithm);
}

// A bag another tool made.
struct GenericBag {
  std::map<std::string, std::string> payload;  // "data/..." -> content (UTF-8 names)
  std::vector<surrogate::DigestAlgorithm> algorithms = {surrogate::DigestAlgorithm::Md5};
  std::string encoding = "UTF-8";                // Tag-File-Character-Encoding
  std::string version = "0.97";
  std::string bagInfo = "Source-Organization: Library of Congress\nBagging-Date: 2015-06-01\n"
                        "External-Description: a bag made by another tool\n";
  bool payloadOxum = true;
  std::string fetch;        // fetch.txt in UTF-8; empty: none
  bool tagManifests = true;

  // Writes the bag into `dir` (which must not exist yet).
  void write(const std::filesystem::path& dir) const {
    using surrogate::DigestAlgorithm;
    std::map<std::string, std::string> tags;  // tag files, as bytes
    tags["bagit.txt"] = "BagIt-Version: " + version + "\nTag-File-Character-Encoding: " + encoding + "\n";
    std::string info = bagInfo;
    if (payloadOxum) {
      std::uint64_t bytes = 0;
      for (const auto& [p, c] : payload) bytes += c.size();
      info += "Payload-Oxum: " + std::to_string(bytes) + "." + std::to_string(payload.size()) + "\n";
    }
    tags["bag-info.txt"] = encodeAs(info, encoding);
    if (!fetch.empty()) tags["fetch.txt"] = encodeAs(fetch, encoding);
    for (DigestAlgorithm a : algorithms) {
      std::string manifest;
      for (const auto& [p, c] : payload) manifest += hexDigest(c, a) + "  " + escapedPath(p) + "\n";
      tags[std::string("manifest-") + surrogate::bagitName(a) + ".txt"] = encodeAs(manifest, encoding);
    }
    for (const auto& [p, c] : payload) writeText(dir / p, c);
    for (const auto& [p, c] : tags) writeText(dir / p, c);
    if (!tagManifests) return;
    for (DigestAlgorithm a : algorithms) {
      std::string manifest;
      for (const auto& [p, c] : tags) manifest += hexDigest(c, a) + " " + p + "\n";
      writeText(dir / (std::string("tagmanifest-") + surrogate::bagitName(a) + ".txt"),
                encodeAs(manifest, encoding));
    }
  }
};

}  // namespace verify_test
