// Private to src/publish: a plane stored as Deep Zoom tiles (plane_j.dzi beside
// plane_j_files/LEVEL/COL_ROW.jpg, docs/formats.md) assembled back into the whole plane from
// the tiles of its full-size level, for publish/web_reader.h.
//
// The full-size level is the highest-numbered one: Surrogate numbers levels from the first
// that fits in one tile (OpenLIME's "deepzoom"), the original Deep Zoom from a 1-pixel level
// ("deepzoom1px"); both are read. Tile (col, row) must hold exactly the texels
// [col*T, col*T + T) x [row*T, row*T + T) of the level, widened by the overlap on every side
// that is not the level's edge; only its inner part is used.
//
//   std::vector<std::uint8_t> rgb = readDeepZoomPlane("web/plane_0.dzi", 12000, 9000);
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace surrogate::publish {

// Throws Error(Input) naming the .dzi or the tile at fault: a .dzi that is not a Deep Zoom
// descriptor of `width` x `height` JPEG tiles, a missing tile, a tile that is not a JPEG of its
// size. Returns RGBRGB..., rows top-first.
std::vector<std::uint8_t> readDeepZoomPlane(const std::filesystem::path& dzi, int width, int height);

}  // namespace surrogate::publish
