// What the page embeds: pictures downscaled as JPEG data: URIs, and a copy of each fitted
// model (PTM or HSH) for the interactive relighting view.
#pragma once

#include <optional>
#include <string>

namespace surrogate::report {

struct EmbeddedPicture {
  std::string dataUri;  // "data:image/jpeg;base64,..."
  int width = 0, height = 0;               // as embedded
  int originalWidth = 0, originalHeight = 0;
};

// Decodes a picture file's bytes (PNG or JPEG, strictly as image::decodePicture; 16-bit
// rounded to 8, grey shown as RGB), downscales it so its longer side is at most `maxSide`
// (OpenCV's area averaging), and encodes it as JPEG (libjpeg, quality 88). nullopt when the
// bytes are not a complete, undamaged PNG or JPEG.
std::optional<EmbeddedPicture> embedPicture(const std::string& bytes, int maxSide);

// A fitted model's bytes (.ptm, or .rti HSH chosen by the first bytes "PTM_") as a JSON object
// for the page's relighting view:
//   PTM: {"model":"ptm","basis":"ptm-lrgb"|"ptm-rgb","format":"lrgb"|"rgb","width":w,"height":h,
//         "originalWidth":W,"originalHeight":H,"scale":[6],"bias":[6],"coefficients":base64,
//         "rgb":base64}             coefficients texel-interleaved: ((c*h + y)*w + x)*6 + k
//   HSH: {"model":"hsh","basis":"hsh2"|"hsh3"|"hsh4","terms":n,"width":w,"height":h,
//         "originalWidth":W,"originalHeight":H,"scale":[n],"bias":[n],"coefficients":base64}
//                                   the .rti layout: ((y*w + x)*3 + c)*n + k
// Rows top-first. The copy keeps the model's resolution when its longer side is at most
// `maxSide`, else it is downscaled by averaging each coefficient byte over the texels of a block
// (exact in decoded units, since decoding is affine per coefficient).
// Throws Error(Input) naming `name` for a malformed model.
std::string relightJson(const std::string& modelBytes, int maxSide, const std::string& name);

}  // namespace surrogate::report
