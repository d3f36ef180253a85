// Writing a DNG that LibRaw decodes and Exiv2 reads: an uncompressed 16-bit CFA image (RGGB)
// in IFD0 with the DNG colour tags, and an EXIF sub-IFD with the exposure.
#include <tiffio.h>

#include <cstring>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "generator/capture_generator.h"

namespace surrogate::generator {

namespace {
constexpr std::uint16_t kBlack = 512;
constexpr std::uint32_t kWhite = 65535;

[[noreturn]] void fail(const std::filesystem::path& path, const char* what) {
  throw Error(ErrorKind::Internal, path.string(), "generator", std::string("could not write the DNG: ") + what);
}
}  // namespace

void writeDng(const Image& rgb, const DngInfo& info, const std::filesystem::path& path) {
  AtomicFile out(path);
  TIFF* tif = TIFFOpen(out.tempPath().c_str(), "w");
  if (!tif) fail(path, "cannot create the file");
  const std::uint32_t w = rgb.width, h = rgb.height;
  TIFFSetField(tif, TIFFTAG_SUBFILETYPE, 0);
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w);
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h);
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 16);
  TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
  TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, 32803);  // CFA
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, 16);
  TIFFSetField(tif, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
  TIFFSetField(tif, TIFFTAG_MAKE, info.make.c_str());
  TIFFSetField(tif, TIFFTAG_MODEL, info.model.c_str());
  TIFFSetField(tif, TIFFTAG_SOFTWARE, "Surrogate capture generator");
  const std::uint16_t repeat[2] = {2, 2};
  TIFFSetField(tif, TIFFTAG_CFAREPEATPATTERNDIM, repeat);
  const std::uint8_t pattern[4] = {0, 1, 1, 2};  // R G / G B
  TIFFSetField(tif, TIFFTAG_CFAPATTERN, 4, pattern);
  const std::uint8_t version[4] = {1, 4, 0, 0}, backward[4] = {1, 1, 0, 0};
  TIFFSetField(tif, TIFFTAG_DNGVERSION, version);
  TIFFSetField(tif, TIFFTAG_DNGBACKWARDVERSION, backward);
  const std::string unique = info.make + " " + info.model;
  TIFFSetField(tif, TIFFTAG_UNIQUECAMERAMODEL, unique.c_str());
  // The camera's primaries are linear sRGB's: ColorMatrix1 is the XYZ(D65) -> linear sRGB
  // matrix, so LibRaw's sRGB output reproduces the rendered values.
  const float xyzToCamera[9] = {3.2406f, -1.5372f, -0.4986f, -0.9689f, 1.8758f, 0.0415f, 0.0557f, -0.2040f, 1.0570f};
  TIFFSetField(tif, TIFFTAG_COLORMATRIX1, 9, xyzToCamera);
  TIFFSetField(tif, TIFFTAG_CALIBRATIONILLUMINANT1, 21);  // D65
  const float neutral[3] = {1, 1, 1};
  TIFFSetField(tif, TIFFTAG_ASSHOTNEUTRAL, 3, neutral);
  const float black = kBlack;
  TIFFSetField(tif, TIFFTAG_BLACKLEVEL, 1, &black);
  const std::uint32_t white = kWhite;
  TIFFSetField(tif, TIFFTAG_WHITELEVEL, 1, &white);
  TIFFSetField(tif, TIFFTAG_DATETIME, info.dateTimeOriginal.c_str());
  TIFFSetField(tif, TIFFTAG_EXIFIFD, static_cast<std::uint64_t>(0));

  std::vector<std::uint16_t> row(w);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      const int c = (y % 2 == 0) ? (x % 2 == 0 ? 0 : 1) : (x % 2 == 0 ? 1 : 2);
      const double v = kBlack + rgb.at(x, y, c) * double(kWhite - kBlack) / 65535.0;
      row[x] = static_cast<std::uint16_t>(v + 0.5);
    }
    if (TIFFWriteScanline(tif, row.data(), y, 0) < 0) {
      TIFFClose(tif);
      fail(path, "writing the pixels failed");
    }
  }
  if (!TIFFWriteDirectory(tif)) {
    TIFFClose(tif);
    fail(path, "writing IFD0 failed");
  }
  // EXIF sub-IFD, then point IFD0's ExifIFD tag at it.
  if (TIFFCreateEXIFDirectory(tif) != 0) {
    TIFFClose(tif);
    fail(path, "cannot create the EXIF directory");
  }
  TIFFSetField(tif, EXIFTAG_EXPOSURETIME, info.exposureSeconds);
  TIFFSetField(tif, EXIFTAG_FNUMBER, info.fNumber);
  const std::uint16_t iso = static_cast<std::uint16_t>(info.iso);
  TIFFSetField(tif, EXIFTAG_ISOSPEEDRATINGS, 1, &iso);
  TIFFSetField(tif, EXIFTAG_DATETIMEORIGINAL, info.dateTimeOriginal.c_str());
  TIFFSetField(tif, EXIFTAG_FOCALLENGTH, info.focalLengthMm);
  TIFFSetField(tif, EXIFTAG_BODYSERIALNUMBER, info.serial.c_str());
  TIFFSetField(tif, EXIFTAG_LENSMODEL, "Synthetic 50 mm");
  // A 6 micrometre pixel pitch: the perspective light model can use it.
  TIFFSetField(tif, EXIFTAG_FOCALPLANEXRESOLUTION, 1000.0 / 6.0);
  TIFFSetField(tif, EXIFTAG_FOCALPLANEYRESOLUTION, 1000.0 / 6.0);
  TIFFSetField(tif, EXIFTAG_FOCALPLANERESOLUTIONUNIT, 4);  // millimetres
  std::uint64_t exifOffset = 0;
  if (!TIFFWriteCustomDirectory(tif, &exifOffset)) {
    TIFFClose(tif);
    fail(path, "writing the EXIF directory failed");
  }
  TIFFSetDirectory(tif, 0);
  TIFFSetField(tif, TIFFTAG_EXIFIFD, exifOffset);
  if (!TIFFRewriteDirectory(tif)) {
    TIFFClose(tif);
    fail(path, "updating IFD0 failed");
  }
  TIFFClose(tif);
  out.commit();
}

}  // namespace surrogate::generator
