// What kind of photograph a file holds, decided by its content before its name.
//
//   FF D8 FF            -> Jpeg
//   89 'PNG' 0D 0A 1A 0A -> Png
//   'II' 2A 00 / 'MM' 00 2A -> Tiff, or CameraRaw when it is a DNG (DNGVersion tag 50706) or has
//                          a raw extension (CR2, NEF, ARW, PEF, ... are TIFF-structured)
//   other raw signatures (CRW, CR3, RAF, ORF, RW2, X3F, MRW) or a raw extension -> CameraRaw
//
//   if (classifyImageFile(p) == SourceKind::CameraRaw) ...   // LibRaw decodes it
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>

namespace surrogate::image {

enum class SourceKind { CameraRaw, Jpeg, Tiff, Png };

// True for the extensions of camera raw formats (.cr2, .nef, .dng, ...), case-insensitive.
bool isCameraRawExtension(const std::filesystem::path& path);

// Jpeg or Png when the bytes start with that format's signature (above), else nothing: how
// both files and pictures held in memory are told apart.
std::optional<SourceKind> jpegOrPngBySignature(const std::uint8_t* head, std::size_t size);

// Throws Error(Input) naming the file when it is missing, unreadable, empty, or not an image
// Surrogate reads.
SourceKind classifyImageFile(const std::filesystem::path& path);

// True when the file is a DNG by its content (a TIFF whose IFD0 has the DNGVersion tag),
// whatever its name. Never throws (false for a file that cannot be read).
bool isDngFile(const std::filesystem::path& path);

}  // namespace surrogate::image
