// The specular highlight on a sphere in one image (hrti-math.md, highlight detection).
//
// Inside the sphere's circle (less a rim of `rimPixels`, where the outline blurs into the
// background): threshold at `threshold` times the brightest pixel, label 8-connected
// components, take each component's centroid weighted by pixel value (sub-pixel), and choose
// the component nearest the sphere's centre (inter-reflections lie farther out).
// Flags: None when nothing stands out (no highlight: the light was behind the sphere or
// the flash failed), Multiple when another component is nearly as bright (>= 90 % of the
// chosen peak, >= 3 pixels): the choice is then worth checking on the overview image.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "hrti/sphere_detection.h"

namespace surrogate::hrti {

struct HighlightOptions {
  double threshold = 0.8;  // fraction of the brightest pixel inside the sphere
  int rimPixels = 2;       // excluded at the sphere's edge

  std::vector<std::pair<std::string, std::string>> toParameters() const;
  static HighlightOptions fromParameters(const std::vector<std::pair<std::string, std::string>>& p);
};

enum class HighlightFlag { Ok, None, Multiple, Manual };

struct Highlight {
  double x = 0, y = 0;  // full-image pixels
  HighlightFlag flag = HighlightFlag::None;
  int components = 0;
  double peak = 0;  // brightest value inside the sphere, 0..1
};

// `crop` holds rows/columns of one luminance image starting at (cropX0, cropY0).
Highlight detectHighlight(const Image& crop, int cropX0, int cropY0, const DetectedSphere& sphere,
                          const HighlightOptions& options);

// Every image's highlight on every sphere: [image][sphere]. Reads only the rows around the
// spheres; parallel over images, identical at any thread count.
std::vector<std::vector<Highlight>> detectHighlights(const ImageStack& luminance,
                                                     const std::vector<DetectedSphere>& spheres,
                                                     const HighlightOptions& options, int threads);

}  // namespace surrogate::hrti
