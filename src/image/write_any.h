// Writing a picture in the format its file name asks for, for commands whose output the user
// names (surrogate render -o OUT): .png (PNG), .jpg or .jpeg (JPEG), .tif or .tiff (TIFF).
// Atomic like write.h's writers.
//
//   if (!image::pictureFormatFor(out)) ... refuse the name ...
//   image::writePicture(relit, out, 95);   // relit.jpg: JPEG quality 95
//
// TIFF: uncompressed, 8-bit when image.bitsPerSample <= 8 else 16-bit, 1 or 3 channels, no
// time stamp (the same pixels give the same bytes).
#pragma once

#include <filesystem>
#include <optional>

#include "core/image.h"

namespace surrogate::image {

enum class PictureFormat { Png, Jpeg, Tiff };

// By the extension, in any letter case; nullopt for any other name.
std::optional<PictureFormat> pictureFormatFor(const std::filesystem::path& path);
const char* pictureFormatName(PictureFormat format);  // "PNG", "JPEG", "TIFF"

void writeTiff(const Image& image, const std::filesystem::path& path);

// Writes `image` in the format of `path`'s extension (JPEG with `jpegQuality`, 1..100).
// Throws Error(Usage) naming the path for any other extension.
void writePicture(const Image& image, const std::filesystem::path& path, int jpegQuality = 95);

}  // namespace surrogate::image
