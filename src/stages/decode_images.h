// Decoding a list of images once into the two streaming stacks the pipeline reads:
//   rgb        display-referred (sRGB-encoded) 16-bit RGB: what the fitters read
//   luminance  Rec. 709 luminance of the decoded values (linear for camera raw): what sphere
//              and highlight detection read
// Images are decoded in parallel, as many at once as the threads and the memory budget allow;
// the stacks and the per-image reports are in input order whatever the thread count.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/stack.h"
#include "image/decode.h"
#include "pipeline/context.h"

namespace surrogate::stages {

struct DecodedImage {
  image::DecodeReport report;
  int width = 0, height = 0, channels = 0, bitsPerSample = 0;
  Transfer transfer = Transfer::Srgb;
  std::string pixelSha256;  // of the decoded pixels, before any conversion
};

struct DecodedStacks {
  std::shared_ptr<ImageStack> rgb;
  std::shared_ptr<ImageStack> luminance;
  std::vector<DecodedImage> images;
};

DecodedStacks decodeImages(const std::vector<std::filesystem::path>& files,
                           const image::RawDecodeSettings& settings,
                           const pipeline::RunSettings& run);

}  // namespace surrogate::stages
