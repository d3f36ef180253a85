#include "core/image.h"

#include <array>

#include "core/cpu_features.h"
#include "core/resident.h"

namespace surrogate {

namespace {

// Weights 0.2126, 0.7152, 0.0722 in 1/65536 units (they sum to 65536 exactly), so a sum of
// three weighted 16-bit samples plus the rounding half stays below 2^32.
constexpr std::uint32_t kWr = 13933, kWg = 46871, kWb = 4732;

std::uint16_t weighted(std::uint32_t r, std::uint32_t g, std::uint32_t b) {
  return static_cast<std::uint16_t>((kWr * r + kWg * g + kWb * b + 32768u) >> 16);
}

// Each channel's weighted term for every 8-bit sample (widened by 257): one table look-up a
// sample instead of a multiplication, the same sums.
struct Weighted8 {
  std::array<std::uint32_t, 256> r, g, b;
  Weighted8() {
    for (std::uint32_t v = 0; v < 256; ++v) {
      r[v] = kWr * v * 257;
      g[v] = kWg * v * 257;
      b[v] = kWb * v * 257;
    }
  }
};

}  // namespace

Image::Image(int w, int h, int c) : width(w), height(h), channels(c) {
  resizeResident(pixels, static_cast<std::size_t>(w) * h * c);
}

Image8::Image8(int w, int h, int c) : width(w), height(h), channels(c) {
  resizeResident(pixels, static_cast<std::size_t>(w) * h * c);
}

Image widen(const Image8& narrow) {
  return widen(narrow.pixels.data(), narrow.width, narrow.height, narrow.channels, narrow.transfer);
}

Image widen(const std::uint8_t* samples, int width, int height, int channels, Transfer transfer) {
  Image out(width, height, channels);
  out.bitsPerSample = 8;
  out.transfer = transfer;
  widenSamples(samples, out.pixels.size(), out.pixels.data());
  return out;
}

void widenSamples(const std::uint8_t* in, std::size_t count, std::uint16_t* out) {
  for (std::size_t k = 0; k < count; ++k) out[k] = static_cast<std::uint16_t>(in[k] * 257);
}

void narrowSamples(const std::uint16_t* in, std::size_t count, std::uint8_t* out) {
  for (std::size_t k = 0; k < count; ++k) out[k] = static_cast<std::uint8_t>((in[k] + 128u) / 257u);
}

void luminanceOfPixels(const std::uint16_t* rgb, std::size_t count, std::uint16_t* out) {
  for (std::size_t i = 0; i < count; ++i, rgb += 3) out[i] = weighted(rgb[0], rgb[1], rgb[2]);
}

namespace detail {

void luminanceOfPixelsBaseline(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out) {
  static const Weighted8 table;
  for (std::size_t i = 0; i < count; ++i, rgb += 3)
    out[i] = static_cast<std::uint16_t>((table.r[rgb[0]] + table.g[rgb[1]] + table.b[rgb[2]] + 32768u) >> 16);
}

#if defined(__x86_64__) && defined(__GNUC__)
// The same sums as the table's, multiplied out: AVX2 multiplies eight 32-bit integers at once,
// where the baseline instruction set has no such multiplication and the table is faster.
__attribute__((target("avx2"))) void luminanceOfPixelsAvx2(const std::uint8_t* __restrict rgb, std::size_t count,
                                                           std::uint16_t* __restrict out) {
  constexpr std::uint32_t r = kWr * 257, g = kWg * 257, b = kWb * 257;
  for (std::size_t i = 0; i < count; ++i)
    out[i] = static_cast<std::uint16_t>((r * rgb[3 * i] + g * rgb[3 * i + 1] + b * rgb[3 * i + 2] + 32768u) >> 16);
}
#else
void luminanceOfPixelsAvx2(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out) {
  luminanceOfPixelsBaseline(rgb, count, out);
}
#endif

}  // namespace detail

void luminanceOfPixels(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out) {
  if (cpuHasAvx2()) detail::luminanceOfPixelsAvx2(rgb, count, out);
  else detail::luminanceOfPixelsBaseline(rgb, count, out);
}

Image luminance(const Image& in) {
  Image out(in.width, in.height, 1);
  out.bitsPerSample = in.bitsPerSample;
  out.transfer = in.transfer;
  if (in.channels == 1) {
    out.pixels = in.pixels;
    return out;
  }
  luminanceOfPixels(in.pixels.data(), static_cast<std::size_t>(in.width) * in.height, out.pixels.data());
  return out;
}

}  // namespace surrogate
