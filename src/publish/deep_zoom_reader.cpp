#include "publish/deep_zoom_reader.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <algorithm>
#include <cstring>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "publish/layout_files.h"
#include "publish/plane_decode.h"

namespace surrogate::publish {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "render";
const char* const kDeepZoomNamespace = "http://schemas.microsoft.com/deepzoom/2008";
// A .dzi is a few hundred bytes: anything much larger is not one.
constexpr std::uintmax_t kMaxDziBytes = 64u << 10;
// Tile sides the readers accept (vips and Surrogate write 254 or 256; 1 would mean a file a texel).
constexpr int kMinTileSide = 16, kMaxTileSide = 65500;

struct Descriptor {
  int tileSize = 0, overlap = 0, width = 0, height = 0;
  std::string format;
};

[[noreturn]] void notDeepZoom(const fs::path& dzi, const std::string& what) {
  throw Error(ErrorKind::Input, dzi.string(), kStep, "is not a Deep Zoom descriptor render reads: " + what);
}

std::optional<long> numberAttribute(const xmlNode* node, const char* name) {
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  if (!value) return std::nullopt;
  const std::string text(reinterpret_cast<const char*>(value));
  xmlFree(value);
  const bool digits = std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (text.empty() || text.size() > 9 || !digits)
    return std::nullopt;
  return std::stol(text);
}

std::string textAttribute(const xmlNode* node, const char* name) {
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  std::string text = value ? reinterpret_cast<const char*>(value) : "";
  xmlFree(value);
  return text;
}

const xmlNode* sizeElement(const xmlNode* image) {
  for (const xmlNode* n = image->children; n; n = n->next)
    if (n->type == XML_ELEMENT_NODE && std::strcmp(reinterpret_cast<const char*>(n->name), "Size") == 0) return n;
  return nullptr;
}

// The root <Image TileSize Overlap Format> and its <Size Width Height>; nullopt when absent.
std::optional<Descriptor> descriptorOf(const xmlNode* image) {
  if (!image || std::strcmp(reinterpret_cast<const char*>(image->name), "Image") != 0 || !image->ns ||
      std::strcmp(reinterpret_cast<const char*>(image->ns->href), kDeepZoomNamespace) != 0)
    return std::nullopt;
  const xmlNode* size = sizeElement(image);
  const auto tile = numberAttribute(image, "TileSize"), overlap = numberAttribute(image, "Overlap");
  const auto width = size ? numberAttribute(size, "Width") : std::nullopt;
  const auto height = size ? numberAttribute(size, "Height") : std::nullopt;
  if (!tile || !overlap || !width || !height) return std::nullopt;
  return Descriptor{static_cast<int>(*tile), static_cast<int>(*overlap), static_cast<int>(*width),
                    static_cast<int>(*height), textAttribute(image, "Format")};
}

Descriptor readDescriptor(const fs::path& dzi, int width, int height) {
  const std::string xml = readLayoutFile(dzi, kMaxDziBytes, kStep);
  xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), dzi.c_str(), nullptr,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
  if (!doc) notDeepZoom(dzi, "it is not well-formed XML");
  const std::optional<Descriptor> d = descriptorOf(xmlDocGetRootElement(doc));
  xmlFreeDoc(doc);
  if (!d) notDeepZoom(dzi, "it has no Deep Zoom <Image> with TileSize, Overlap and a <Size> of Width and Height");
  if (d->width != width || d->height != height)
    notDeepZoom(dzi, "its size is " + std::to_string(d->width) + "x" + std::to_string(d->height) +
                         ", but info.json gives " + std::to_string(width) + "x" + std::to_string(height));
  if (d->tileSize < kMinTileSide || d->tileSize > kMaxTileSide || d->overlap > d->tileSize)
    notDeepZoom(dzi, "its TileSize " + std::to_string(d->tileSize) + " or Overlap " + std::to_string(d->overlap) +
                         " is outside what the viewers use (a tile side from 16, an overlap up to the side)");
  if (d->format != "jpg" && d->format != "jpeg")
    notDeepZoom(dzi, "its tiles are not JPEG (Format \"" + d->format + "\")");
  return *d;
}

// The highest level number: halvings (rounding up) down to one tile, or down to one texel.
int fullLevel(const fs::path& tiles, const Descriptor& d) {
  int toOneTile = 0, toOneTexel = 0;
  for (int w = d.width, h = d.height; w > d.tileSize || h > d.tileSize; w = (w + 1) / 2, h = (h + 1) / 2) ++toOneTile;
  for (int w = d.width, h = d.height; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2) ++toOneTexel;
  std::error_code ec;
  return fs::is_directory(tiles / std::to_string(toOneTexel), ec) ? toOneTexel : toOneTile;
}

// Copies the inner part of tile (col, row) (its overlap left out) into `plane`.
void placeTile(const fs::path& file, const Descriptor& d, int col, int row, std::vector<std::uint8_t>* plane) {
  const int x0 = col * d.tileSize, y0 = row * d.tileSize;
  const int x1 = std::min(d.width, x0 + d.tileSize), y1 = std::min(d.height, y0 + d.tileSize);
  const int left = col > 0 ? d.overlap : 0, top = row > 0 ? d.overlap : 0;
  const int tileWidth = std::min(d.width, x1 + d.overlap) - (x0 - left);
  const int tileHeight = std::min(d.height, y1 + d.overlap) - (y0 - top);
  if (!somethingAt(file))
    throw Error(ErrorKind::Input, file.string(), kStep,
                "is missing: a tile of the plane's full-size level; publish the model again");
  // Never through a link; far larger than a JPEG tile of its size, refused before it is read.
  const std::uintmax_t texels = static_cast<std::uintmax_t>(tileWidth) * static_cast<std::uintmax_t>(tileHeight);
  const std::vector<std::uint8_t> tile = decodePlaneJpeg(
      readLayoutFile(file, texels * kMaxJpegBytesPerTexel + kJpegHeaderBytes, kStep), tileWidth, tileHeight,
      file.string());
  const auto rowBytes = static_cast<std::size_t>(x1 - x0) * 3;
  for (int y = y0; y < y1; ++y) {
    const std::size_t from = (static_cast<std::size_t>(y - y0 + top) * tileWidth + left) * 3;
    std::copy_n(tile.begin() + static_cast<std::ptrdiff_t>(from), rowBytes,
                plane->begin() + static_cast<std::ptrdiff_t>((static_cast<std::size_t>(y) * d.width + x0) * 3));
  }
}
}  // namespace

std::vector<std::uint8_t> readDeepZoomPlane(const fs::path& dzi, int width, int height) {
  const Descriptor d = readDescriptor(dzi, width, height);
  const fs::path tiles = dzi.parent_path() / (dzi.stem().string() + "_files");
  refuseLinkedFolder(tiles, kStep);
  const fs::path level = tiles / std::to_string(fullLevel(tiles, d));
  refuseLinkedFolder(level, kStep);
  std::vector<std::uint8_t> plane(static_cast<std::size_t>(width) * height * 3);
  for (int row = 0; row * d.tileSize < height; ++row)
    for (int col = 0; col * d.tileSize < width; ++col)
      placeTile(level / (std::to_string(col) + "_" + std::to_string(row) + "." + d.format), d, col, row, &plane);
  return plane;
}

}  // namespace surrogate::publish
