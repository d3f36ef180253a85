#include "formats/text_parse.h"

#include <charconv>
#include <cmath>

#include "core/error.h"

namespace surrogate::formats {

HeaderCursor::HeaderCursor(const std::uint8_t* data, std::size_t size, std::string file,
                           std::string step)
    : data_(data), size_(size), file_(std::move(file)), step_(std::move(step)) {}

std::string_view HeaderCursor::line(const std::string& what, std::size_t maxLength) {
  const std::size_t start = pos_;
  std::size_t end = start;
  while (end < size_ && data_[end] != '\n') {
    if (end - start >= maxLength) {
      ++lineNumber_;
      fail("line " + std::to_string(lineNumber_) + " (" + what +
           ") is far too long; this is not a valid header");
    }
    ++end;
  }
  ++lineNumber_;
  if (end >= size_) {
    fail("the file ends before the end of line " + std::to_string(lineNumber_) + " (" + what +
         "); the file is truncated or not in this format");
  }
  pos_ = end + 1;
  std::size_t len = end - start;
  if (len > 0 && data_[start + len - 1] == '\r') --len;
  return std::string_view(reinterpret_cast<const char*>(data_ + start), len);
}

void HeaderCursor::fail(const std::string& message) const {
  throw Error(ErrorKind::Input, file_, step_, message);
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t' || text.front() == '\r'))
    text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
    text.remove_suffix(1);
  return text;
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

namespace {
std::string_view dropPlus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  return token;
}
}  // namespace

bool parseInt(std::string_view token, long long* value) {
  token = dropPlus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto r = std::from_chars(token.data(), end, *value);
  return r.ec == std::errc() && r.ptr == end;
}

bool parseDouble(std::string_view token, double* value) {
  token = dropPlus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto r = std::from_chars(token.data(), end, *value, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == end && std::isfinite(*value);
}

std::string formatFixed(double value) {
  char buffer[512];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  if (r.ec != std::errc()) return "0";  // unreachable for the values writers accept
  return std::string(buffer, r.ptr);
}

}  // namespace surrogate::formats
