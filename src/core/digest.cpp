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

const EVP_MD* evpOf(DigestAlgorithm algorithm) {
  switch (algorithm) {
    case DigestAlgorithm::Sha256: return EVP_sha256();
    case DigestAlgorithm::Sha512: return EVP_sha512();
    case DigestAlgorithm::Md5: return EVP_md5();
    case DigestAlgorithm::Sha1: return EVP_sha1();
  }
  return nullptr;
}

}  // namespace

struct MultiDigest::State {
  DigestAlgorithm algorithm;
  EVP_MD_CTX* ctx = nullptr;
  std::string hex;  // set when finished
  ~State() { EVP_MD_CTX_free(ctx); }
};

MultiDigest::MultiDigest(std::vector<DigestAlgorithm> algorithms) {
  for (DigestAlgorithm a : algorithms) {
    auto s = std::make_unique<State>();
    s->algorithm = a;
    s->ctx = EVP_MD_CTX_new();
    const EVP_MD* md = evpOf(a);
    if (!s->ctx || !md || EVP_DigestInit_ex(s->ctx, md, nullptr) != 1)
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

std::string MultiDigest::hex(DigestAlgorithm algorithm) {
  for (auto& s : states_) {
    if (s->algorithm != algorithm) continue;
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
