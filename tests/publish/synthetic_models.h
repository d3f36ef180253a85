// Test support for tests/publish: small PTM and HSH models of known, smooth coefficients, so
// that a swapped plane or channel, or a flipped row order, shows as a large error.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::test {

// A byte that differs along x and y and between terms k and channels c; `ramp` levels are
// added from the top row to the bottom one (centred on 0), over `height` rows.
inline std::uint8_t smoothField(int x, int y, int k, int c, int height, double ramp) {
  const double v = 128 + 80 * std::sin(0.07 * x + 0.9 * k + 0.5 * c) * std::cos(0.05 * y + 0.4 * k) +
                   ramp * y / height - ramp / 2;
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
}

// A PTM (LRGB: one luminance polynomial and the colour as term 7; RGB: one per channel).
inline formats::PtmFile smoothPtm(formats::PtmFile::Format format, int w, int h, double ramp) {
  formats::PtmFile p;
  p.format = format;
  p.width = w;
  p.height = h;
  p.scale = {0.4, 0.35, 0.3, 0.5, 0.45, 1.0};
  p.bias = {130, 125, 128, 120, 135, 0};
  const bool lrgb = format == formats::PtmFile::Format::Lrgb;
  const int channels = lrgb ? 1 : 3;
  p.coefficients.resize(p.texels() * 6 * static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < 6; ++k)
          p.coefficients[((static_cast<std::size_t>(c) * h + y) * w + x) * 6 + k] = smoothField(x, y, k, c, h, ramp);
  if (lrgb) {
    p.rgb.resize(p.texels() * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          p.rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c] = smoothField(x, y, 7, c, h, ramp);
  }
  return p;
}

// An HSH model of `terms` terms per colour.
inline formats::HshFile smoothHsh(int terms, int w, int h, double ramp) {
  formats::HshFile m;
  m.width = w;
  m.height = h;
  m.terms = terms;
  for (int k = 0; k < terms; ++k) {
    m.scale.push_back(k == 0 ? 1.5f : 0.6f);
    m.bias.push_back(k == 0 ? 0.1f : -0.3f);
  }
  m.coefficients.resize(m.texels() * 3 * static_cast<std::size_t>(terms));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < terms; ++k)
          m.coefficients[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k] = smoothField(x, y, k, c, h, ramp);
  return m;
}

// fit::render (what `surrogate render` calls) of `model` at light `l`, as 8-bit RGB values,
// rows top-first.
inline std::vector<int> renderedValues(const fit::Relightable& model, const std::array<double, 3>& l) {
  const Image img = model.render(l, {});
  std::vector<int> out;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) out.push_back(img.at(x, y, c) / 257);
  return out;
}

}  // namespace surrogate::test
