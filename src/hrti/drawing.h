// Pictures for people checking the light estimation (as RTIBuilder draws them): the detected
// spheres on the median image, and every image's highlight on one enlarged picture of a
// sphere. 8-bit RGB, deterministic.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "hrti/highlight_detection.h"

namespace surrogate::hrti {

// Spheres numbered from 1 ("sphere 1  r=45.3  conf 0.96"), every label inside the picture.
Image drawSphereOverlay(const Image& medianLuminance, const std::vector<DetectedSphere>& spheres);

// Highlights in red, flagged ones in yellow, refused ones left out; the circle in green. Each
// highlight is labelled labels[i] (the image's file name), or i + 1 where labels has no entry;
// every label lies inside the picture.
Image drawHighlightOverview(const Image& medianLuminance, const DetectedSphere& sphere,
                            const std::vector<Highlight>& perImage, const std::vector<std::string>& labels = {});

}  // namespace surrogate::hrti
