#include "core/base64.h"

#include <algorithm>

#include <openssl/evp.h>

namespace surrogate {

void appendBase64(std::string& out, const void* data, std::size_t size) {
  const auto* in = static_cast<const unsigned char*>(data);
  std::size_t at = out.size();
  // EVP_EncodeBlock takes an int count and ends its output with a NUL, which the next chunk
  // overwrites: room for one more byte, cut at the end. Chunks are a multiple of 3 bytes, so
  // only the last one is padded.
  out.resize(at + 4 * ((size + 2) / 3) + 1);
  constexpr std::size_t kChunk = std::size_t(3) << 24;
  for (std::size_t done = 0; done < size; done += kChunk) {
    const std::size_t n = std::min(kChunk, size - done);
    at += static_cast<std::size_t>(
        EVP_EncodeBlock(reinterpret_cast<unsigned char*>(&out[at]), in + done, static_cast<int>(n)));
  }
  out.resize(at);
}

std::string base64(const std::string& bytes) {
  std::string out;
  appendBase64(out, bytes.data(), bytes.size());
  return out;
}

}  // namespace surrogate
