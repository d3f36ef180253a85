// Decoding photographs: camera raw and DNG through LibRaw, JPEG/TIFF/PNG through OpenCV.
//
// The folder's front door: including it gives the whole public interface of src/image.
//
//   camera raw, DNG --LibRaw, RawDecodeSettings--> linear 16-bit RGB      (Transfer::Linear)
//   JPEG, TIFF, PNG --OpenCV, pixels as stored---> 8/16-bit grey or RGB   (Transfer::Srgb)
//
// Every LibRaw setting that changes pixels is fixed by RawDecodeSettings, which the pipeline
// records in the carrier and re-applies on re-execution, so decoding is deterministic:
//
//   RawDecodeSettings settings;                   // AHD, as-shot white balance, linear sRGB
//   DecodeReport report;
//   Image im = decodeImage("IMG_0001.dng", settings, &report);
//   // report.decoder == "LibRaw 0.20.2-Release", report.blackLevel, report.whiteLevel, ...
//
// Errors are surrogate::Error(Input) naming the file, with a sentence a photographer can act
// on ("the file is truncated ..."). No library prints to the terminal.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "image/raw_settings.h"
#include "image/source_kind.h"
#include "image/srgb.h"
#include "image/write.h"

namespace surrogate::image {

struct ImageProbe {
  int width = 0;   // as decodeImage returns it with default settings
  int height = 0;
  SourceKind kind = SourceKind::Jpeg;
};

// Checks that the file is a readable, complete image and returns its size without decoding
// pixels: JPEG markers up to end-of-image, PNG header and end chunk, TIFF strip table, LibRaw's
// header parse for raw. Missing, empty, truncated or unsupported files are Error(Input).
// (A raw whose pixel data is damaged inside an intact container is found by decodeImage.)
ImageProbe probeImage(const std::filesystem::path& path);

struct DecodeReport {
  std::string decoder;  // "LibRaw 0.20.2-Release" or "OpenCV 4.6.0"
  int blackLevel = -1;  // camera raw only: the black level subtracted (file's, or the override)
  int whiteLevel = -1;  // camera raw only: the white (saturation) level scaled to 65535
  // Camera raw only: the black level subtracted from each channel (R, G, B, G2): the common
  // level plus the file's per-channel offsets (all equal to blackLevel when overridden).
  std::vector<int> channelBlackLevels;
  std::vector<double> whiteBalanceMultipliers;  // camera raw only: applied R, G, B, G2 (G = 1)
  std::vector<std::string> warnings;            // e.g. no as-shot white balance in the file
};

// Decodes the whole image. Camera raw: linear 16-bit RGB (or grey for monochrome sensors).
// Others: as stored (8-bit widened by 257, bitsPerSample kept; grey stays one channel; alpha
// dropped; the EXIF orientation tag is not applied). Safe to call from several threads at once.
Image decodeImage(const std::filesystem::path& path, const RawDecodeSettings& settings,
                  DecodeReport* report = nullptr);

std::string librawVersion();  // "0.20.2-Release" (LibRaw::version())
std::string opencvVersion();  // "4.6.0"

}  // namespace surrogate::image
