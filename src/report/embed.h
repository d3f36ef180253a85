// What the page embeds: pictures downscaled as JPEG data: URIs, and a copy of each fitted
// model (PTM or HSH) for the interactive relighting view.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "core/image.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::report {

// The bytes of coefficients (before base64, which adds a third) each model in the relighting
// view may take. The page's size must not grow with the capture's (docs/user-guide.md, "The
// HTML report"): at 24 x 1200x800 the two default models kept whole took 27 MB of a 28 MB page,
// and at 2000x1500 they were averaged to 1000x750 and still took 22 MB. 1.5 MB keeps each model
// of 400x300 (the test captures) whole, gives a PTM (LRGB) of 1200x800 at 400x267 and an HSH of
// order 2 at 400x267 (block side 3), and keeps the page of the default two models, with its
// pictures (kReportBudgetBytes, report.h), under 5 MB at any capture size.
inline constexpr std::size_t kRelightModelBytes = 1'500'000;

// The bytes of coefficients of all the models of the relighting view together: the default two
// take kRelightModelBytes each, a capture with more shares them out (four models: 0.75 MB
// each), so that the page stays within its budget whatever the number of models (four made a
// page of 8.5 MB when each had its own 1.5 MB).
inline constexpr std::size_t kRelightModelsBytes = 2 * kRelightModelBytes;

// One model's share of `totalBytes` among `models` models: at most kRelightModelBytes; 0 (no
// limit) when totalBytes is 0.
std::size_t relightShare(std::size_t totalBytes, std::size_t models);

struct EmbeddedPicture {
  std::string dataUri;  // "data:image/jpeg;base64,..."
  int width = 0, height = 0;               // as embedded
  int originalWidth = 0, originalHeight = 0;
};

// A picture as the page shows it before it is encoded: 8-bit RGB (16-bit samples rounded to 8
// as narrowSamples does, grey repeated), downscaled so its longer side is at most `maxSide`
// (OpenCV's area averaging; 0 = not downscaled).
struct DisplayPicture {
  Image8 rgb;
  int originalWidth = 0, originalHeight = 0;
  int maxSide = 0;  // what it was made for
};

// The display copy of pixels a step holds (a PNG's pixels: 8-bit samples as value * 257 when
// image.bitsPerSample <= 8): the same as the display copy of the PNG file image::writePng makes
// of them, decoded, without writing or decoding it.
DisplayPicture displayPicture(const Image& picture, int maxSide);

// A display copy encoded as JPEG (libjpeg, quality 88); nullopt if the encoder fails.
std::optional<EmbeddedPicture> embedPicture(const DisplayPicture& picture);

// Decodes a picture file's bytes (PNG or JPEG, strictly as image::decodePicture), makes its
// display copy and encodes it as above. nullopt when the bytes are not a complete, undamaged
// PNG or JPEG.
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
// `maxSide` and its coefficients take at most `maxBytes` (0: no limit), else it is downscaled
// by the smallest whole factor that meets both (relightBlockSide), averaging each coefficient
// byte over the texels of a block (exact in decoded units, since decoding is affine per
// coefficient).
// Throws Error(Input) naming `name` for a malformed model.
std::string relightJson(const std::string& modelBytes, int maxSide, const std::string& name,
                        std::size_t maxBytes = kRelightModelBytes);

// The same of a model in memory: what relightJson gives for the file formats::writePtm or
// formats::writeRti makes of it (their numbers read back exactly).
std::string relightJson(const formats::PtmFile& ptm, int maxSide, std::size_t maxBytes = kRelightModelBytes);
std::string relightJson(const formats::HshFile& hsh, int maxSide, std::size_t maxBytes = kRelightModelBytes);

// Texels per block side of the copy of a width x height model of `bytesPerTexel` bytes (PTM
// LRGB 9, PTM RGB 18, HSH 3 x terms): the smallest whole factor that brings its longer side to
// at most maxSide (0: any) and its texels' bytes to at most maxBytes (0: any); 1 keeps it whole.
int relightBlockSide(int width, int height, std::size_t bytesPerTexel, int maxSide, std::size_t maxBytes);

// A model's interactive copy made while it was in memory (surrogate run: as each fit writes
// its model), for ReportOptions::relightCopies.
struct RelightCopy {
  std::string json;  // relightJson of the model
  int maxSide = 0;   // what it was made for
  std::size_t maxBytes = kRelightModelBytes;
};

}  // namespace surrogate::report
