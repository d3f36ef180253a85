// Private to src/image: PNG encoding (write.h's writePng).
//
// Fixed settings, so the bytes depend only on the pixels and the libdeflate version: every row
// filtered with Up (the difference from the row above), the rows compressed at once by
// libdeflate at level 1, libpng writing the header and framing the stream as IDAT chunks of
// 1 MiB, no ancillary chunks. On the maps of a relief at 3000x2000 (noisy data that deflate
// hardly shrinks) libdeflate takes 0.14-0.15 s for an 8-bit picture where zlib at level 1 with
// the run-length strategy took 0.31-0.35 s (docs/developer-guide.md, "Benchmarks").
#pragma once

#include <string>

#include "core/image.h"

namespace surrogate::image {

// The PNG file of `image` (1 or 3 channels): 8-bit samples when image.bitsPerSample <= 8
// (16-bit values rounded to nearest: v8 = (v16 + 128) / 257), else 16-bit. Throws
// Error(Internal) with libpng's message when libpng fails.
std::string encodePng(const Image& image, const std::string& what);

}  // namespace surrogate::image
