// Private to src/image: the size and completeness of a PNG file, read without decoding it.
//
//   89 50 4E 47 0D 0A 1A 0A | len "IHDR" width height depth colour ... | ... | 0 "IEND" AE426082
//
// The IHDR chunk comes first and gives the size; a complete file ends with the IEND chunk.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace surrogate::image {

struct PngStructure {
  int width = 0;
  int height = 0;
  int bitDepth = 0;
  std::string problem;  // empty when the file is complete; else a sentence for the user
};

PngStructure readPngStructure(const std::filesystem::path& path);
// The same, of a file already in memory.
PngStructure readPngStructure(const std::uint8_t* data, std::size_t size);
// From the file's first `headSize` (at least 33) bytes, its last `tailSize` (up to 4096) bytes
// and its size.
PngStructure pngStructureOf(const std::uint8_t* head, std::size_t headSize, const std::uint8_t* tail,
                            std::size_t tailSize, std::uint64_t size);

}  // namespace surrogate::image
