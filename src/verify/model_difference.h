// How far apart two fitted models (.ptm or .rti files) are, when their bytes differ.
//
//   coefficient difference: max and RMS of |a_k - b_k| over every texel, term and channel,
//                           in the format's decoded units (PTM: 0..255, HSH: 0..1)
//   render PSNR:            10 log10(255^2 / MSE) of relit 8-bit images, the worst of five
//                           lights (overhead and four raking lights); infinite when identical
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace surrogate::verify {

struct ModelDifference {
  bool comparable = false;  // same kind, format and size
  std::string why;          // when not comparable
  double maxCoefficient = 0, rmsCoefficient = 0;
  double renderPsnr = 0;    // dB; +inf when the renders are identical
  std::string describe() const;
};

// Reads both files (.ptm or .rti, by their first bytes); Error(Input) when one cannot be read.
ModelDifference compareModels(const std::filesystem::path& recorded,
                              const std::filesystem::path& reproduced);

// How far apart two images (.png, .jpg, .tif outputs: normal maps, previews, overlays) are:
// max difference and PSNR in 8-bit levels. Error(Input) when one cannot be decoded.
std::string compareImages(const std::filesystem::path& recorded,
                          const std::filesystem::path& reproduced);

}  // namespace surrogate::verify
