// Pictures for people checking the light estimation (as RTIBuilder draws them): the detected
// spheres on the median image, and every image's highlight on one enlarged picture of a
// sphere. 8-bit RGB, deterministic.
#pragma once

#include <vector>

#include "core/image.h"
#include "hrti/highlight_detection.h"

namespace surrogate::hrti {

Image drawSphereOverlay(const Image& medianLuminance, const std::vector<DetectedSphere>& spheres);

// Highlights in red (numbered by image, from 1), flagged ones in yellow, refused ones left out;
// the circle in green.
Image drawHighlightOverview(const Image& medianLuminance, const DetectedSphere& sphere,
                            const std::vector<Highlight>& perImage);

}  // namespace surrogate::hrti
