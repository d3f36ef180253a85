// What the page embeds: pictures downscaled with OpenCV as data: URIs, and a downscaled copy of
// a PTM for the interactive relighting view.
#pragma once

#include <optional>
#include <string>

namespace surrogate::report {

struct EmbeddedPicture {
  std::string dataUri;  // "data:image/jpeg;base64,..."
  int width = 0, height = 0;               // as embedded
  int originalWidth = 0, originalHeight = 0;
};

// Decodes an image file's bytes (PNG, JPEG, TIFF; 16-bit is reduced to 8), downscales it so its
// longer side is at most `maxSide` (area averaging), and encodes it as JPEG. nullopt when the
// bytes are not an image OpenCV can read.
std::optional<EmbeddedPicture> embedPicture(const std::string& bytes, int maxSide);

// A .ptm's bytes as a JSON object for the page's relighting view:
//   {"format":"lrgb"|"rgb","width":w,"height":h,"scale":[6],"bias":[6],
//    "coefficients":base64, "rgb":base64}
// The copy is downscaled to at most `maxSide` by averaging each coefficient byte over the
// texels of a block (exact in decoded units, since decoding is affine per coefficient).
// Throws Error(Input) naming `name` for a malformed PTM.
std::string relightJson(const std::string& ptmBytes, int maxSide, const std::string& name);

}  // namespace surrogate::report
