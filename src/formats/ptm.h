// HP Polynomial Texture Maps (.ptm), version 1.2: raw LRGB and RGB written and read, the
// JPEG-compressed LRGB and RGB variants read (docs/formats.md, ".ptm").
//
// A PTM stores, per texel, the six coefficients of a biquadratic in the light's projection
// (lu, lv) = (lx, ly) on the image plane:
//
//     L(lu, lv) = a0 lu^2 + a1 lv^2 + a2 lu lv + a3 lu + a4 lv + a5      (0..255 units)
//     a_k       = (byte_k - bias_k) * scale_k                            (decoding)
//
// LRGB: one polynomial (luminance) per texel plus an 8-bit colour; a viewer shows
// colour * L / 255. RGB: one polynomial per colour channel.
//
// In memory, rows are TOP-first like surrogate::Image (the file stores them bottom-first;
// the reader and writer flip). Layout of `coefficients`:
//   Lrgb: width*height*6 bytes, texel (x, y) at ((y*width + x)*6 + k); `rgb` holds
//         width*height*3 bytes, texel (x, y) at ((y*width + x)*3 + c).
//   Rgb:  three blocks (red, green, blue) of width*height*6 bytes: channel c, texel (x, y),
//         coefficient k at ((c*height + y)*width + x)*6 + k; `rgb` is empty.
//
//   PtmFile ptm = readPtm("finished-files/object.ptm");
//   double a5 = ptm.coefficient(10, 20, 5);     // decoded, 0..255 units
//   writePtm("copy.ptm", ptm);                  // byte-identical to a PTM_1.2 input
//
// Files written: "PTM_1.2\n", the format line, width and height on separate lines, six
// scales in plain decimal notation (shortest text that reads back exactly, never an exponent),
// six integer biases, single spaces, no trailing space, then the payload bottom-up.
// Files read: PTM_1.2 and PTM_1.1 (LRGB only, 9 interleaved bytes per texel), width and
// height on one line or two, extra spaces and '\r' tolerated. Bytes after the payload are
// ignored and counted in PtmReadReport::trailingBytes (viewers ignore them as well).
// PTM_FORMAT_JPEG_LRGB and PTM_FORMAT_JPEG_RGB (PTM_1.2) are read into the same PtmFile as
// their raw forms: each coefficient or colour plane is a greyscale JPEG, possibly predicted
// from another plane and corrected by side information (docs/formats.md, "JPEG-compressed
// PTMs"); the bytes are the JPEG's approximation of the fitted ones, and writePtm writes
// them back uncompressed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "formats/model_budget.h"

namespace surrogate::formats {

struct PtmFile {
  enum class Format { Lrgb, Rgb };
  Format format = Format::Lrgb;
  int width = 0;
  int height = 0;
  std::array<double, 6> scale{};  // shared by the R, G and B blocks of Rgb
  std::array<int, 6> bias{};      // 0..255
  std::vector<std::uint8_t> coefficients;  // see the layout above
  std::vector<std::uint8_t> rgb;           // Lrgb only

  std::size_t texels() const { return static_cast<std::size_t>(width) * height; }
  // Byte of coefficient k of texel (x, y) (channel c for Rgb; 0 for Lrgb).
  std::uint8_t byte(int x, int y, int k, int c = 0) const {
    return coefficients[((static_cast<std::size_t>(c) * height + y) * width + x) * 6 + k];
  }
  // Decoded coefficient (byte - bias) * scale, in 0..255 units.
  double coefficient(int x, int y, int k, int c = 0) const {
    return (byte(x, y, k, c) - bias[k]) * scale[k];
  }
  bool operator==(const PtmFile& o) const;
  bool operator!=(const PtmFile& o) const { return !(*this == o); }
};

const char* formatName(PtmFile::Format format);  // "PTM_FORMAT_LRGB", "PTM_FORMAT_RGB"

// What the reader noticed that the PtmFile itself does not say.
struct PtmReadReport {
  std::string version;         // "PTM_1.2" or "PTM_1.1"
  std::string formatLine;      // the format as the file names it ("PTM_FORMAT_JPEG_LRGB")
  bool sizeOnOneLine = false;  // "w h" on one line (readable, but RTIViewer rejects it)
  std::size_t trailingBytes = 0;
  int jpegQuality = -1;        // JPEG variants: the compression parameter; -1 for raw files
};

// One plane of a JPEG-compressed PTM as its header describes it. Planes are numbered as the
// raw layout orders bytes: LRGB a0..a5, R, G, B (9); RGB a0..a5 of red, green, blue (18).
struct PtmJpegPlane {
  int transform = 0;            // 0 none, 1 invert the reference (255 - r), 2 motion compensation
  int motionX = 0, motionY = 0;
  int order = 0;                // position in the decoding sequence (0 = decoded first)
  int reference = -1;           // the plane this one is predicted from, or -1
  std::uint64_t jpegBytes = 0;  // its JPEG stream, stored first
  std::uint64_t sideBytes = 0;  // then its side information: 5-byte corrections
};

// Header fields only, for `surrogate info` (reads the header, not the payload).
struct PtmHeader {
  PtmReadReport report;
  PtmFile::Format format = PtmFile::Format::Lrgb;
  int width = 0, height = 0;
  std::array<double, 6> scale{};
  std::array<int, 6> bias{};
  std::size_t payloadOffset = 0;  // bytes of header
  std::size_t payloadBytes = 0;   // 9 or 18 per texel; JPEG: the sum of the planes' sizes
  std::vector<PtmJpegPlane> jpegPlanes;  // JPEG variants only (9 or 18), in plane order
};

// Limits the readers enforce before allocating anything.
constexpr int kMaxSide = 65536;
constexpr std::uint64_t kMaxTexels = 1ull << 31;

// Parses the header at the start of `data` (the payload need not be present), with, for the
// JPEG variants, the plane table that follows the biases.
// Throws Error(Input) naming `name` for a bad magic, an unsupported version or format, bad
// dimensions (outside 1..65536 or more than 2^31 texels; JPEG variants: more than
// image::kMaxImagePixels), malformed scale/bias lines, or a plane table that cannot describe
// a decodable file (a decoding order that is not a permutation, a reference decoded later
// than the plane it predicts, a side-information size not a multiple of 5, ...).
PtmHeader parsePtmHeader(const std::uint8_t* data, std::size_t size, const std::string& name);

// What reading the model `h` declares takes at its peak besides the `fileBytes` held: the
// model (9 or 18 bytes a texel), and for the JPEG variants one decoded plane and the
// coefficients libjpeg keeps for a progressive plane (3 bytes a texel).
std::uint64_t ptmReadBytes(const PtmHeader& h);

// Parses a whole file held in memory; also throws when the payload is shorter than the header
// says, and, for the JPEG variants, when a plane's JPEG stream is damaged, is not a greyscale
// image of the PTM's size, or a side-information entry points outside the image. Never reads
// outside [data, data + size). Before anything is allocated, throws Error(Input) naming `name`
// when `size` + ptmReadBytes + budget.besidePerTexel a texel exceeds budget.bytes
// (core/memory_budget.h): a JPEG-compressed PTM of a few megabytes can declare gigabytes.
PtmFile parsePtm(const std::uint8_t* data, std::size_t size, const std::string& name,
                 PtmReadReport* report = nullptr, const ModelBudget& budget = {});
PtmFile readPtm(const std::filesystem::path& path, PtmReadReport* report = nullptr,
                const ModelBudget& budget = {});

// Throws Error(Input) naming `name` when the object cannot be written as a valid file:
// dimensions out of range, wrong vector sizes, biases outside 0..255, non-finite scales or
// |scale| outside [1e-12, 1e12] (0 is allowed).
void validatePtm(const PtmFile& ptm, const std::string& name);

// Serialises as PTM_1.2 (validates first). writePtm is atomic: a temporary file renamed into
// place, so a failed write never leaves a partial .ptm under `path`.
void writePtm(std::ostream& out, const PtmFile& ptm, const std::string& name);
void writePtm(const std::filesystem::path& path, const PtmFile& ptm);
std::string serializePtm(const PtmFile& ptm);

}  // namespace surrogate::formats
