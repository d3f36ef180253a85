// Private to src/image: what the directories (IFDs) of a TIFF-structured file say, read with
// libtiff without decoding pixels.
//
//   header -> IFD0 -> IFD1 -> ...        (each IFD may point to SubIFDs: where DNG and NEF
//              \-> SubIFD0, SubIFD1        keep the full-size raw)
//
// DNG and most camera raw formats (CR2, NEF, ARW, PEF, ...) are TIFF files too; a DNG is told
// apart by its DNGVersion tag (50706) in IFD0. Completeness is checked through the strip or
// tile tables of every IFD and SubIFD: each block of image data must lie inside the file. This
// is what finds a pruned or truncated DNG, which LibRaw 0.20 would decode to a black image
// without any error.
#pragma once

#include <tiffio.h>

#include <filesystem>
#include <memory>
#include <string>

namespace surrogate::image {

struct TiffStructure {
  int width = 0;   // of the image in IFD0 (for a DNG often the preview, not the raw)
  int height = 0;
  int bitsPerSample = 0;
  bool isDng = false;
  std::string unreadable;  // libtiff could not read the structure (its message), else empty
  bool truncated = false;  // some image data lies past the end of the file
};

// Never prints: libtiff's messages are collected into `unreadable`.
TiffStructure readTiffStructure(const std::filesystem::path& path);

// libtiff open options (TIFFOpenExt) whose per-handle handlers keep libtiff's first error
// message in `*firstError` and drop its warnings: nothing reaches stderr, and the process-wide
// handlers stay as they are. Thread-safe (libtiff >= 4.5).
using TiffOpenOptionsPtr = std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions*)>;
TiffOpenOptionsPtr quietTiffOptions(std::string* firstError);

// A sentence for the user when the structure is unusable as a TIFF export (unreadable or
// truncated), else empty.
std::string tiffProblem(const TiffStructure& s);

}  // namespace surrogate::image
