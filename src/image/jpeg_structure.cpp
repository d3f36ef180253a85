#include "image/jpeg_structure.h"

#include <cstdint>
#include <cstring>

#include "core/atomic_file.h"

namespace surrogate::image {

namespace {

constexpr const char* kTruncated =
    "the file is truncated: the JPEG data stops before its end-of-image marker; copy it from "
    "the card again";

bool isStartOfFrame(std::uint8_t m) {
  // C0..CF are frame headers except C4 (Huffman tables), C8 (reserved) and CC (arithmetic tables).
  return m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
}

bool isStandalone(std::uint8_t m) { return m == 0x01 || (m >= 0xD0 && m <= 0xD7); }

// From `pos` inside entropy-coded data, the offset of the next real marker's FF, or `size`.
std::size_t skipEntropyData(const std::uint8_t* d, std::size_t size, std::size_t pos) {
  while (pos < size) {
    const void* ff = std::memchr(d + pos, 0xFF, size - pos);
    if (!ff) return size;
    pos = static_cast<std::size_t>(static_cast<const std::uint8_t*>(ff) - d);
    if (pos + 1 >= size) return size;
    const std::uint8_t next = d[pos + 1];
    if (next == 0x00 || (next >= 0xD0 && next <= 0xD7)) {
      pos += 2;  // a stuffed zero or a restart marker: still inside the scan
      continue;
    }
    if (next == 0xFF) {
      pos += 1;  // a fill byte; the marker code follows the run
      continue;
    }
    return pos;
  }
  return size;
}

}  // namespace

JpegStructure readJpegStructure(const std::filesystem::path& path) {
  const std::string bytes = readFile(path, "image probe");
  return readJpegStructure(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

JpegStructure readJpegStructure(const std::uint8_t* d, std::size_t size) {
  JpegStructure s;
  if (size < 4 || d[0] != 0xFF || d[1] != 0xD8) {
    s.problem = "is not a JPEG file (it does not start with the JPEG start-of-image marker)";
    return s;
  }
  bool sawFrame = false, sawScan = false;
  std::size_t pos = 2;
  while (true) {
    // Markers may be preceded by any number of FF fill bytes.
    if (pos >= size || d[pos] != 0xFF) {
      s.problem = pos >= size ? kTruncated : "the JPEG structure is damaged (data where a marker should be)";
      return s;
    }
    while (pos < size && d[pos] == 0xFF) ++pos;
    if (pos >= size) {
      s.problem = kTruncated;
      return s;
    }
    const std::uint8_t marker = d[pos++];
    if (marker == 0xD9) {
      if (!sawFrame || !sawScan) s.problem = "the JPEG holds no image data (no frame or scan before its end)";
      return s;
    }
    if (isStandalone(marker)) continue;
    if (pos + 2 > size) {
      s.problem = kTruncated;
      return s;
    }
    const std::size_t length = (std::size_t(d[pos]) << 8) | d[pos + 1];
    if (length < 2) {
      s.problem = "the JPEG structure is damaged (a segment with an impossible length)";
      return s;
    }
    if (pos + length > size) {
      s.problem = kTruncated;
      return s;
    }
    if (isStartOfFrame(marker) && !sawFrame) {
      if (length < 8) {
        s.problem = "the JPEG structure is damaged (a frame header too short)";
        return s;
      }
      s.height = (d[pos + 3] << 8) | d[pos + 4];
      s.width = (d[pos + 5] << 8) | d[pos + 6];
      s.components = d[pos + 7];
      sawFrame = true;
    }
    pos += length;
    if (marker == 0xDA) {
      sawScan = true;
      pos = skipEntropyData(d, size, pos);
      if (pos >= size) {
        s.problem = kTruncated;
        return s;
      }
    }
  }
}

}  // namespace surrogate::image
