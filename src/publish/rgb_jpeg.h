// Private to src/publish: JPEG encoding of one plane image, three unrelated 8-bit values per
// pixel stored as the JPEG's three components with no colour transform.
//
// The planes hold coefficients, not colours: libjpeg's usual RGB -> YCbCr conversion and
// chroma subsampling would mix the three coefficients of a pixel and blur two of them, so the
// encoder is told the JPEG colour space is RGB (an Adobe marker with transform 0, sampling
// 1x1 for every component), as the web viewers' own exporter does. The bytes depend only on
// the pixels, the quality and the libjpeg version: integer DCT (JDCT_ISLOW), standard Huffman
// tables, no optimisation pass, no JFIF time or comment.
//
//   std::string jpeg = encodeRgbJpeg(pixels, width, height, 95);   // pixels: RGBRGB..., rows top-first
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace surrogate::publish {

// Throws Error(Internal) if libjpeg reports a failure.
std::string encodeRgbJpeg(const std::vector<std::uint8_t>& pixels, int width, int height, int quality);

}  // namespace surrogate::publish
