#include "image/png_structure.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/error.h"

namespace surrogate::image {

namespace {

std::uint32_t bigEndian32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

}  // namespace

PngStructure readPngStructure(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throwInputError(path.string(), "image probe", "cannot be opened for reading");
  const std::streamoff size = in.tellg();
  PngStructure s;
  // Signature (8) + IHDR chunk (4 length + 4 type + 13 data + 4 CRC) + IEND chunk (12).
  if (size < 8 + 25 + 12) {
    s.problem = "the file is truncated: it is too short to hold a PNG image";
    return s;
  }
  unsigned char head[33];
  in.seekg(0);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  if (bigEndian32(head + 8) != 13 || std::memcmp(head + 12, "IHDR", 4) != 0) {
    s.problem = "the PNG structure is damaged (its first chunk is not the image header)";
    return s;
  }
  s.width = static_cast<int>(bigEndian32(head + 16));
  s.height = static_cast<int>(bigEndian32(head + 20));
  s.bitDepth = head[24];
  // IEND is normally the last 12 bytes; tolerate a little trailing padding some tools add.
  const std::streamoff tailSize = std::min<std::streamoff>(size, 4096);
  std::vector<char> tail(static_cast<std::size_t>(tailSize));
  in.seekg(size - tailSize);
  in.read(tail.data(), tailSize);
  static const char kIend[] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', char(0xAE), 0x42, 0x60, char(0x82)};
  if (std::search(tail.begin(), tail.end(), std::begin(kIend), std::end(kIend)) == tail.end())
    s.problem = "the file is truncated: the PNG has no end chunk (IEND); copy it again";
  return s;
}

}  // namespace surrogate::image
