// Private to src/image: JPEG, PNG and TIFF (exports, and originals from cameras that write
// them), each through its own library called directly, after checking the file's structure
// (libjpeg decodes a truncated JPEG with only a warning and grey rows, so completeness is
// checked first by walking the format's own structure).
//
//   structure check -> libjpeg / libpng / libtiff, every warning through the library's own
//   hook (DecoderMessages) -> DecodedPixels (8-bit samples kept as bytes, 16-bit as Image;
//   Transfer::Srgb)
//
// The values are those OpenCV's imread gave (IMREAD_UNCHANGED | IMREAD_ANYDEPTH |
// IMREAD_IGNORE_ORIENTATION), which decoded these files before; OpenCV hides the libraries'
// warnings (it prints them, or drops them), which is why it is no longer the decoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "image/decode.h"
#include "image/decoder_messages.h"

namespace surrogate::image {

// Throws Error(Input) naming the file if its structure is incomplete or damaged; returns the
// size the structure declares.
ImageProbe checkExportStructure(const std::filesystem::path& path, SourceKind kind);

DecodedPixels decodeExport(const std::filesystem::path& path, SourceKind kind, DecodeReport* report,
                           const DecodeOptions& options);

// The decoders, on a file whose structure was checked (JPEG and PNG: its bytes, read once).
// Messages are collected into `messages`; the caller settles them. A decode stopped by a
// warning (refused by the caller) returns empty pixels.
DecodedPixels decodeJpeg(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size,
                         const DecodeOptions& options, DecoderMessages& messages);
DecodedPixels decodePng(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size,
                        const DecodeOptions& options, DecoderMessages& messages);
DecodedPixels decodeTiff(const std::filesystem::path& path, const DecodeOptions& options, DecoderMessages& messages);

}  // namespace surrogate::image
