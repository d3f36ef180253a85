#include "image/png_structure.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/error.h"

namespace surrogate::image {

namespace {

std::uint32_t bigEndian32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

}  // namespace

PngStructure readPngStructure(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throwInputError(path.string(), "image probe", "cannot be opened for reading");
  const std::streamoff size = in.tellg();
  if (size < 8 + 25 + 12) return pngStructureOf(nullptr, 0, nullptr, 0, static_cast<std::uint64_t>(std::max<std::streamoff>(size, 0)));
  // The header and the last 4 KB are all the check reads.
  std::string bytes(static_cast<std::size_t>(std::min<std::streamoff>(size, 33)), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  const std::streamoff tailSize = std::min<std::streamoff>(size, 4096);
  std::string tail(static_cast<std::size_t>(tailSize), '\0');
  in.seekg(size - tailSize);
  in.read(tail.data(), tailSize);
  if (!in) throwInputError(path.string(), "image probe", "cannot be read");
  return pngStructureOf(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                        reinterpret_cast<const std::uint8_t*>(tail.data()), tail.size(),
                        static_cast<std::uint64_t>(size));
}

PngStructure readPngStructure(const std::uint8_t* data, std::size_t size) {
  const std::size_t tail = std::min<std::size_t>(size, 4096);
  return pngStructureOf(data, std::min<std::size_t>(size, 33), data + size - tail, tail, size);
}

PngStructure pngStructureOf(const std::uint8_t* head, std::size_t headSize, const std::uint8_t* tail,
                            std::size_t tailSize, std::uint64_t size) {
  PngStructure s;
  // Signature (8) + IHDR chunk (4 length + 4 type + 13 data + 4 CRC) + IEND chunk (12).
  if (size < 8 + 25 + 12 || headSize < 33) {
    s.problem = "the file is truncated: it is too short to hold a PNG image";
    return s;
  }
  if (bigEndian32(head + 8) != 13 || std::memcmp(head + 12, "IHDR", 4) != 0) {
    s.problem = "the PNG structure is damaged (its first chunk is not the image header)";
    return s;
  }
  s.width = static_cast<int>(bigEndian32(head + 16));
  s.height = static_cast<int>(bigEndian32(head + 20));
  s.bitDepth = head[24];
  // IEND is normally the last 12 bytes; tolerate a little trailing padding some tools add.
  static const std::uint8_t kIend[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  if (std::search(tail, tail + tailSize, std::begin(kIend), std::end(kIend)) == tail + tailSize)
    s.problem = "the file is truncated: the PNG has no end chunk (IEND); copy it again";
  return s;
}

}  // namespace surrogate::image
