// Private to src/formats: PRONOM's signatures as pronom.cpp reads them, generated from a DROID
// signature file by scripts/pronom-table into pronom_signatures.cpp.
#pragma once

#include <cstdint>
#include <vector>

namespace surrogate::formats {

// Where a part of a signature is sought: its first byte at [min, max] from the start of the
// file (max -1: anywhere after min), its last byte at [min, max] from the end, or its first byte
// at [min, max] after the end of the part before it.
enum class PronomAnchor { Bof, Eof, AfterPrevious };

// One part, in PRONOM's expression syntax: hex bytes, {n} or {n-m} gaps, (a|b) alternatives,
// [aa:bb] a byte in a range.
struct PronomPart {
  PronomAnchor anchor;
  std::int64_t min, max;
  const char* expression;
};

struct PronomFormat {
  const char* puid;
  const char* name;
  const char* version;                                // "" when PRONOM gives none
  std::vector<std::vector<PronomPart>> signatures;    // any one matching identifies the format
  std::vector<const char*> priorityOver;              // PUIDs this format wins over when both match
};

// The signature file's release ("118").
extern const char* const kPronomRelease;

const std::vector<PronomFormat>& pronomFormats();

}  // namespace surrogate::formats
