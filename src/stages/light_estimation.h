// Private to src/stages: what the light-estimation stages (SphereDetection,
// HighlightDetection, LightDirections, LightsFromFile) share: their pixel and light types,
// reading numbers recorded in the carrier, the median made viewable, and lights.lp.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "core/image.h"
#include "core/stack.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"
#include "pipeline/context.h"
#include "stages/inputs.h"

namespace surrogate::stages {

using Spheres = std::vector<hrti::DetectedSphere>;
using Highlights = std::vector<std::vector<hrti::Highlight>>;  // [image][sphere]
using Lights = std::vector<std::array<double, 3>>;

// `count` comma-separated numbers recorded in the carrier ("cx,cy,r"); Error(Input) naming
// `what` otherwise.
std::vector<double> recordedNumbers(const std::string& text, std::size_t count,
                                    const std::string& what);

// The median image made viewable: camera-raw luminance is linear and would look black.
Image displayable(const Image& median, const ImageStack& lum);

// The light file LightDirections and LightsFromFile write (their info().outputs).
std::vector<std::string> lightsFileOutput(const carrier::Step&);

// Writes assembly-files/lights.lp. Like every .lp, it names the images relative to its own
// folder ("../original-captures/IMG_0001.dng"), as RTIBuilder and relight expect; the names
// are made from the capture-relative paths alone, lexically, so the file's bytes do not
// depend on where the capture is (the verifier re-executes elsewhere and compares hashes).
void writeLights(pipeline::Context& ctx, const carrier::Step& step, carrier::Result& result,
                 const InputImages& inputs, const Lights& lights);

// Where the lights were, when any is near (LightPlaces): assembly-files/lights.dome, relight's
// dome file (relightlab's "3D light positions": lightConfiguration lights3d, positions3d), the
// companion of lights.lp, which stays the directions (relight's .lp reader normalises every
// vector, so positions cannot go in it). docs/formats.md, "Light positions".
inline constexpr double kFarLightWidths = 1000;  // where the dome file puts a light at infinity
void writeLightsDome(pipeline::Context& ctx, const carrier::Step& step, carrier::Result& result,
                     const InputImages& inputs, const Lights& lights, const LightPlaces& places);

// One <light> item of a step's result: the direction, its elevation and azimuth in degrees, and
// when measured (uncertaintyDeg >= 0) its uncertainty: uncertaintyDegrees, the 95 % bound on the
// angle between this direction and the true one (hrti/light_uncertainty.h). A light read from a
// user's .lp file states none.
void addLightItem(carrier::Result& result, const std::string& fileId, const std::array<double, 3>& l,
                  const std::string& source, double uncertaintyDeg = -1);

}  // namespace surrogate::stages
