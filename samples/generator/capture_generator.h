// A synthetic Highlight-RTI capture with known truth, for tests, benchmarks and the demo.
//
// Scene (orthographic camera; image x right, y down; camera frame X right, Y up, Z towards the
// camera): a textured relief (smooth bumps, engraved strokes, fine noise) lit Lambertian by a
// distant light, with cast shadows, and one or two glossy black spheres standing on it whose
// specular highlight peaks exactly at the mirror point N = normalize(L + V), V = (0, 0, 1):
//
//     highlight centre (pixels) = (cx + r Nx, cy - r Ny)
//
// Near lights (lightDistance D > 0, frame widths; the frame coordinates of issue 53: origin at
// image point ((W-1)/2, (H-1)/2) on the object's plane, X right, Y up, Z towards the camera):
// light i stands at X_i = D W l_i, l_i the direction planCapture gives (so lights.lp keeps it).
// Every point p of the relief (its own height as z) and of a sphere (centre (cx - (W-1)/2,
// (H-1)/2 - cy, r) + r N) is lit from L(p) = normalize(X_i - p) with the flash's intensity times
// (|X_i| / |X_i - p|)^2: Lambert, cast shadows and the specular lobe all use that L(p), so a
// sphere's highlight is where N bisects V and L of that very point. The room's ambient light and
// reflections do not fall off. D = 0 (the default) is the distant light, byte for byte.
//
// Each shot is written twice, as a photographer's card and export would hold it:
//   original-captures/IMG_0001.dng   uncompressed 16-bit RGGB Bayer mosaic (libtiff), with the
//                                    DNG and EXIF tags LibRaw and Exiv2 need
//   jpeg-exports/IMG_0001.jpg        the sRGB-encoded 8-bit export
// and the truth beside them in truth/ (lights.lp, spheres.txt, generator.txt, normals.png: the
// true normals encoded as the pipeline's normals.png, src/fit/normals.h; light-positions.txt for
// near lights; colour-chart.txt with a chart): never inside the folders a tool reads.
//
// Colour (issue 54): with colourChart a ColorChecker Classic lies flat on the relief, its patches'
// albedo the reference's linear sRGB; colourCast is the camera's 3x3 response applied to every
// pixel's linear RGB (both outputs), so an uncorrected capture is measurably off.
//
//   GeneratorOptions o;  o.images = 24;  o.seed = 7;
//   writeCapture(o, "/tmp/capture");          // identical bytes for identical options
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace surrogate::generator {

enum class OutputFormats { Both, Dng, Jpeg };

inline constexpr std::array<double, 9> kNoColourCast = {1, 0, 0, 0, 1, 0, 0, 0, 1};

// The colour casts by name: "none" (identity), "warm" (a tungsten-like cast: red up, blue well
// down, with cross-talk between channels), "cool" (the opposite), or nine numbers "m00,m01,
// ...,m22" (row-major). Error(Usage) otherwise. The matrices are in generator/chart.cpp.
std::array<double, 9> parseColourCast(const std::string& text);

struct GeneratorOptions {
  int images = 24;               // number of shots (lights)
  int width = 1200;              // pixels
  int height = 800;
  int spheres = 1;               // 1 or 2
  double sphereRadius = 80;      // pixels
  double noise = 100;            // read noise, 16-bit DN (shot noise is added on top)
  int jpegQuality = 95;          // of the exports
  std::uint64_t seed = 1;        // everything random derives from it
  bool strongTexture = false;    // high-contrast albedo pattern: a hard case for detection
  bool shadows = true;           // cast shadows of the relief and the spheres
  OutputFormats formats = OutputFormats::Both;
  int threads = 0;               // 0 = all cores; output is identical at any count
  double lightDistance = 0;      // frame widths from the frame's centre; 0 = at infinity
  double sphereSeparation = 0;   // > 0 (two spheres): pixels from the first sphere's centre to
                                 // the second's, on its row to its left; 0 = the two corners

  // Hard cases (docs/hrti-math.md, "Generated hard cases"). Each is off by default, and a
  // capture made without them has the bytes it had before they existed.
  bool reflections = false;      // a bright window and a dim room mirrored in every sphere, the
                                 // same in every shot (a studio's window or softbox)
  int dustSpecks = 0;            // bright specks of dust fixed on each sphere (0-100); lit by the
                                 // flash, they brighten and darken with the light
  double glare = 0;              // a lens glare streak through each highlight: its brightness next
                                 // to the core, as a fraction of full scale (0 = none, up to 2)
  int darkFrame = -1;            // this shot (0-based) exposed at kDarkExposure: a weak flash
  int noFlashFrame = -1;         // this shot (0-based) lit by the room's ambient light alone
  double lightConeDeg = 0;       // > 0: every light within this angle of one direction (a narrow
                                 // cone of lights), instead of spread over the hemisphere
  double lightConeElevationDeg = 90;  // that direction's elevation (90: the view axis); the cone
                                      // must stay kMinConeElevationDeg above the horizon

  // Colour (issue 54): a ColorChecker Classic lying flat on the relief, and the camera's
  // colour response. Off by default, and a capture made without them keeps its bytes.
  bool colourChart = false;      // the chart in the bottom-left of the frame (generator/chart.h)
  std::string chartReference = "colorchecker-classic-2014";  // its edition (colour/chart_reference.h)
  std::array<double, 9> colourCast = kNoColourCast;  // camera RGB = M * scene RGB, row-major,
                                                     // in linear light before exposure and noise
  double exposure = 1;           // multiplies the exposure of every shot (kExposure)
};

// The dark frame's exposure, a fraction of the others' (GeneratorOptions::darkFrame).
inline constexpr double kDarkExposure = 0.05;
// The lowest elevation a narrow cone of lights may reach (GeneratorOptions::lightConeDeg).
inline constexpr double kMinConeElevationDeg = 5;

struct SphereTruth {
  double cx, cy, r;  // pixels, origin at the centre of the top-left pixel
};

// The chart of GeneratorOptions::colourChart: the grid's corners (the outer corners of patches
// 0, 5, 23 and 18, colour/chart_detection.h's order) and each patch's centre, in pixels (x
// right, y down, pixel centres at integer coordinates). reference empty: no chart.
struct ChartTruth {
  std::string reference;
  double angleDeg = 0;                        // its rotation in the image (clockwise on screen)
  double patchSide = 0, gap = 0, border = 0;  // pixels
  std::array<std::array<double, 2>, 4> corners{};
  std::array<std::array<double, 2>, 24> centres{};
};

struct CaptureTruth {
  std::vector<std::array<double, 3>> lights;  // unit vectors, one per shot
  std::vector<SphereTruth> spheres;
  // Near lights only (empty at infinity): each light's position in the frame coordinates
  // above, pixels: lightDistance * width * lights[i].
  std::vector<std::array<double, 3>> positions;
  ChartTruth chart;  // GeneratorOptions::colourChart only
};

// The lowest near-light distance, frame widths: nearer, a light would hang over the frame.
inline constexpr double kMinLightDistance = 1;

// The lights and spheres the options give (deterministic in the seed).
CaptureTruth planCapture(const GeneratorOptions& options);

// Linear 16-bit RGB of shot `index` (0-based) after exposure and noise: what the DNG's
// mosaic samples (before its black level is added).
Image renderShot(const GeneratorOptions& options, const CaptureTruth& truth, int index);

// The true normals as the pipeline's normals.png encodes them (src/fit/normals.h): 16-bit RGB,
// value = round((n + 1) / 2 * 65535), x right, y up, z towards the camera, rows top first; the
// relief's normal, or the sphere's where the pixel's centre is on a sphere.
Image trueNormals(const GeneratorOptions& options, const CaptureTruth& truth);

// DNG tags that vary per shot.
struct DngInfo {
  std::string make = "Surrogate";
  std::string model = "Synthetic HRTI";
  std::string serial = "SYN-0001";
  std::string dateTimeOriginal = "2026:01:01 12:00:00";
  double exposureSeconds = 1.0 / 125;
  double fNumber = 8;
  int iso = 100;
  double focalLengthMm = 50;
};

// Writes a linear RGB image as a DNG holding its RGGB mosaic (atomic).
void writeDng(const Image& linearRgb, const DngInfo& info, const std::filesystem::path& path);

// Writes the whole capture into `dir` (created; must be empty or absent).
void writeCapture(const GeneratorOptions& options, const std::filesystem::path& dir);

}  // namespace surrogate::generator
