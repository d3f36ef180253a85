// Golden files from an independent implementation (tests/formats/test_independent_reader.cpp
// says how they are used): a small reader and writer of .ptm (PTM_1.2, PTM_FORMAT_LRGB and
// PTM_FORMAT_RGB) and .rti (HSH, RTI type 3), written from the published layouts that
// docs/formats.md restates (HP's "PTM File Format" 1.2; CHI's RTIViewer loaders and relight's
// writers for .rti), and a renderer from the closed-form bases of tests/fit/reference_basis.h.
// None of it calls src/formats, and the renderer does not call src/fit.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace indep {

using Bytes = std::string;

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// --- .ptm ---------------------------------------------------------------------------------
// Texel data is held by image position with rows counted from the TOP of the image; the file
// stores rows from the BOTTOM (first stored row = bottom image row), left to right.
struct Ptm {
  bool lrgb = true;  // PTM_FORMAT_LRGB, else PTM_FORMAT_RGB
  int width = 0, height = 0;
  std::array<double, 6> scale{};
  std::array<int, 6> bias{};
  // coef[channel][rowFromTop][column] -> a0..a5 bytes (LRGB: channel 0 only)
  std::vector<std::vector<std::vector<std::array<std::uint8_t, 6>>>> coef;
  // colour[rowFromTop][column] -> R, G, B bytes (LRGB only)
  std::vector<std::vector<std::array<std::uint8_t, 3>>> colour;
  std::array<std::string, 6> headerLines;  // as read

  void allocate() {
    coef.assign(lrgb ? 1 : 3, std::vector<std::vector<std::array<std::uint8_t, 6>>>(
                                  height, std::vector<std::array<std::uint8_t, 6>>(width)));
    colour.assign(lrgb ? height : 0, std::vector<std::array<std::uint8_t, 3>>(width));
  }
  // a_k = (byte - bias_k) * scale_k, 0..255 units.
  double a(int c, int x, int y, int k) const { return (coef[c][y][x][k] - bias[k]) * scale[k]; }
};

Bytes writePtm(const Ptm& p);
// The strictest reading of the format: the rules every viewer's parser is happy with.
Ptm readPtm(const Bytes& b);

// --- .rti (HSH) ------------------------------------------------------------------------------
// Rows are stored from the TOP; per texel all terms of red, then green, then blue.
struct Rti {
  int width = 0, height = 0, terms = 0;
  std::vector<float> scale, bias;  // one per term, shared by R, G, B
  // coef[rowFromTop][column][channel][term]
  std::vector<std::vector<std::array<std::vector<std::uint8_t>, 3>>> coef;
  std::vector<std::string> headerLines;  // as read, comments included

  void allocate() {
    coef.assign(height, std::vector<std::array<std::vector<std::uint8_t>, 3>>(width));
    for (auto& row : coef)
      for (auto& texel : row)
        for (auto& channel : texel) channel.assign(terms, 0);
  }
  // coefficient = byte / 255 * SCALE_k + BIAS_k, 0..1 units.
  double a(int x, int y, int c, int k) const {
    return coef[y][x][c][k] / 255.0 * static_cast<double>(scale[k]) + static_cast<double>(bias[k]);
  }
};

Bytes writeRti(const Rti& r);
Rti readRti(const Bytes& b);

// --- rendering from the closed forms (0..255 units, unclamped, unrounded) -------------------
// PTM: L = sum_k a_k w_k(lu, lv), (lu, lv) = (lx, ly) of the unit light.
// LRGB shows colour_c * L / 255; RGB shows L_c. HSH shows 255 * sum_k coef_{c,k} H_k.
double ptmValue(const Ptm& p, int x, int y, int c, double lx, double ly, double lz);
double rtiValue(const Rti& r, int x, int y, int c, double lx, double ly, double lz);

}  // namespace indep
