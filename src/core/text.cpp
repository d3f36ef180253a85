#include "core/text.h"

#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace surrogate {

std::string lowerCase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string formatNumber(double value) {
  if (!std::isfinite(value))
    throw Error(ErrorKind::Internal, "", "writing a number",
                "a value that is not a finite number (NaN or infinity) was to be recorded");
  // Below 1e15 every integer part is exact (2^53 is about 9.007e15), so the shortest plain
  // decimal has the same significant digits as the shortest scientific form; above, plain
  // notation would spell out digits the double does not determine.
  const double magnitude = std::fabs(value);
  const bool plain = magnitude == 0 || (magnitude >= 1e-6 && magnitude < 1e15);
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value,
                               plain ? std::chars_format::fixed : std::chars_format::scientific);
  if (r.ec != std::errc())
    throw Error(ErrorKind::Internal, "", "writing a number", "the number does not fit its buffer");
  return std::string(buffer, r.ptr);
}

std::string fixedDecimals(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

bool isValidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    int extra = 0;
    unsigned int code = 0;
    if (c < 0x80) { ++i; continue; }
    if ((c & 0xE0) == 0xC0) { extra = 1; code = c & 0x1F; }
    else if ((c & 0xF0) == 0xE0) { extra = 2; code = c & 0x0F; }
    else if ((c & 0xF8) == 0xF0) { extra = 3; code = c & 0x07; }
    else return false;
    if (i + extra >= s.size()) return false;
    for (int k = 1; k <= extra; ++k) {
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xC0) != 0x80) return false;
      code = (code << 6) | (d & 0x3F);
    }
    if ((extra == 1 && code < 0x80) || (extra == 2 && code < 0x800) ||
        (extra == 3 && (code < 0x10000 || code > 0x10FFFF)) || (code >= 0xD800 && code <= 0xDFFF))
      return false;
    i += extra + 1;
  }
  return true;
}

}  // namespace surrogate
