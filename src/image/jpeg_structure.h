// Private to src/image: the marker structure of a JPEG file, read without decoding it.
//
// A JPEG is a sequence of marker segments:
//
//   FFD8 (SOI)  [FFxx len payload]...  FFC0..FFCF (SOF: size)  ...  FFDA (SOS) entropy data ...  FFD9 (EOI)
//
// Entropy-coded data never holds FF followed by anything but 00 (a stuffed byte) or D0..D7
// (restart markers), so the next real marker can be found without decoding. libjpeg (and so
// OpenCV) decodes a file cut inside the entropy data with only a warning and grey rows; walking
// the markers is how Surrogate tells a truncated JPEG from a complete one before decoding it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace surrogate::image {

struct JpegStructure {
  int width = 0;        // from the first SOF segment (the main image; thumbnails sit inside APP1)
  int height = 0;
  int components = 0;   // 1 grey, 3 colour, 4 CMYK
  std::string problem;  // empty when the file is complete; else a sentence for the user
};

// Walks the markers of the file from SOI to EOI. Reads the file once; bounded by its size.
JpegStructure readJpegStructure(const std::filesystem::path& path);
// The same, of a file already in memory.
JpegStructure readJpegStructure(const std::uint8_t* data, std::size_t size);

}  // namespace surrogate::image
