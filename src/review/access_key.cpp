#include "review/access_key.h"

#include <algorithm>

#include <openssl/crypto.h>
#include <openssl/rand.h>

#include "core/error.h"

namespace surrogate::review {

namespace {

// 256 bits: a key nobody finds by trying, even at a million requests a second for years.
constexpr int kKeyBytes = 32;

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

}  // namespace

const char* const kForgetKeyJs =
    "if (window.location.search && window.history.replaceState)\n"
    "  window.history.replaceState(null, \"\", window.location.pathname);\n";

std::vector<std::string> cookieValues(const std::string& cookieHeader, const std::string& name) {
  std::vector<std::string> values;
  std::size_t start = 0;
  while (start <= cookieHeader.size()) {
    const std::size_t end = std::min(cookieHeader.find(';', start), cookieHeader.size());
    const std::string pair = trimmed(cookieHeader.substr(start, end - start));
    const auto equals = pair.find('=');
    if (equals != std::string::npos && trimmed(pair.substr(0, equals)) == name) values.push_back(trimmed(pair.substr(equals + 1)));
    start = end + 1;
  }
  return values;
}

AccessKey AccessKey::generate() {
  unsigned char bytes[kKeyBytes];
  if (RAND_bytes(bytes, kKeyBytes) != 1)
    throw Error(ErrorKind::Internal, "", "review",
                "no random bytes could be had for the review page's key (OpenSSL RAND_bytes failed)");
  static const char* const kDigits = "0123456789abcdef";
  AccessKey key;
  for (unsigned char b : bytes) {
    key.text_ += kDigits[b >> 4];
    key.text_ += kDigits[b & 15];
  }
  return key;
}

bool AccessKey::matches(const std::string& given) const {
  // The length is public (64 digits): only the contents are compared in constant time.
  return given.size() == text_.size() && CRYPTO_memcmp(given.data(), text_.data(), text_.size()) == 0;
}

bool AccessKey::matchesOneOf(const std::vector<std::string>& given) const {
  bool found = false;
  for (const std::string& g : given) found = matches(g) || found;  // every one compared, in constant time each
  return found;
}

std::string AccessKey::cookieName(int port) { return "surrogate-review-" + std::to_string(port); }

}  // namespace surrogate::review
