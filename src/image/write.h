// Writing images for people to look at: PNG for results (normal maps, overlays, relit
// previews), JPEG for small previews, through libpng and libjpeg called directly. Atomic (temporary file, then rename), so a failed
// write never leaves a half file under the final name.
//
//   Image overlay = ...;                 // bitsPerSample 8 -> 8-bit PNG, 16 -> 16-bit PNG
//   writePng(overlay, "assembly-files/sphere-overlay.png");
//
// PNG bytes are deterministic for a given image and libdeflate version: fixed filter and
// compression level, no timestamp chunk (src/image/png_encoder.h). 16 -> 8 bits rounds to
// nearest: v8 = (v16 + 128) / 257.
#pragma once

#include <filesystem>
#include <string>

#include "core/image.h"

namespace surrogate::image {

// 8-bit PNG when image.bitsPerSample <= 8, else 16-bit; 1 or 3 channels.
void writePng(const Image& image, const std::filesystem::path& path);

// 8-bit JPEG (always; 16-bit values are rounded to 8), quality 1..100.
void writeJpeg(const Image& image, const std::filesystem::path& path, int quality);

// The JPEG file of 8-bit samples (1 or 3 channels, RGB), quality 1..100, with libjpeg's
// baseline defaults (4:2:0 chroma, standard Huffman tables): the bytes OpenCV's imencode gave
// with IMWRITE_JPEG_QUALITY alone. Throws Error naming `what` when it cannot be encoded.
std::string encodeJpeg(const Image8& image, int quality, const std::string& what);

std::string libdeflateVersion();  // "1.14": what compresses the PNG files written here

}  // namespace surrogate::image
