// A file's PRONOM identifier (PUID) from its own bytes, as DROID and Siegfried find it: every
// PRONOM signature of the formats Surrogate meets (and of every format PRONOM prefers to one of
// them) is sought at the offsets PRONOM gives, from the start or the end of the file; of the
// formats whose signatures match, those another match has priority over are set aside. One
// format left is the identification; none, or several (DROID then reports each), leave the PUID
// empty. mappings/pronom.md lists the formats and the release.
//
// A file no signature matches is then named as Siegfried and fido name it (identifyPronomNamed):
// text (UTF-8 or ASCII with no control character but tab, line and page breaks) is PRONOM's
// Plain Text File, x-fmt/111, or, by its name's extension, JSON (.json, fmt/817) or JavaScript
// (.js, x-fmt/423): PRONOM gives these three no signature. An .lp is plain text (PRONOM has no
// entry for light-position files). The name decides nothing else.
//
//   const PronomIdentity id = identifyPronomFile("original-captures/IMG_0001.dng");
//   id.puid;        // "fmt/730"
//   id.describe();  // "Digital Negative Format (DNG) 1.4 (fmt/730)"
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace surrogate::formats {

struct PronomIdentity {
  std::string puid;     // "" when no single format is identified
  std::string name;     // PRONOM's format name, e.g. "JPEG File Interchange Format"
  std::string version;  // PRONOM's version of it, e.g. "1.01"; "" when PRONOM gives none
  std::vector<std::string> matches;  // every PUID left after priorities (several: ambiguous)
  bool fromText = false;  // no signature matched: named as text (and by extension), as Siegfried does

  bool identified() const { return !puid.empty(); }
  // "JPEG File Interchange Format 1.01 (fmt/43)"; "no PRONOM signature matches" or
  // "PRONOM signatures of several formats match: fmt/a, fmt/b".
  std::string describe() const;
};

// The bytes of a whole file, by PRONOM's signatures only.
PronomIdentity identifyPronom(std::string_view bytes);

// The same, then, when no signature matches, as text named by `fileName`'s extension (above).
PronomIdentity identifyPronomNamed(std::string_view bytes, const std::string& fileName);

// Whether `bytes` are text as Siegfried's and fido's text match take it: not empty, UTF-8 (an
// optional byte-order mark first), no control character but tab, line feed, carriage return,
// vertical tab and form feed.
bool isPlainText(std::string_view bytes);

// The file at `file` (identifyPronomNamed with its name), mapped (only the pages a signature
// reaches are read, and for text the file). Throws Error when it cannot be opened or read.
PronomIdentity identifyPronomFile(const std::filesystem::path& file);

// The DROID signature file release the signatures come from, e.g. "118".
std::string pronomRelease();

}  // namespace surrogate::formats
