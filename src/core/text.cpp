#include "core/text.h"

#include <algorithm>
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

namespace {

// The length of the well-formed UTF-8 sequence at s[i] (its code point in *code), or 0.
std::size_t utf8SequenceAt(const std::string& s, std::size_t i, unsigned* code) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  int extra = 0;
  unsigned int value = 0;
  if (c < 0x80) {
    *code = c;
    return 1;
  }
  if ((c & 0xE0) == 0xC0) { extra = 1; value = c & 0x1F; }
  else if ((c & 0xF0) == 0xE0) { extra = 2; value = c & 0x0F; }
  else if ((c & 0xF8) == 0xF0) { extra = 3; value = c & 0x07; }
  else return 0;
  if (i + extra >= s.size()) return 0;
  for (int k = 1; k <= extra; ++k) {
    const unsigned char d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xC0) != 0x80) return 0;
    value = (value << 6) | (d & 0x3F);
  }
  if ((extra == 1 && value < 0x80) || (extra == 2 && value < 0x800) ||
      (extra == 3 && (value < 0x10000 || value > 0x10FFFF)) || (value >= 0xD800 && value <= 0xDFFF))
    return 0;
  *code = value;
  return static_cast<std::size_t>(extra) + 1;
}

bool isControl(unsigned code, bool keepLineBreaks) {
  if (keepLineBreaks && (code == '\t' || code == '\n' || code == '\r')) return false;
  return code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0xFFFE || code == 0xFFFF;
}

}  // namespace

bool isValidUtf8(const std::string& s) {
  unsigned code = 0;
  for (std::size_t i = 0, n = 0; i < s.size(); i += n)
    if ((n = utf8SequenceAt(s, i, &code)) == 0) return false;
  return true;
}

bool needsEscaping(const std::string& bytes, bool keepLineBreaks) {
  unsigned code = 0;
  for (std::size_t i = 0, n = 0; i < bytes.size(); i += n)
    if ((n = utf8SequenceAt(bytes, i, &code)) == 0 || isControl(code, keepLineBreaks)) return true;
  return false;
}

std::string escapedText(const std::string& bytes, bool keepLineBreaks) {
  if (!needsEscaping(bytes, keepLineBreaks)) return bytes;
  static const char* kDigits = "0123456789ABCDEF";
  std::string out;
  unsigned code = 0;
  for (std::size_t i = 0; i < bytes.size();) {
    std::size_t n = utf8SequenceAt(bytes, i, &code);
    if (n > 0 && !isControl(code, keepLineBreaks)) {
      out.append(bytes, i, n);
    } else {
      for (std::size_t k = 0; k < std::max<std::size_t>(n, 1); ++k) {
        const unsigned char b = static_cast<unsigned char>(bytes[i + k]);
        out += "\\x";
        out += kDigits[b >> 4];
        out += kDigits[b & 15];
      }
      n = std::max<std::size_t>(n, 1);
    }
    i += n;
  }
  return out;
}

std::string hexBytes(const std::string& bytes) {
  static const char* kDigits = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (unsigned char b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 15];
  }
  return out;
}

std::string listedWithMore(const std::vector<std::string>& items, std::size_t most) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < most; ++i) out += (i ? ", " : "") + items[i];
  if (items.size() > most) out += " and " + std::to_string(items.size() - most) + " more";
  return out;
}

std::string listedInFull(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  // Three rows of the dynamic-programming table: the swap looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({previous[j] + 1, row[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], before[j - 2] + 1);
    }
    before.swap(previous);
    previous.swap(row);
  }
  return previous[b.size()];
}

std::optional<std::string> nearestName(const std::string& name, const std::vector<std::string>& candidates) {
  if (name.empty()) return std::nullopt;
  std::optional<std::string> best;
  std::size_t bestDistance = 3;
  bool tie = false;
  for (const std::string& c : candidates) {
    const std::size_t d = editDistance(name, c);
    if (d == 0 || 2 * d > name.size()) continue;
    if (d < bestDistance) {
      best = c;
      bestDistance = d;
      tie = false;
    } else if (d == bestDistance && c != *best) {
      tie = true;
    }
  }
  if (best && !tie) return best;
  std::optional<std::string> prefixed;
  for (const std::string& c : candidates) {
    if (c.size() <= name.size() || c.compare(0, name.size(), name) != 0) continue;
    if (prefixed && *prefixed != c) return std::nullopt;
    prefixed = c;
  }
  return prefixed;
}

std::string escapeHtml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string shellWord(const std::string& text) {
  const bool plain = !text.empty() && text.find_first_not_of(
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._/+-:,@%=") == std::string::npos;
  if (plain) return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace surrogate
