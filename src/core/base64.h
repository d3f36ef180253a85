// Standard base64 (RFC 4648 section 4: with padding, no line breaks), by OpenSSL's
// EVP_EncodeBlock: how the report and the web copy embed pictures and models in text.
//
//   std::string uri = "data:image/jpeg;base64," + base64(jpegBytes);
//   appendBase64(json, coefficients.data(), coefficients.size());  // no temporary copy
#pragma once

#include <cstddef>
#include <string>

namespace surrogate {

// Appends the base64 of the `size` bytes at `data` to `out`.
void appendBase64(std::string& out, const void* data, std::size_t size);

// The base64 of `bytes`.
std::string base64(const std::string& bytes);

}  // namespace surrogate
