// PRONOM's published signatures read and matched by the tests, independently of src/formats:
// the entries of a DROID signature file kept in tests/data/pronom/ (SOURCE.md there), read with
// libxml2 in the file's own structure (byte sequences, subsequences, left and right fragments)
// and matched by brute force, sequences anchored at the end matched backwards from it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pronom_reference {

// The formats of the kept excerpt, by PUID.
std::vector<std::string> puids();

// Whether any of the format's signatures in the excerpt matches the bytes of a whole file.
// Throws std::runtime_error for a PUID the excerpt does not hold.
bool matches(const std::string& puid, std::string_view bytes);

// The excerpt's formats that PRONOM gives priority over `puid` (HasPriorityOverFileFormatID).
std::vector<std::string> preferredTo(const std::string& puid);

// What DROID would report if PRONOM held only the kept formats: every format whose signature
// matches, less those another match has priority over; sorted.
std::vector<std::string> identify(std::string_view bytes);

// The signature file's release ("118").
std::string release();

std::string bytesOf(const std::string& path);

}  // namespace pronom_reference
