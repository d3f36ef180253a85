// Pre-processing of the photographs the fit reads: the parameters of the Crop, Resize and
// WhiteBalance steps, and the pure computations behind them (the automatic crop rectangle, the
// white-balance gains of a grey region).
//
// Each options struct is what the carrier records as the step's parameters: toParameters()
// writes every field, fromParameters() reads them back (missing names keep their defaults;
// unknown names or bad values are Error(Usage) naming `origin`, the option or "carrier").
// fromText() parses the command-line forms:
//
//   --crop 100,50,800,600   CropOptions::fromText("100,50,800,600", "--crop")
//   --crop auto             the largest rectangle clear of the detected spheres
//   --resize 0.5 | 640x480  ResizeOptions::fromText("0.5", "--resize")
//   --wb as-shot | region:x,y,w,h | multipliers:r,g,b
//
// Coordinates are pixels of the step's input images, origin at the top-left corner, x right,
// y down; a rectangle x,y,w,h covers columns x..x+w-1 and rows y..y+h-1.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace surrogate::stages {

using Parameters = std::vector<std::pair<std::string, std::string>>;

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  long long area() const { return static_cast<long long>(width) * height; }
  std::string text() const;  // "x,y,w,h"
};

struct CropOptions {
  std::string method = "user";  // "user": `rect` as given; "auto": clear of the spheres
  PixelRect rect;               // user only
  // auto only: the clearance kept around each sphere, as a fraction of its radius (covers the
  // sphere's shadow and the rim of its stand); larger trades image area for safety.
  double margin = 0.25;

  Parameters toParameters() const;
  static CropOptions fromParameters(const Parameters& p, const std::string& origin = "carrier");
  static CropOptions fromText(const std::string& text, const std::string& origin = "--crop");
};

// The smallest side a resize may give: a fit of a few pixels is no surrogate of anything.
inline constexpr int kMinResizeSide = 16;

struct ResizeOptions {
  // Either a scale factor (0 < factor <= 1) or a target size; factor 0 means "use the size".
  // Either way the result has at least kMinResizeSide pixels per side.
  double factor = 0;
  int width = 0, height = 0;
  // "area": each output pixel is the area-weighted mean of the input pixels it covers,
  // averaged in linear light, exact integer weights (deterministic). Reduces only.
  std::string filter = "area";

  // The output size for an input of w x h; Error(Usage) naming `origin` if it would enlarge or
  // give fewer than kMinResizeSide pixels on a side.
  std::pair<int, int> outputSize(int w, int h, const std::string& origin = "carrier") const;
  Parameters toParameters() const;
  static ResizeOptions fromParameters(const Parameters& p, const std::string& origin = "carrier");
  static ResizeOptions fromText(const std::string& text, const std::string& origin = "--resize");
};

struct WhiteBalanceOptions {
  // "as-shot": no further gains (camera raw: the decoder applied the camera's as-shot
  // multipliers, see ImageDecode whiteBalance=camera; exports: whatever the camera or the
  // exporting software did). "region": gains that make the grey region neutral. "multipliers":
  // the gains given.
  std::string mode = "as-shot";
  PixelRect region;                         // region only
  std::array<double, 3> multipliers{1, 1, 1};  // multipliers only; each > 0
  // Encoding of the values the fit reads: "srgb" (display-referred, like the decoded stack and
  // every RTI viewer expects) or "linear" (proportional to light, for radiometric work).
  std::string outputSpace = "srgb";

  Parameters toParameters() const;
  static WhiteBalanceOptions fromParameters(const Parameters& p, const std::string& origin = "carrier");
  static WhiteBalanceOptions fromText(const std::string& text, const std::string& origin = "--wb");
};

// A circle to keep out of the automatic crop (pixel centres at integer coordinates).
struct Circle {
  double cx = 0, cy = 0, r = 0;
};

// The largest axis-aligned rectangle inside a width x height frame that contains no pixel
// within r * (1 + margin) of any circle's centre (each circle is kept out with its bounding
// square). Ties go to the first candidate in a fixed order (top-left first). Returns an empty
// rectangle (area 0) when the circles leave no room.
PixelRect largestClearRectangle(int width, int height, const std::vector<Circle>& circles,
                                double margin);

// Per-channel white-balance gains from a grey region: `means[i]` is the mean linear R, G, B of
// the region in image i; the median over the images of each channel (the mean of the two
// middle values for an even count) gives m; gains are (mG/mR, 1, mG/mB). Error(Input) naming
// `origin` when a median is zero (a black region cannot set a white balance).
std::array<double, 3> greyRegionGains(const std::vector<std::array<double, 3>>& means,
                                      const std::string& origin);

// The median of values (mean of the two middle ones for an even count); values is reordered.
double medianOf(std::vector<double> values);

}  // namespace surrogate::stages
