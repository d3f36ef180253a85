// RTIViewer ".rti" files holding hemispherical harmonics (HSH, RTI type 3), docs/formats.md
// ".rti".
//
// Per texel and colour channel c, `terms` (4, 9 or 16) coefficients of the HSH basis H_k
// (fit/basis.h) in 0..1 intensity units:
//
//     coef_{c,k} = byte / 255 * scale_k + bias_k
//     value_c    = sum_k coef_{c,k} H_k(theta, phi)          (displayed: clamp(value_c*255))
//
// File: "#HSH1.2\n3\n<w> <h> 3\n<terms> 2 1\n", then terms float32 scales, terms float32
// biases (little-endian), then per texel (rows TOP to bottom, left to right) the red terms,
// the green terms, the blue terms. In memory the layout is the same as the file's:
// texel (x, y), channel c, term k at ((y*width + x)*3 + c)*terms + k.
//
//   HshFile hsh = readRti("object.rti");
//   double red0 = hsh.coefficient(x, y, 0, 0);
//   writeRti("copy.rti", hsh);   // byte-identical to a file we wrote
//
// The reader skips any leading '#' comment lines (RTIViewer does), requires type 3, 3
// channels, basis type 2 and element size 1 (the "2 1" every HSH writer writes), and accepts
// the order codes 1 and 2 for 4 and 9 terms. Bytes after the payload
// are ignored and counted in RtiReadReport::trailingBytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "formats/model_budget.h"

namespace surrogate::formats {

struct HshFile {
  int width = 0;
  int height = 0;
  int terms = 0;             // 4, 9 or 16
  std::vector<float> scale;  // terms values, shared by R, G, B
  std::vector<float> bias;   // terms values
  std::vector<std::uint8_t> coefficients;  // width*height*3*terms, see the layout above

  std::size_t texels() const { return static_cast<std::size_t>(width) * height; }
  std::uint8_t byte(int x, int y, int c, int k) const {
    return coefficients[((static_cast<std::size_t>(y) * width + x) * 3 + c) * terms + k];
  }
  // Decoded coefficient in 0..1 units.
  double coefficient(int x, int y, int c, int k) const {
    return byte(x, y, c, k) / 255.0 * scale[k] + bias[k];
  }
  bool operator==(const HshFile& o) const;
  bool operator!=(const HshFile& o) const { return !(*this == o); }
};

struct RtiReadReport {
  std::vector<std::string> comments;  // the leading '#' lines, without the '#'
  std::size_t trailingBytes = 0;
};

struct RtiHeader {
  RtiReadReport report;
  int width = 0, height = 0, terms = 0;
  std::size_t tablesOffset = 0;  // where the float32 scale table starts
  std::vector<float> scale, bias;  // filled when the buffer holds the tables, else empty
  std::size_t payloadBytes = 0;  // 8*terms + 3*terms*width*height
};

// Parses the ASCII header. Throws Error(Input) naming `name` for a missing header, an RTI type
// other than 3 (HSH), a channel count other than 3, a term count other than 4, 9 or 16, a
// basis type other than 2 or an element size other than 1, or dimensions outside 1..65536 /
// above 2^31 texels.
RtiHeader parseRtiHeader(const std::uint8_t* data, std::size_t size, const std::string& name);

// Parses a whole file in memory (never reads outside the buffer); also throws for a truncated
// payload and for non-finite scale or bias values, and, before allocating the model, when
// `size` + the model + budget.besidePerTexel a texel exceeds budget.bytes
// (core/memory_budget.h).
HshFile parseRti(const std::uint8_t* data, std::size_t size, const std::string& name,
                 RtiReadReport* report = nullptr, const ModelBudget& budget = {});
HshFile readRti(const std::filesystem::path& path, RtiReadReport* report = nullptr,
                const ModelBudget& budget = {});

// Throws Error(Input) when the object cannot be written as a valid file.
void validateHsh(const HshFile& hsh, const std::string& name);
// Writes the "#HSH1.2" file; writeRti is atomic (temporary file renamed into place).
void writeRti(std::ostream& out, const HshFile& hsh, const std::string& name);
void writeRti(const std::filesystem::path& path, const HshFile& hsh);
std::string serializeRti(const HshFile& hsh);

}  // namespace surrogate::formats
