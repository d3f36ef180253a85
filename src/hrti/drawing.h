// Pictures for people checking the light estimation (as RTIBuilder draws them): the detected
// spheres on the median image, and every image's highlight on one enlarged picture of a
// sphere. 8-bit RGB, deterministic.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "hrti/highlight_detection.h"

namespace surrogate::hrti {

// Spheres numbered from 1 ("sphere 1  r=45.3  conf 0.96"; "sphere 2  r=40.0  by hand" for one
// given by hand), every label inside the picture.
// `medianLuminance` may be the frame reduced `factor` times (StackMedian::coarse()): the
// spheres, in full-resolution pixels, are drawn reduced with it; their labels give the
// full-resolution radius.
Image drawSphereOverlay(const Image& medianLuminance, const std::vector<DetectedSphere>& spheres, int factor = 1);

// Where the labels of marks go in a width x height picture: for each mark (its centre) and
// its label's size, a box inside the picture that overlaps no other label and no mark (a
// square of 2 markRadius + 1 around each). Each takes, in the marks' order, the first free of
// the places around its mark: right of it and above first, then rings of places further out
// (steps of 8 px across and a label's height down), nearest ring first, up to the whole
// picture; nullopt for a label that finds no free place there (more labels than the picture
// holds). Deterministic.
std::vector<std::optional<Rect>> placeLabels(const std::vector<std::pair<int, int>>& marks,
                                             const std::vector<std::pair<int, int>>& sizes, int width, int height,
                                             int markRadius);

// Highlights in red, flagged ones in yellow, refused ones left out; the circle in green. Each
// highlight is labelled labels[i] (the image's file name), or i + 1 where labels has no entry;
// every label lies inside the picture, and no two overlap (placeLabels): a label moved away
// from its highlight by clustered neighbours is joined to it by a thin line.
Image drawHighlightOverview(const Image& medianLuminance, const DetectedSphere& sphere,
                            const std::vector<Highlight>& perImage, const std::vector<std::string>& labels = {});
// The same for a width x height frame of which only the part around the sphere is read:
// crop(rect) gives the median's pixels over rect (StackMedian::window()).
using MedianCrop = std::function<Image(const Rect&)>;
Image drawHighlightOverview(int width, int height, const MedianCrop& crop, const DetectedSphere& sphere,
                            const std::vector<Highlight>& perImage, const std::vector<std::string>& labels = {});

}  // namespace surrogate::hrti
