// sRGB encoding of linear values: what lets raw-based results be viewed like JPEG-based ones.
//
//   V = 12.92 L                     for L <= 0.0031308
//   V = 1.055 L^(1/2.4) - 0.055     otherwise             (IEC 61966-2-1)
//
// Applied through a 65536-entry table built once, so the result is the same on every run.
//
//   Image display = srgbEncode(decodeImage(raw, settings));   // Transfer::Linear -> Srgb
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace surrogate::image {

// Linear 16-bit values to sRGB-encoded 16-bit, any channel count; bitsPerSample is kept.
// The values are taken as linear whatever `transfer` says (callers build images, such as a
// median of linear photographs, without always setting it); the result is Transfer::Srgb.
Image srgbEncode(const Image& linear);
// The table srgbEncode applies: entry v is the sRGB encoding of linear value v (65536 entries).
const std::vector<std::uint16_t>& srgbEncodingTable();

}  // namespace surrogate::image
