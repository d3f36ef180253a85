// Decoding photographs: camera raw and DNG through LibRaw, JPEG/TIFF/PNG through OpenCV.
//
// Every LibRaw setting that changes pixels is fixed by RawDecodeSettings, which the pipeline
// records in the carrier and re-applies on re-execution, so decoding is deterministic:
//
//   RawDecodeSettings settings;                 // AHD demosaic, as-shot white balance, sRGB
//   DecodeReport report;                        // primaries, linear gamma, no auto-brightening
//   Image im = decodeImage("IMG_0001.dng", settings, &report);
//
// Errors name the file and say what is wrong in a photographer's words.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace surrogate::image {

enum class SourceKind { CameraRaw, Jpeg, Tiff, Png };

// True for the extensions of camera raw formats (.cr2, .nef, .dng, ...), case-insensitive.
bool isCameraRawExtension(const std::filesystem::path& path);

// What the file is, by its first bytes (then its extension for raw formats built on TIFF).
// Throws Error(Input) naming the file when it is not an image Surrogate reads.
SourceKind classifyImageFile(const std::filesystem::path& path);

struct RawDecodeSettings {
  std::string demosaic = "AHD";          // linear, VNG, PPG, AHD, DCB: quality against time
  std::string whiteBalance = "camera";   // camera (as shot), daylight, none (unity)
  std::string outputColorSpace = "srgb"; // srgb (linear sRGB primaries) or raw (camera space)
  int highlightMode = 0;                 // 0 clip, 1 unclip, 2 blend, 3+ rebuild
  int outputBits = 16;                   // always 16: the precision the fit works in
  bool noAutoBright = true;              // never rescale by a histogram (not deterministic
                                         // across captures, and changes the data)
  bool halfSize = false;                 // half resolution without demosaicing (fast preview)

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  // Missing names keep their defaults; unknown names or values are Error(Usage).
  static RawDecodeSettings fromParameters(const std::vector<std::pair<std::string, std::string>>& p);
};

struct ImageProbe {
  int width = 0;
  int height = 0;
  SourceKind kind = SourceKind::Jpeg;
};

// Checks that the file is a readable, complete image and returns its size, without decoding
// the pixels where the format allows. Truncated or unreadable files are Error(Input).
ImageProbe probeImage(const std::filesystem::path& path);

struct DecodeReport {
  std::string decoder;  // "LibRaw 0.20.2" or "OpenCV 4.6.0"
  int blackLevel = -1;  // camera raw only: the levels LibRaw used
  int whiteLevel = -1;
  std::vector<double> whiteBalanceMultipliers;  // camera raw only: R, G, B, G2
};

// Decodes the whole image. Camera raw: linear 16-bit RGB (Transfer::Linear). Others: as stored
// (Transfer::Srgb; 8-bit widened by 257; grey stays one channel; alpha dropped). Safe to call
// from several threads at once.
Image decodeImage(const std::filesystem::path& path, const RawDecodeSettings& settings,
                  DecodeReport* report = nullptr);

// Writes an 8-bit (bitsPerSample 8) or 16-bit PNG, atomically, with fixed compression so the
// bytes are the same for the same image.
void writePng(const Image& image, const std::filesystem::path& path);
// Writes an 8-bit JPEG, atomically.
void writeJpeg(const Image& image, const std::filesystem::path& path, int quality);

// Linear 16-bit values to sRGB-encoded 16-bit (the sRGB transfer function), any channel count.
Image srgbEncode(const Image& linear);

std::string librawVersion();
std::string opencvVersion();

}  // namespace surrogate::image
