#include "publish/deep_zoom.h"

#include <algorithm>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/parallel.h"
#include "publish/rgb_jpeg.h"

namespace surrogate::publish {

namespace {
cv::Mat view(const PlaneRaster& r) {
  return cv::Mat(r.height, r.width, CV_8UC3, const_cast<std::uint8_t*>(r.rgb.data()));
}

PlaneRaster fromMat(const cv::Mat& m) {
  PlaneRaster r;
  r.width = m.cols;
  r.height = m.rows;
  r.rgb.resize(static_cast<std::size_t>(m.cols) * m.rows * 3);
  for (int y = 0; y < m.rows; ++y)
    std::copy(m.ptr<std::uint8_t>(y), m.ptr<std::uint8_t>(y) + m.cols * 3, r.rgb.data() + static_cast<std::size_t>(y) * m.cols * 3);
  return r;
}

std::string dziXml(int width, int height, int tileSize) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<Image xmlns=\"http://schemas.microsoft.com/deepzoom/2008\" Format=\"jpg\" Overlap=\"" +
         std::to_string(kDeepZoomOverlap) + "\" TileSize=\"" + std::to_string(tileSize) + "\">\n  <Size Width=\"" +
         std::to_string(width) + "\" Height=\"" + std::to_string(height) + "\"/>\n</Image>\n";
}

struct Tile {
  int level, col, row;
};

// The texels of one tile, its overlap included, clipped to the level.
std::string encodeTile(const PlaneRaster& level, const Tile& t, int tileSize, int quality) {
  const int x0 = std::max(0, t.col * tileSize - kDeepZoomOverlap);
  const int y0 = std::max(0, t.row * tileSize - kDeepZoomOverlap);
  const int x1 = std::min(level.width, (t.col + 1) * tileSize + kDeepZoomOverlap);
  const int y1 = std::min(level.height, (t.row + 1) * tileSize + kDeepZoomOverlap);
  const PlaneRaster part = fromMat(view(level)(cv::Rect(x0, y0, x1 - x0, y1 - y0)));
  return encodeRgbJpeg(part.rgb, part.width, part.height, quality);
}
}  // namespace

std::vector<std::uint8_t> halveTexels(const std::uint8_t* texels, int width, int height, int channels) {
  const cv::Mat source(height, width, CV_8UC(channels), const_cast<std::uint8_t*>(texels));
  cv::Mat even;
  cv::copyMakeBorder(source, even, 0, height % 2, 0, width % 2, cv::BORDER_REPLICATE);
  cv::Mat half;
  // An exact factor of two: OpenCV's area resampling is then the mean of each 2x2 block.
  cv::resize(even, half, cv::Size(even.cols / 2, even.rows / 2), 0, 0, cv::INTER_AREA);
  const std::size_t row = static_cast<std::size_t>(half.cols) * channels;
  std::vector<std::uint8_t> out(row * half.rows);
  for (int y = 0; y < half.rows; ++y) std::copy(half.ptr<std::uint8_t>(y), half.ptr<std::uint8_t>(y) + row, out.data() + y * row);
  return out;
}

PlaneRaster halfSize(const PlaneRaster& level) {
  return {(level.width + 1) / 2, (level.height + 1) / 2, halveTexels(level.rgb.data(), level.width, level.height, 3)};
}

int halvingsToFit(int width, int height, int side) {
  int halvings = 0;
  for (; width > side || height > side; ++halvings) {
    width = (width + 1) / 2;
    height = (height + 1) / 2;
  }
  return halvings;
}

int deepZoomLevelCount(int width, int height, int tileSize) { return 1 + halvingsToFit(width, height, tileSize); }

std::vector<std::pair<std::string, std::string>> deepZoomFiles(const PlaneRaster& full, const std::string& stem,
                                                               int tileSize, int quality, int threads) {
  const int count = deepZoomLevelCount(full.width, full.height, tileSize);
  // The levels below the full one (the full one is `full` itself, not copied).
  std::vector<PlaneRaster> lower(static_cast<std::size_t>(count - 1));
  for (int l = count - 2; l >= 0; --l)
    lower[static_cast<std::size_t>(l)] = halfSize(l == count - 2 ? full : lower[static_cast<std::size_t>(l) + 1]);
  const auto levelAt = [&](int l) -> const PlaneRaster& {
    return l == count - 1 ? full : lower[static_cast<std::size_t>(l)];
  };
  std::vector<Tile> tiles;
  for (int l = 0; l < count; ++l) {
    const PlaneRaster& level = levelAt(l);
    for (int row = 0; row * tileSize < level.height; ++row)
      for (int col = 0; col * tileSize < level.width; ++col) tiles.push_back({l, col, row});
  }
  std::vector<std::string> encoded(tiles.size());
  parallelFor(tiles.size(), 4, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      encoded[i] = encodeTile(levelAt(tiles[i].level), tiles[i], tileSize, quality);
  });
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back(stem + ".dzi", dziXml(full.width, full.height, tileSize));
  for (std::size_t i = 0; i < tiles.size(); ++i)
    files.emplace_back(stem + "_files/" + std::to_string(tiles[i].level) + "/" + std::to_string(tiles[i].col) + "_" +
                           std::to_string(tiles[i].row) + ".jpg",
                       std::move(encoded[i]));
  return files;
}

}  // namespace surrogate::publish
