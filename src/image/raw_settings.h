// RawDecodeSettings: every LibRaw setting that changes the pixels of a decoded camera raw.
//
// Decoding a raw file is a chain of choices (black subtraction, white balance, demosaicing,
// colour matrix, orientation). The pipeline records the settings in the carrier as name=value
// pairs and re-applies them on re-execution, so a package can be decoded again bit for bit:
//
//   RawDecodeSettings s;                      // AHD, as-shot white balance, linear sRGB
//   s.demosaic = "DCB";
//   auto recorded = s.toParameters();         // [("demosaic","DCB"), ("whiteBalance","camera"), ...]
//   RawDecodeSettings again = RawDecodeSettings::fromParameters(recorded);
//
// Settings that Surrogate never varies (linear gamma, 16-bit output, brightness 1, no
// chromatic-aberration or exposure correction, the file's first image, no dark frame or
// bad-pixel map) are recorded too, as fixed values, so the record is complete; fromParameters
// refuses any other value for them.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace surrogate::image {

struct RawDecodeSettings {
  // Demosaicing: "linear" (bilinear, fastest, soft), "VNG", "PPG", "AHD" (default: sharp, few
  // artefacts, about 2x the time of linear), "DCB".
  std::string demosaic = "AHD";
  // DCB only: refinement passes (0 = LibRaw's single pass) and its false-colour enhancement.
  int dcbIterations = 0;
  bool dcbEnhance = false;
  // Post-demosaic 3x3 median passes on colour differences: removes colour moire, softens
  // colour edges. 0 keeps the demosaiced values.
  int medianPasses = 0;
  // Interpolate the two greens as separate colours: fixes maze patterns on some sensors.
  bool fourColorRgb = false;
  // Equalise the two green channels before demosaicing (helps sensors with unequal greens).
  bool greenMatching = false;
  // Wavelet denoising threshold (LibRaw -n); 0 = off. Denoising changes the shading the fit sees.
  double noiseThreshold = 0.0;

  // White balance: "camera" (as-shot multipliers), "daylight" (the camera's daylight
  // multipliers), "none" (unity: raw channel ratios, for radiometric work).
  std::string whiteBalance = "camera";
  // "srgb": camera RGB converted to linear sRGB primaries; "raw": camera RGB, no matrix.
  std::string outputColorSpace = "srgb";
  // Which camera-to-XYZ matrix converts colour: "auto" (LibRaw default: the file's embedded
  // matrix with as-shot white balance, else LibRaw's built-in table), "embedded" (always the
  // file's), "builtin" (always LibRaw's table).
  std::string colorMatrix = "auto";
  // Highlights: 0 clip (default; clipped areas stay neutral), 1 unclip, 2 blend, 3..9 rebuild.
  int highlightMode = 0;

  // Levels: -1 uses the file's black and white levels; a value overrides them (LibRaw -k / -S).
  int blackLevel = -1;
  int whiteLevel = -1;
  // LibRaw by default lowers the white level to the image's brightest value when that exceeds
  // this fraction of it (0.75), which scales each photograph differently: fatal for RTI, whose
  // photographs must share one radiometric scale. 0 disables it (default).
  double adjustMaximumThreshold = 0.0;
  // Never rescale by the histogram (LibRaw's auto-brightening differs from shot to shot).
  bool noAutoBright = true;

  // "as-stored" (default): pixels in sensor order, like JPEGs read with their orientation tag
  // ignored, so raw and exported files of one capture share pixel coordinates. "camera":
  // rotated as the camera's orientation tag says.
  std::string orientation = "as-stored";
  // Half resolution, each 2x2 Bayer cell one pixel, no demosaicing: 4x fewer pixels, 4x faster.
  bool halfSize = false;

  int outputBits = 16;  // fixed: the precision the fit works in

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  // Missing names keep their defaults; unknown names or values are Error(Usage).
  static RawDecodeSettings fromParameters(const std::vector<std::pair<std::string, std::string>>& p);
};

}  // namespace surrogate::image
