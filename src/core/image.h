// surrogate::Image: a decoded photograph, independent of any imaging library.
//
// Pixels are 16-bit, interleaved (RGBRGB... or a single grey channel), rows top to bottom,
// no padding: sample (x, y, c) is pixels[(y * width + x) * channels + c].
// 8-bit sources are widened by *257 so that 255 -> 65535 exactly; `bitsPerSample` keeps the
// source depth. `transfer` says how values relate to light: Linear (camera raw decoded with
// gamma 1) or Srgb (display-encoded JPEG/TIFF/PNG exports).
// Public headers of other folders use this type, never cv::Mat (docs/developer-guide.md,
// "Code conventions").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace surrogate {

enum class Transfer { Linear, Srgb };

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;         // 1 or 3
  int bitsPerSample = 16;   // depth of the source: 8 or 16
  Transfer transfer = Transfer::Srgb;
  std::vector<std::uint16_t> pixels;

  Image() = default;
  // Zeroed pixels (their memory backed at once: core/resident.h).
  Image(int w, int h, int c);

  bool empty() const { return pixels.empty(); }
  std::size_t index(int x, int y, int c = 0) const {
    return (static_cast<std::size_t>(y) * width + x) * channels + c;
  }
  std::uint16_t at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
  std::uint16_t& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
};

// The samples of an 8-bit source as its decoder gave them, one byte each: what the pipeline
// keeps of a JPEG (and of an 8-bit PNG or TIFF), half the memory of the same image as an Image.
// Same layout as Image::pixels.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 0;  // 1 or 3
  Transfer transfer = Transfer::Srgb;
  std::vector<std::uint8_t> pixels;

  Image8() = default;
  Image8(int w, int h, int c);  // zeroed, as Image's
};

// The Image of an 8-bit source: every sample * 257, bitsPerSample 8.
Image widen(const Image8& narrow);
// The same of width * height * channels samples held elsewhere (a decoded stack's slot).
Image widen(const std::uint8_t* samples, int width, int height, int channels, Transfer transfer);
// `count` 8-bit samples widened by 257 into `out` (which must not overlap `in`).
void widenSamples(const std::uint8_t* in, std::size_t count, std::uint16_t* out);
// `count` 16-bit samples rounded to nearest 8-bit ones, v8 = (v16 + 128) / 257 (integer
// arithmetic, so the bytes never depend on floating-point rounding): how every 8-bit file is
// written.
void narrowSamples(const std::uint16_t* in, std::size_t count, std::uint8_t* out);

// Rec. 709 luminance of an RGB image (or a copy of a grey one), same 16-bit encoding,
// rounded to nearest. Deterministic: integer arithmetic only.
Image luminance(const Image& rgb);
// The same for `count` RGB pixels, 16-bit or 8-bit (taken as widened by 257).
void luminanceOfPixels(const std::uint16_t* rgb, std::size_t count, std::uint16_t* out);
void luminanceOfPixels(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out);
namespace detail {
// The two variants luminanceOfPixels chooses between (core/cpu_features.h), for the test that
// compares them; the AVX2 one only where the processor has AVX2.
void luminanceOfPixelsBaseline(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out);
void luminanceOfPixelsAvx2(const std::uint8_t* rgb, std::size_t count, std::uint16_t* out);
}  // namespace detail

}  // namespace surrogate
