// Private to src/image: PNG encoding through libpng directly (write.h's writePng).
//
// Fixed settings, so the bytes depend only on the pixels and the zlib version: every row
// filtered with Up (the difference from the row above), deflate at level 1 with the run-length
// strategy (Z_RLE), no ancillary chunks. On the normals, albedo and previews of a relief (noisy
// data that deflate hardly shrinks) this encodes 2 to 2.5 times faster than libpng's adaptive
// filter choice at level 1 with the default strategy, for files within a few per cent of its
// size (docs/developer-guide.md, "Benchmarks").
#pragma once

#include <string>

#include "core/image.h"

namespace surrogate::image {

// The PNG file of `image` (1 or 3 channels): 8-bit samples when image.bitsPerSample <= 8
// (16-bit values rounded to nearest: v8 = (v16 + 128) / 257), else 16-bit. Throws
// Error(Internal) with libpng's message when libpng fails.
std::string encodePng(const Image& image, const std::string& what);

}  // namespace surrogate::image
