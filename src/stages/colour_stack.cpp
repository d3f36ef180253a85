#include "stages/colour_stack.h"

#include <algorithm>
#include <cmath>

#include "colour/colour_space.h"
#include "core/error.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace {

// Linear values are encoded through a table of this many steps (rounded to the nearest): a
// step is 1/2^18 of full scale, under a third of a 16-bit level even where the sRGB curve is
// steepest (12.92 x), so the table costs no precision the 16-bit output keeps.
constexpr int kEncodeSteps = 1 << 18;

}  // namespace

ColourStack::ColourStack(std::shared_ptr<const ImageStack> inner, colour::ColourModel model)
    : inner_(std::move(inner)), model_(std::move(model)), toLinear_(65536), encode_(kEncodeSteps + 1) {
  if (inner_->channels() != 3)
    throw Error(ErrorKind::Internal, "colour correction", "ColourStack", "needs RGB images");
  const bool srgb = inner_->transfer() == Transfer::Srgb;
  for (int v = 0; v < 65536; ++v) toLinear_[v] = toLinear(static_cast<std::uint16_t>(v), inner_->transfer());
  for (int i = 0; i <= kEncodeSteps; ++i) {
    const double l = static_cast<double>(i) / kEncodeSteps;
    encode_[i] = static_cast<std::uint16_t>(std::lround((srgb ? colour::srgbEncode(l) : l) * 65535));
  }
}

void ColourStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  inner_->readRows(index, y0, y1, out);
  const std::size_t n = static_cast<std::size_t>(y1 - y0) * width();
  for (std::size_t p = 0; p < n; ++p) {
    std::uint16_t* s = out + 3 * p;
    const colour::Rgb rgb = model_.apply({toLinear_[s[0]], toLinear_[s[1]], toLinear_[s[2]]});
    for (int c = 0; c < 3; ++c)
      s[c] = encode_[static_cast<std::size_t>(std::lround(std::clamp(rgb[c], 0.0, 1.0) * kEncodeSteps))];
  }
}

}  // namespace surrogate::stages
