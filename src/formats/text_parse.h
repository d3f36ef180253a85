// Private to src/formats: bounds-checked parsing of the ASCII headers of .ptm, .rti and .lp.
//
// Every reader in this folder parses from a byte buffer whose size is known; HeaderCursor
// never looks past that size, and numbers are parsed with std::from_chars (locale independent,
// no exceptions, no reading past the token). Not a public header: other folders use ptm.h,
// rti_hsh.h, lp.h and summary.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace surrogate::formats {

class HeaderCursor {
 public:
  // `file` and `step` name the source in error messages.
  HeaderCursor(const std::uint8_t* data, std::size_t size, std::string file, std::string step);

  // The next '\n'-terminated line without its terminator (a trailing '\r' is dropped too).
  // Throws Error(Input) naming `what` when the buffer ends first or the line is longer than
  // `maxLength` bytes (a binary file mistaken for a header).
  std::string_view line(const std::string& what, std::size_t maxLength = 4096);
  bool atEnd() const { return pos_ >= size_; }
  std::uint8_t peek() const { return data_[pos_]; }  // only when !atEnd()
  std::size_t offset() const { return pos_; }
  int lineNumber() const { return lineNumber_; }  // 1-based number of the last line read
  [[noreturn]] void fail(const std::string& message) const;

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  int lineNumber_ = 0;
  std::string file_, step_;
};

// Whitespace-separated tokens (spaces and tabs; empty tokens skipped).
std::vector<std::string_view> tokens(std::string_view line);
std::string_view trim(std::string_view text);

// Whole-token parses; false when the token is not entirely a number (or out of range).
// A leading '+' is accepted (from_chars alone rejects it).
bool parseInt(std::string_view token, long long* value);
bool parseDouble(std::string_view token, double* value);  // also false for inf/nan

// Shortest decimal text that reads back as exactly `value`, never in exponent notation: the PTM
// header's scales, whose bytes RtiFit's version stands for (records use formatNumber, core/text.h).
std::string formatFixed(double value);

}  // namespace surrogate::formats
