#include "core/digest.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.h"

namespace surrogate {

const char* bagitName(DigestAlgorithm algorithm) {
  switch (algorithm) {
    case DigestAlgorithm::Sha256: return "sha256";
    case DigestAlgorithm::Sha512: return "sha512";
    case DigestAlgorithm::Md5: return "md5";
    case DigestAlgorithm::Sha1: return "sha1";
  }
  return "";
}

namespace {

// An OpenSSL digest fetched by name, freed on scope exit.
struct FetchedDigest {
  EVP_MD* md = nullptr;
  explicit FetchedDigest(const std::string& bagitName);
  ~FetchedDigest() { EVP_MD_free(md); }
  FetchedDigest(const FetchedDigest&) = delete;
  FetchedDigest& operator=(const FetchedDigest&) = delete;
};

// BagIt names are lower-case words; OpenSSL's names differ in a few spellings: bagit-python
// writes Python's hashlib names (sha3_256, blake2b), OpenSSL sha3-256, BLAKE2B-512.
std::string opensslName(const std::string& bagitName) {
  if (bagitName == "blake2b") return "BLAKE2B-512";
  if (bagitName == "blake2s") return "BLAKE2S-256";
  std::string name = bagitName;
  for (char& c : name)
    if (c == '_') c = '-';
  return name;
}

bool plausibleDigestName(const std::string& name) {
  if (name.empty() || name.size() > 32) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_')) return false;
  return true;
}

FetchedDigest::FetchedDigest(const std::string& bagitName) {
  if (!plausibleDigestName(bagitName)) return;
  md = EVP_MD_fetch(nullptr, opensslName(bagitName).c_str(), nullptr);
  // No fixed length (an extendable-output function), or none at all (OpenSSL's "null"): no
  // manifest could hold it.
  if (md && ((EVP_MD_get_flags(md) & EVP_MD_FLAG_XOF) != 0 || EVP_MD_get_size(md) <= 0)) {
    EVP_MD_free(md);
    md = nullptr;
  }
}

}  // namespace

std::size_t namedDigestSize(const std::string& bagitName) {
  const FetchedDigest digest(bagitName);
  return digest.md ? static_cast<std::size_t>(EVP_MD_get_size(digest.md)) : 0;
}

struct MultiDigest::State {
  std::string name;  // the BagIt name
  EVP_MD_CTX* ctx = nullptr;
  std::string hex;  // set when finished
  ~State() { EVP_MD_CTX_free(ctx); }
};

MultiDigest::MultiDigest(std::vector<DigestAlgorithm> algorithms)
    : MultiDigest([&] {
        std::vector<std::string> names;
        for (DigestAlgorithm a : algorithms) names.emplace_back(bagitName(a));
        return names;
      }()) {}

MultiDigest::MultiDigest(const std::vector<std::string>& bagitNames) {
  for (const std::string& name : bagitNames) {
    auto s = std::make_unique<State>();
    s->name = name;
    s->ctx = EVP_MD_CTX_new();
    const FetchedDigest digest(name);
    if (!digest.md)
      throw Error(ErrorKind::Internal, name, "hashing", "OpenSSL offers no digest of that name");
    // The context keeps its own reference to the digest.
    if (!s->ctx || EVP_DigestInit_ex(s->ctx, digest.md, nullptr) != 1)
      throw std::runtime_error("OpenSSL could not initialise a digest");
    states_.push_back(std::move(s));
  }
}

MultiDigest::~MultiDigest() = default;
MultiDigest::MultiDigest(MultiDigest&&) noexcept = default;
MultiDigest& MultiDigest::operator=(MultiDigest&&) noexcept = default;

void MultiDigest::update(const void* data, std::size_t size) {
  for (auto& s : states_) {
    if (!s->hex.empty()) throw std::logic_error("MultiDigest::update after hex()");
    EVP_DigestUpdate(s->ctx, data, size);
  }
  bytes_ += size;
}

std::string MultiDigest::hex(DigestAlgorithm algorithm) { return hex(std::string(bagitName(algorithm))); }

std::string MultiDigest::hex(const std::string& bagitName) {
  for (auto& s : states_) {
    if (s->name != bagitName) continue;
    if (s->hex.empty()) {
      unsigned char out[EVP_MAX_MD_SIZE];
      unsigned int len = 0;
      EVP_DigestFinal_ex(s->ctx, out, &len);
      static const char* digits = "0123456789abcdef";
      s->hex.reserve(len * 2);
      for (unsigned i = 0; i < len; ++i) {
        s->hex.push_back(digits[out[i] >> 4]);
        s->hex.push_back(digits[out[i] & 15]);
      }
    }
    return s->hex;
  }
  throw std::logic_error("MultiDigest::hex: algorithm not requested");
}

FileDigests digestFile(const std::filesystem::path& path, bool withSha512) {
  std::vector<DigestAlgorithm> algorithms{DigestAlgorithm::Sha256};
  if (withSha512) algorithms.push_back(DigestAlgorithm::Sha512);
  MultiDigest digest(algorithms);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throwInputError(path.string(), "hashing", std::string("cannot open the file: ") +
                                                        std::strerror(errno));
  // One buffer per thread for every file: a fresh zeroed MiB per file (and malloc consolidating
  // its heap on each free) cost more than hashing the small files a capture holds by thousands.
  static thread_local std::vector<unsigned char> buffer(1 << 20);
  for (;;) {
    const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), f);
    if (n > 0) digest.update(buffer.data(), n);
    if (n < buffer.size()) break;
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throwInputError(path.string(), "hashing", "reading the file failed");
  FileDigests result;
  result.size = digest.bytes();
  result.sha256 = digest.hex(DigestAlgorithm::Sha256);
  if (withSha512) result.sha512 = digest.hex(DigestAlgorithm::Sha512);
  return result;
}

std::string sha256Hex(const std::string& bytes) {
  MultiDigest d({DigestAlgorithm::Sha256});
  d.update(bytes.data(), bytes.size());
  return d.hex(DigestAlgorithm::Sha256);
}

std::string opensslVersion() { return OpenSSL_version(OPENSSL_VERSION); }

}  // namespace surrogate
