// Private to src/publish: plane images at reduced sizes and cut into Deep Zoom tiles, as
// OpenLIME's "deepzoom" layout and relight's tiled export read them (docs/formats.md, "Deep
// Zoom tiles").
//
// A pyramid has levels 0..n-1: level n-1 is the plane at full size, each level below it half
// the one above (odd sizes rounded up), and level 0 the first one that fits in one tile. Tile
// (col, row) of a level covers [col*T, col*T + T) x [row*T, row*T + T) of that level, widened
// by kDeepZoomOverlap texels on every side that is not the level's edge, and is written as
// plane_j_files/LEVEL/COL_ROW.jpg beside plane_j.dzi.
//
//   PlaneRaster smaller = halfSize(full);                     // the level below
//   auto files = deepZoomFiles(full, "plane_0", 256, 95);   // plane_0.dzi first, then the tiles
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace surrogate::publish {

// Texels each tile shares with its neighbours, on each side (vips dzsave's default for Deep
// Zoom): the viewers interpolate between texels, and without a shared border they would
// clamp at every tile edge and show seams.
constexpr int kDeepZoomOverlap = 1;

// Three bytes per texel (a plane's three coefficients, or an RGB picture), rows top-first.
struct PlaneRaster {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

// The next level down: 2x2 averages rounded to nearest (an odd last column or row repeated),
// ceil(width/2) x ceil(height/2). Integer arithmetic only: the same bytes on every machine.
PlaneRaster halfSize(const PlaneRaster& level);

// The same halving of `width` x `height` texels of `channels` bytes each (interleaved, rows
// top-first), for a model's coefficients: 2x2 means (OpenCV's area resampling, which rounds
// them to nearest for 3 channels and may differ by a unit for others), the same bytes on
// every run.
std::vector<std::uint8_t> halveTexels(const std::uint8_t* texels, int width, int height, int channels);

// Halvings (rounding up) until both sides are at most `side`.
int halvingsToFit(int width, int height, int side);

// Number of levels: 1 + the halvings until both sides are at most tileSize.
int deepZoomLevelCount(int width, int height, int tileSize);

// "<stem>.dzi" and every tile "<stem>_files/L/C_R.jpg" of the pyramid of `full`, each tile
// encoded at `quality` (publish/rgb_jpeg.h). Tiles are encoded on `threads` workers (0 = all
// cores); the bytes do not depend on the count.
std::vector<std::pair<std::string, std::string>> deepZoomFiles(const PlaneRaster& full, const std::string& stem,
                                                               int tileSize, int quality, int threads);

}  // namespace surrogate::publish
