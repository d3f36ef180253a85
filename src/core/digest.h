// Message digests of files and streams (OpenSSL EVP), computed in one pass.
//
// Fixity is the first promise of an archival package: every file is recorded with its
// SHA-256 (carrier, manifests) and SHA-512 (manifests). A file is read once and both digests
// are fed from the same buffer.
//
//   MultiDigest d({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
//   d.update(buffer, n);  ...
//   std::string hex256 = d.hex(DigestAlgorithm::Sha256);
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace surrogate {

// Md5 and Sha1 only to check bags made by other tools: RFC 8493 section 2.4 lets a verifier
// accept them for existing bags; nothing Surrogate writes uses them.
enum class DigestAlgorithm { Sha256, Sha512, Md5, Sha1 };

// The BagIt name of an algorithm: "sha256", "sha512", "md5", "sha1".
const char* bagitName(DigestAlgorithm algorithm);

// Digests named as a BagIt manifest names them (manifest-NAME.txt), for bags made by other
// tools: whatever OpenSSL offers under that name ("sha224", "sha384", "sha3-256" or
// bagit-python's "sha3_256", "blake2b", ...). The size of its digest in bytes, or 0 when
// OpenSSL offers no such digest, or only one of no fixed length (shake128, shake256). The name
// is untrusted: anything but a short lower-case word of letters, digits, '-' and '_' is 0.
std::size_t namedDigestSize(const std::string& bagitName);

class MultiDigest {
 public:
  explicit MultiDigest(std::vector<DigestAlgorithm> algorithms);
  // By BagIt name (namedDigestSize must be non-zero for each); throws Error(Internal) otherwise.
  explicit MultiDigest(const std::vector<std::string>& bagitNames);
  ~MultiDigest();
  MultiDigest(MultiDigest&&) noexcept;
  MultiDigest& operator=(MultiDigest&&) noexcept;
  MultiDigest(const MultiDigest&) = delete;
  MultiDigest& operator=(const MultiDigest&) = delete;

  void update(const void* data, std::size_t size);
  // Finishes (once) and returns the lower-case hex digest of `algorithm`, which must be one
  // of those given to the constructor.
  std::string hex(DigestAlgorithm algorithm);
  std::string hex(const std::string& bagitName);
  std::uint64_t bytes() const { return bytes_; }

 private:
  struct State;
  std::vector<std::unique_ptr<State>> states_;
  std::uint64_t bytes_ = 0;
};

struct FileDigests {
  std::uint64_t size = 0;
  std::string sha256;
  std::string sha512;  // empty unless asked for
};

// Reads `path` once and returns its size and digests. Throws Error(Input) naming the file if
// it cannot be read.
FileDigests digestFile(const std::filesystem::path& path, bool withSha512 = false);

// SHA-256 of a byte string, hex.
std::string sha256Hex(const std::string& bytes);

std::string opensslVersion();

}  // namespace surrogate
