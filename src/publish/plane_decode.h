// Private to src/publish: decoding one coefficient plane of a web layout (a JPEG) into three
// 8-bit values per pixel, as a browser hands them to the viewers' shaders.
//
// A plane Surrogate writes is coded in JPEG's RGB colour space (rgb_jpeg.h): libjpeg returns
// its components with no transform, the bytes the encoder was given up to the compression
// error. A plane another tool coded as YCbCr (relight may) or greyscale is converted to RGB
// by libjpeg, as a browser converts it. The size in the JPEG's header is checked against the
// size the layout gives before any pixel is decoded; every warning libjpeg gives about damaged
// data is an error, as in src/image's decoders.
//
//   std::vector<std::uint8_t> rgb = decodePlaneJpeg(bytes, width, height, "web/plane_0.jpg");
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace surrogate::publish {

// A JPEG of w x h texels is at most w * h * kMaxJpegBytesPerTexel + kJpegHeaderBytes bytes: at
// quality 100 pure noise takes under 1.5 bytes a value (4.5 a texel); a larger file is not a
// plane of that size, and is refused before it is read.
constexpr std::uintmax_t kMaxJpegBytesPerTexel = 6;
constexpr std::uintmax_t kJpegHeaderBytes = 1u << 20;

// Throws Error(Input) naming `file` when `bytes` is not a JPEG libjpeg decodes without a
// warning, or is not `width` x `height`. Returns RGBRGB..., rows top-first.
std::vector<std::uint8_t> decodePlaneJpeg(const std::string& bytes, int width, int height, const std::string& file);

}  // namespace surrogate::publish
