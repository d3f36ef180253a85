#include "image/tiff_structure.h"

#include <tiffio.h>

#include <cstdarg>
#include <cstdio>
#include <memory>
#include <vector>

namespace surrogate::image {

namespace {

// Bounds the walk: no real file has more directories, and a crafted file cannot make it long.
constexpr int kMaxDirectories = 64;

// Per-handle handlers (libtiff >= 4.5): thread-safe, and they leave the process-wide handlers
// untouched. Returning 1 stops the global handler.
int collectError(TIFF*, void* user, const char*, const char* fmt, va_list ap) {
  auto* text = static_cast<std::string*>(user);
  if (text->empty()) {
    char buf[512];
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    *text = buf;
  }
  return 1;
}

int ignoreWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};

// True when every strip or tile of the current directory lies inside the file.
bool dataInsideFile(TIFF* tif, std::uint64_t fileSize) {
  const std::uint32_t blocks = TIFFIsTiled(tif) ? TIFFNumberOfTiles(tif) : TIFFNumberOfStrips(tif);
  for (std::uint32_t i = 0; i < blocks; ++i) {
    int err = 0;
    const std::uint64_t offset = TIFFGetStrileOffsetWithErr(tif, i, &err);
    const std::uint64_t count = TIFFGetStrileByteCountWithErr(tif, i, &err);
    if (err) return true;  // no table for this directory: nothing to check
    if (offset > fileSize || count > fileSize - offset) return false;
  }
  return true;
}

// Walks IFD0, IFD1, ... and the SubIFDs of each, checking their image data.
bool allDataInsideFile(TIFF* tif, std::uint64_t fileSize) {
  for (tdir_t main = 0; main < kMaxDirectories; ++main) {
    if (main > 0 && !TIFFSetDirectory(tif, main)) break;
    if (!dataInsideFile(tif, fileSize)) return false;
    std::uint16_t count = 0;
    std::uint64_t* offsets = nullptr;
    if (TIFFGetField(tif, TIFFTAG_SUBIFD, &count, &offsets) && count > 0) {
      // Copied: the array belongs to the current directory, which the loop replaces.
      const std::vector<std::uint64_t> subs(offsets, offsets + std::min<int>(count, kMaxDirectories));
      for (std::uint64_t sub : subs)
        if (TIFFSetSubDirectory(tif, sub) && !dataInsideFile(tif, fileSize)) return false;
      if (!TIFFSetDirectory(tif, main)) break;
    }
  }
  return true;
}

}  // namespace

TiffStructure readTiffStructure(const std::filesystem::path& path) {
  TiffStructure s;
  std::string libtiffError;
  const TiffOpenOptionsPtr options = quietTiffOptions(&libtiffError);
  // Opening reads the header and IFD0 only. "m": no memory-mapping, so a file shrinking while
  // it is read gives an error, not a fault.
  std::unique_ptr<TIFF, TiffCloser> tif(TIFFOpenExt(path.c_str(), "rm", options.get()));
  if (!tif) {
    s.unreadable = libtiffError.empty() ? "libtiff cannot open it" : libtiffError;
    return s;
  }
  std::uint32_t w = 0, h = 0;
  std::uint16_t bits = 0;
  TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h);
  TIFFGetFieldDefaulted(tif.get(), TIFFTAG_BITSPERSAMPLE, &bits);
  s.width = static_cast<int>(w);
  s.height = static_cast<int>(h);
  s.bitsPerSample = bits;
  std::uint8_t* dngVersion = nullptr;  // DNGVersion: 4 bytes, fixed count (no count argument)
  s.isDng = TIFFGetField(tif.get(), TIFFTAG_DNGVERSION, &dngVersion) == 1;

  std::error_code ec;
  const std::uint64_t fileSize = std::filesystem::file_size(path, ec);
  if (!ec) s.truncated = !allDataInsideFile(tif.get(), fileSize);
  s.unreadable = libtiffError;
  return s;
}

TiffOpenOptionsPtr quietTiffOptions(std::string* firstError) {
  TiffOpenOptionsPtr options(TIFFOpenOptionsAlloc(), TIFFOpenOptionsFree);
  TIFFOpenOptionsSetErrorHandlerExtR(options.get(), collectError, firstError);
  TIFFOpenOptionsSetWarningHandlerExtR(options.get(), ignoreWarning, nullptr);
  return options;
}

std::string tiffProblem(const TiffStructure& s) {
  if (s.truncated)
    return "the file is truncated: its image data extends past the end of the file; copy it again";
  if (!s.unreadable.empty()) return "the TIFF structure is damaged (libtiff: " + s.unreadable + ")";
  return {};
}

}  // namespace surrogate::image
