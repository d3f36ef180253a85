// FileSummary: what a .ptm, .rti or .lp file holds, for `surrogate info`.
//
//   FileSummary s = summarize("finished-files/object.ptm");
//   std::cout << s.toText();   // or s.toJson() for --json
//
// For .ptm and .rti only the header is parsed and the file size is checked against it (the
// payload is not loaded, so this is fast on large files); a truncated file is reported as an
// Error(Input). For .lp the whole file is read and validated.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace surrogate::formats {

struct FileSummary {
  std::string path;
  std::string kind;     // "ptm", "rti" or "lp"
  std::string format;   // the PTM format line ("PTM_FORMAT_LRGB", "PTM_FORMAT_JPEG_LRGB", ...),
                        // "HSH" or "light positions"
  std::string version;  // "PTM_1.2", "PTM_1.1", the first comment of an .rti ("HSH1.2")
  std::string basis;    // "ptm-lrgb", "ptm-rgb", "hsh2", "hsh3", "hsh4"; empty for .lp
  int width = 0, height = 0;
  int terms = 0;               // coefficients per channel (6 for PTM)
  std::vector<double> scale;   // per term, as stored
  std::vector<double> bias;    // per term, as stored
  int lightCount = 0;          // .lp only
  double minElevationDegrees = 0, maxElevationDegrees = 0;  // .lp only: asin(lz)
  std::string puid;             // PRONOM identifier from the bytes (formats/pronom.h), "" if none
  std::string pronom;           // PronomIdentity::describe(): the format's name and PUID, or why none
  std::uint64_t fileBytes = 0;
  std::uint64_t trailingBytes = 0;  // bytes after the payload (ignored by readers)
  std::vector<std::string> notes;   // compatibility remarks, one sentence each

  std::string toText() const;  // "PATH: what it is", then indented "label: value" lines
  std::string toJson() const;  // one JSON object
};

// Chooses the reader from the file's first bytes ("PTM_" or '#'), else from the extension
// (.lp). Throws Error(Input) naming the file when it is none of these or is invalid.
FileSummary summarize(const std::filesystem::path& path);

}  // namespace surrogate::formats
