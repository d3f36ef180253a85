// Per-pixel median of an image stack (docs/hrti-math.md, "Spheres in the median image").
//
// Shadows and highlights move from image to image; the spheres do not. The median over the
// stack keeps the spheres and drops both. It needs every image's value at a pixel but never
// whole images: the stack is read in bands of `bandRows` rows, so memory is
// O(N * bandRows * width) whatever the image size.
//
// For an even count the median is the lower of the two middle values (no averaging: the
// result is one of the measured values, exactly reproducible).
#pragma once

#include "core/image.h"
#include "core/stack.h"

namespace surrogate::hrti {

// Median of a one-channel stack; deterministic at any thread count.
Image medianImage(const ImageStack& luminance, int bandRows, int threads);

}  // namespace surrogate::hrti
