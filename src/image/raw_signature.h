// Private to src/image: recognising camera raw containers by their first bytes.
//
//   'II' 2A 00 / 'MM' 00 2A     TIFF-structured: DNG, CR2, NEF, ARW, PEF, ...
//   'II' 1A 00 00 00 HEAPCCDR   Canon CRW (CIFF)          .... ftyp crx    Canon CR3
//   FUJIFILM  Fujifilm RAF      IIRO / IIRS / MMOR  Olympus ORF     IIU\0  Panasonic RW2
//   FOVb      Sigma X3F         \0MRM  Minolta MRW
#pragma once

#include <filesystem>

namespace surrogate::image {

enum class RawContainer { None, Tiff, Ciff, Cr3, Other };

// From the first 16 bytes; None when they match no raw container (or cannot be read).
RawContainer rawContainerOf(const unsigned char* head, std::size_t size);
RawContainer rawContainerOf(const std::filesystem::path& path);

}  // namespace surrogate::image
