// Damaged images, made from sound ones the way damage happens: a copy cut short with its end
// marker patched back, bits flipped on a card, a PNG chunk's CRC broken, a TIFF strip table that
// promises less data than the image needs, a raw tile overwritten. Shared by the image tests,
// the end-to-end tests and the fuzz corpus (fuzz/corpus/image/SOURCE.md).
//
// Also a tiny DNG writer with lossless-JPEG tiles (compression 7, as cameras and Adobe's DNG
// Converter write them), since the generator's DNGs are uncompressed and damage to
// uncompressed raw data cannot be detected by any decoder.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace surrogate::test {

inline std::string readBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// Offset of the first byte of a JPEG's entropy-coded data (after its first SOS segment).
inline std::size_t jpegScanStart(const std::string& jpeg) {
  std::size_t pos = 2;
  while (pos + 4 <= jpeg.size()) {
    if (static_cast<unsigned char>(jpeg[pos]) != 0xFF) throw std::runtime_error("not a JPEG marker");
    const unsigned char marker = static_cast<unsigned char>(jpeg[pos + 1]);
    const std::size_t length = (std::size_t(static_cast<unsigned char>(jpeg[pos + 2])) << 8) |
                               static_cast<unsigned char>(jpeg[pos + 3]);
    pos += 2 + length;
    if (marker == 0xDA) return pos;
  }
  throw std::runtime_error("no scan in the JPEG");
}

// The case: half the entropy-coded data gone, the end-of-image marker appended again.
// The marker structure is whole; libjpeg runs out of data and warns ("Corrupt JPEG data:
// premature end of data segment"), and would fill the rest with grey.
inline std::string halfJpeg(const std::string& jpeg) {
  const std::size_t scan = jpegScanStart(jpeg);
  std::string cut = jpeg.substr(0, scan + (jpeg.size() - scan) / 2);
  while (!cut.empty() && static_cast<unsigned char>(cut.back()) == 0xFF) cut.pop_back();  // no dangling FF
  return cut + "\xFF\xD9";
}

// `flips` bits of the entropy-coded data flipped at positions drawn from `seed` (never making a
// 0xFF byte, which would be a marker: the structure check would refuse the file before libjpeg
// saw it).
inline std::string flipJpegBits(const std::string& jpeg, std::uint32_t seed, int flips) {
  std::string out = jpeg;
  const std::size_t scan = jpegScanStart(jpeg);
  const std::size_t span = jpeg.size() - 2 - scan;  // not the EOI marker
  std::uint32_t state = seed * 2654435761u + 1;
  for (int i = 0; i < flips;) {
    state = state * 1664525u + 1013904223u;
    const std::size_t at = scan + (state >> 8) % span;
    const unsigned char before = static_cast<unsigned char>(out[at]);
    const unsigned char after = before ^ static_cast<unsigned char>(1u << (state & 7));
    // Neither a new marker nor a change to a stuffed FF 00 pair.
    if (after == 0xFF || before == 0xFF || (at > 0 && static_cast<unsigned char>(out[at - 1]) == 0xFF)) continue;
    out[at] = static_cast<char>(after);
    ++i;
  }
  return out;
}

// The CRC of the PNG's first chunk of type `type` ("IDAT", or an ancillary one) broken.
inline std::string pngWithBadCrc(const std::string& png, const char* type = "IDAT") {
  std::string out = png;
  const std::size_t at = out.find(type, 8);
  if (at == std::string::npos) throw std::runtime_error("no such chunk");
  const std::size_t length = (std::size_t(static_cast<unsigned char>(out[at - 4])) << 24) |
                             (std::size_t(static_cast<unsigned char>(out[at - 3])) << 16) |
                             (std::size_t(static_cast<unsigned char>(out[at - 2])) << 8) |
                             static_cast<unsigned char>(out[at - 1]);
  out[at + 4 + length] = static_cast<char>(out[at + 4 + length] ^ 0x5A);
  return out;
}

namespace detail {
inline std::uint32_t le32(const std::string& b, std::size_t at) {
  return std::uint32_t(static_cast<unsigned char>(b[at])) | std::uint32_t(static_cast<unsigned char>(b[at + 1])) << 8 |
         std::uint32_t(static_cast<unsigned char>(b[at + 2])) << 16 | std::uint32_t(static_cast<unsigned char>(b[at + 3])) << 24;
}
inline std::uint16_t le16(const std::string& b, std::size_t at) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) | static_cast<unsigned char>(b[at + 1]) << 8);
}
inline void put32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<char>(v >> (8 * i));
}
inline void put16(std::string& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<char>(v);
  b[at + 1] = static_cast<char>(v >> 8);
}
}  // namespace detail

// A little-endian TIFF whose last strip's byte count (StripByteCounts) is cut to a third: every
// byte is still in the file, but the table says the strip ends early, as when a copy tool or an
// editor wrote a short strip. libtiff reports it when it decodes that strip.
inline std::string tiffWithShortStrip(const std::string& tiff) {
  using namespace detail;
  if (tiff.compare(0, 4, std::string("II*\0", 4)) != 0) throw std::runtime_error("not a little-endian TIFF");
  std::string out = tiff;
  const std::uint32_t ifd = le32(out, 4);
  const std::uint16_t entries = le16(out, ifd);
  for (std::uint16_t e = 0; e < entries; ++e) {
    const std::size_t at = ifd + 2 + 12 * std::size_t(e);
    if (le16(out, at) != 279) continue;  // StripByteCounts
    const std::uint16_t type = le16(out, at + 2);
    const std::uint32_t count = le32(out, at + 4);
    const std::size_t size = type == 3 ? 2 : 4;
    const std::size_t values = count * size <= 4 ? at + 8 : le32(out, at + 8);
    const std::size_t last = values + (count - 1) * size;
    if (size == 2) put16(out, last, static_cast<std::uint16_t>(le16(out, last) / 3));
    else put32(out, last, le32(out, last) / 3);
    return out;
  }
  throw std::runtime_error("no StripByteCounts");
}

// ---- Headers declaring huge sizes ----------------------------------------------------------

inline std::uint32_t crc32(const std::string& data) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : data) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

// `jpeg` (a small sound JPEG) with its frame header saying w x h: a few hundred bytes that
// declare any size (the entropy data is the small image's).
inline std::string jpegDeclaring(const std::string& jpeg, int w, int h) {
  std::string out = jpeg;
  std::size_t pos = 2;
  while (pos + 9 < out.size()) {
    const unsigned char marker = static_cast<unsigned char>(out[pos + 1]);
    const std::size_t length = (std::size_t(static_cast<unsigned char>(out[pos + 2])) << 8) |
                               static_cast<unsigned char>(out[pos + 3]);
    if (marker >= 0xC0 && marker <= 0xC2) {
      out[pos + 5] = static_cast<char>(h >> 8);
      out[pos + 6] = static_cast<char>(h & 0xFF);
      out[pos + 7] = static_cast<char>(w >> 8);
      out[pos + 8] = static_cast<char>(w & 0xFF);
      return out;
    }
    pos += 2 + length;
  }
  throw std::runtime_error("no frame header");
}

// A complete, 57-byte PNG (RGB, 8 bits) whose header declares w x h; its one IDAT chunk holds an
// empty zlib stream. Every chunk's CRC is right.
inline std::string pngDeclaring(std::uint32_t w, std::uint32_t h) {
  auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
  };
  const std::string ihdr = be32(w) + be32(h) + std::string("\x08\x02\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1A\n", 8) + chunk("IHDR", ihdr) +
         chunk("IDAT", std::string("\x78\x9C\x03\x00\x00\x00\x00\x01", 8)) + chunk("IEND", "");
}

// ---- A DNG with lossless-JPEG tiles --------------------------------------------------------

namespace detail {

// Lossless JPEG (ITU T.81 annex H, SOF3), predictor 1, one component, one Huffman table in
// which every difference category 0..16 has a 5-bit code: what LibRaw's ljpeg decoder reads.
inline std::string losslessJpeg(const std::vector<std::uint16_t>& samples, int w, int h, int bits) {
  std::string out = "\xFF\xD8";
  auto segment = [&](unsigned char marker, const std::string& body) {
    out += '\xFF';
    out += static_cast<char>(marker);
    out += static_cast<char>((body.size() + 2) >> 8);
    out += static_cast<char>((body.size() + 2) & 0xFF);
    out += body;
  };
  std::string dht(1, '\0');  // class 0, table 0
  for (int len = 1; len <= 16; ++len) dht += static_cast<char>(len == 5 ? 17 : 0);
  for (int s = 0; s <= 16; ++s) dht += static_cast<char>(s);
  segment(0xC4, dht);
  std::string sof;
  sof += static_cast<char>(bits);
  sof += static_cast<char>(h >> 8);
  sof += static_cast<char>(h & 0xFF);
  sof += static_cast<char>(w >> 8);
  sof += static_cast<char>(w & 0xFF);
  sof += std::string("\x01\x01\x11\x00", 4);
  segment(0xC3, sof);
  segment(0xDA, std::string("\x01\x01\x00\x01\x00\x00", 6));  // Ss = predictor 1
  std::uint32_t acc = 0;
  int filled = 0;
  auto emit = [&](std::uint32_t value, int count) {
    for (int i = count - 1; i >= 0; --i) {
      acc = (acc << 1) | ((value >> i) & 1);
      if (++filled == 8) {
        out += static_cast<char>(acc);
        if (acc == 0xFF) out += '\0';
        acc = 0;
        filled = 0;
      }
    }
  };
  int above = 1 << (bits - 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int value = samples[static_cast<std::size_t>(y) * w + x];
      const int pred = x == 0 ? above : samples[static_cast<std::size_t>(y) * w + x - 1];
      if (x == 0) above = value;
      const int diff = value - pred;
      int category = 0;
      for (int m = diff < 0 ? -diff : diff; m; m >>= 1) ++category;
      emit(static_cast<std::uint32_t>(category), 5);
      if (category) emit(static_cast<std::uint32_t>(diff < 0 ? diff + (1 << category) - 1 : diff), category);
    }
  if (filled) emit(0x7F, 8 - filled);  // pad with ones
  out += "\xFF\xD9";
  return out;
}

}  // namespace detail

struct LosslessDng {
  std::string bytes;
  std::vector<std::size_t> tileOffsets, tileSizes;  // where each tile's JPEG is in `bytes`
};

// A 12-bit RGGB DNG of w x h (multiples of `tile`, itself a multiple of 16) in lossless-JPEG
// tiles, holding a smooth pattern. Little-endian classic TIFF, written byte by byte.
inline LosslessDng losslessDng(int w, int h, int tile = 16) {
  using namespace detail;
  const int bits = 12;
  std::vector<std::string> tiles;
  for (int ty = 0; ty < h; ty += tile)
    for (int tx = 0; tx < w; tx += tile) {
      std::vector<std::uint16_t> s(static_cast<std::size_t>(tile) * tile);
      for (int y = 0; y < tile; ++y)
        for (int x = 0; x < tile; ++x)
          s[static_cast<std::size_t>(y) * tile + x] =
              static_cast<std::uint16_t>(256 + ((tx + x) * 23 + (ty + y) * 17 + ((x ^ y) & 1) * 300) % 3500);
      tiles.push_back(losslessJpeg(s, tile, tile, bits));
    }
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count;
    std::string data;  // little-endian values
  };
  auto shorts = [](std::initializer_list<std::uint16_t> v) {
    std::string d;
    for (std::uint16_t x : v) d += std::string{static_cast<char>(x & 0xFF), static_cast<char>(x >> 8)};
    return d;
  };
  auto longs = [](const std::vector<std::uint32_t>& v) {
    std::string d;
    for (std::uint32_t x : v)
      for (int i = 0; i < 4; ++i) d += static_cast<char>(x >> (8 * i));
    return d;
  };
  auto rationals = [&](std::initializer_list<double> v) {
    std::vector<std::uint32_t> parts;
    for (double x : v) {
      parts.push_back(static_cast<std::uint32_t>(static_cast<std::int32_t>(x * 10000)));
      parts.push_back(10000);
    }
    return longs(parts);
  };
  std::vector<Entry> entries = {
      {254, 4, 1, longs({0})},
      {256, 4, 1, longs({static_cast<std::uint32_t>(w)})},
      {257, 4, 1, longs({static_cast<std::uint32_t>(h)})},
      {258, 3, 1, shorts({bits})},
      {259, 3, 1, shorts({7})},
      {262, 3, 1, shorts({32803})},
      {271, 2, 10, std::string("Surrogate\0", 10)},
      {272, 2, 10, std::string("Lossless\0\0", 10)},
      {274, 3, 1, shorts({1})},
      {277, 3, 1, shorts({1})},
      {284, 3, 1, shorts({1})},
      {322, 4, 1, longs({static_cast<std::uint32_t>(tile)})},
      {323, 4, 1, longs({static_cast<std::uint32_t>(tile)})},
      {324, 4, static_cast<std::uint32_t>(tiles.size()), {}},
      {325, 4, static_cast<std::uint32_t>(tiles.size()), {}},
      {33421, 3, 2, shorts({2, 2})},
      {33422, 1, 4, std::string("\x00\x01\x01\x02", 4)},
      {50706, 1, 4, std::string("\x01\x04\x00\x00", 4)},
      {50707, 1, 4, std::string("\x01\x01\x00\x00", 4)},
      {50708, 2, 19, std::string("Surrogate Lossless\0", 19)},
      {50714, 3, 1, shorts({64})},
      {50717, 3, 1, shorts({4095})},
      {50721, 10, 9, rationals({3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570})},
      {50728, 5, 3, rationals({1, 1, 1})},
      {50778, 3, 1, shorts({21})},
  };
  LosslessDng dng;
  std::string& b = dng.bytes;
  b = std::string("II*\0\0\0\0\0", 8);
  std::vector<std::uint32_t> offsets, sizes;
  for (const std::string& t : tiles) {
    offsets.push_back(static_cast<std::uint32_t>(b.size()));
    sizes.push_back(static_cast<std::uint32_t>(t.size()));
    dng.tileOffsets.push_back(b.size());
    dng.tileSizes.push_back(t.size());
    b += t;
    if (b.size() & 1) b += '\0';
  }
  for (Entry& e : entries) {
    if (e.tag == 324) e.data = longs(offsets);
    if (e.tag == 325) e.data = longs(sizes);
  }
  // Values longer than 4 bytes go before the directory.
  std::vector<std::uint32_t> where(entries.size(), 0);
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (entries[i].data.size() > 4) {
      where[i] = static_cast<std::uint32_t>(b.size());
      b += entries[i].data;
      if (b.size() & 1) b += '\0';
    }
  const std::uint32_t ifd = static_cast<std::uint32_t>(b.size());
  put32(b, 4, ifd);
  b += shorts({static_cast<std::uint16_t>(entries.size())});
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    b += shorts({e.tag, e.type});
    b += longs({e.count});
    std::string value = e.data.size() > 4 ? longs({where[i]}) : e.data;
    value.resize(4, '\0');
    b += value;
  }
  b += longs({0});
  return dng;
}

// Tile `index`'s entropy-coded data overwritten in its middle by a run of 0x21 bytes, as a bad
// sector would leave it: decoded, the differences carry values out of the 12-bit range, which
// LibRaw reports as corrupt data (and decodes on). LibRaw notices damage only that way: a run
// that happens to decode to in-range values goes unnoticed (0x21 x 12 is noticed).
inline std::string dngWithCorruptTile(const LosslessDng& dng, std::size_t index) {
  std::string out = dng.bytes;
  const std::size_t start = dng.tileOffsets.at(index), size = dng.tileSizes.at(index);
  for (std::size_t i = start + size / 2; i < start + size / 2 + 12 && i + 2 < start + size; ++i) out[i] = '\x21';
  return out;
}

}  // namespace surrogate::test
