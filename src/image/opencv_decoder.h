// Private to src/image: JPEG, TIFF and PNG through OpenCV's imread, after checking the file's
// structure (OpenCV decodes a truncated JPEG with only a warning on stderr and grey rows, so
// completeness is checked first by walking the format's own structure).
//
//   structure check -> cv::imread(UNCHANGED | ANYDEPTH | IGNORE_ORIENTATION) -> BGR to RGB
//   -> Image (8-bit widened by 257, Transfer::Srgb)
#pragma once

#include <filesystem>

#include "image/decode.h"

namespace surrogate::image {

// Throws Error(Input) naming the file if its structure is incomplete or damaged; returns the
// size the structure declares.
ImageProbe checkExportStructure(const std::filesystem::path& path, SourceKind kind);

Image decodeExport(const std::filesystem::path& path, SourceKind kind, DecodeReport* report);

}  // namespace surrogate::image
