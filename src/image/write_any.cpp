#include "image/write_any.h"

#include <cerrno>
#include <tiffio.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "image/tiff_structure.h"
#include "image/write.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {
constexpr const char* kStep = "image write";
}  // namespace

std::optional<PictureFormat> pictureFormatFor(const fs::path& path) {
  const std::string ext = lowerCase(path.extension().string());
  if (ext == ".png") return PictureFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return PictureFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return PictureFormat::Tiff;
  return std::nullopt;
}

const char* pictureFormatName(PictureFormat format) {
  switch (format) {
    case PictureFormat::Png: return "PNG";
    case PictureFormat::Jpeg: return "JPEG";
    case PictureFormat::Tiff: return "TIFF";
  }
  return "PNG";
}

namespace {

// The image's rows into the open TIFF `tif`; false when libtiff fails (its words are kept by
// quietTiffOptions).
bool writeTiffRows(TIFF* tif, const Image& image, bool eightBit) {
  const std::uint32_t w = static_cast<std::uint32_t>(image.width), h = static_cast<std::uint32_t>(image.height);
  const std::uint16_t samples = static_cast<std::uint16_t>(image.channels);
  const std::uint16_t bits = eightBit ? 8 : 16;
  bool ok = TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w) && TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h) &&
            TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, bits) && TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, samples) &&
            TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, samples == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK) &&
            TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG) &&
            TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_NONE) &&
            TIFFSetField(tif, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT) &&
            TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tif, 0));
  const std::size_t n = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<std::uint8_t> row8(eightBit ? n : 0);
  std::vector<std::uint16_t> row16(eightBit ? 0 : n);
  for (std::uint32_t y = 0; ok && y < h; ++y) {
    const std::uint16_t* in = image.pixels.data() + y * n;
    if (eightBit) narrowSamples(in, n, row8.data());  // rounded to nearest, as writePng
    else std::copy(in, in + n, row16.begin());
    ok = TIFFWriteScanline(tif, eightBit ? static_cast<void*>(row8.data()) : static_cast<void*>(row16.data()), y, 0) == 1;
  }
  return ok;
}

}  // namespace

void writeTiff(const Image& image, const fs::path& path) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, path.string(), kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  AtomicFile out(path);
  std::string libtiffError;
  const TiffOpenOptionsPtr options = quietTiffOptions(&libtiffError);
  TIFF* tif = TIFFOpenExt(out.tempPath().c_str(), "w", options.get());
  if (!tif)
    throw Error(ErrorKind::Input, path.string(), kStep,
                "cannot create the file (" + (libtiffError.empty() ? std::string("libtiff cannot open it") : libtiffError) +
                    "); check that its folder exists and can be written");
  errno = 0;  // what a failing write(2) inside libtiff sets
  const bool rowsWritten = writeTiffRows(tif, image, image.bitsPerSample <= 8);
  const bool flushed = rowsWritten && TIFFFlush(tif) == 1;
  const int writeErrno = errno;
  TIFFClose(tif);
  if (!flushed && writeErrno != 0) throw writeError(path, kStep, writeErrno);
  if (!flushed)
    throw Error(ErrorKind::Input, path.string(), kStep,
                "libtiff could not write the TIFF (" + (libtiffError.empty() ? std::string("no reason given") : libtiffError) +
                    "); check the free space of its folder");
  out.commit();
}

void writePicture(const Image& image, const fs::path& path, int jpegQuality) {
  const auto format = pictureFormatFor(path);
  if (!format)
    throw Error(ErrorKind::Usage, path.string(), kStep,
                "the picture's format comes from its name: end it in .png, .jpg, .jpeg, .tif or .tiff");
  switch (*format) {
    case PictureFormat::Png: writePng(image, path); return;
    case PictureFormat::Jpeg: writeJpeg(image, path, jpegQuality); return;
    case PictureFormat::Tiff: writeTiff(image, path); return;
  }
}

}  // namespace surrogate::image
