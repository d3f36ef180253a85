#include "image/write.h"

#include <opencv2/core/version.hpp>

#include <string>

#include "core/atomic_file.h"
#include "image/png_encoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

void writePng(const Image& image, const fs::path& path) {
  writeFileAtomically(path, encodePng(image, path.string()));
}

void writeJpeg(const Image& image, const fs::path& path, int quality) {
  Image8 narrow;
  narrow.width = image.width;
  narrow.height = image.height;
  narrow.channels = image.channels;
  narrow.pixels.resize(image.pixels.size());
  narrowSamples(image.pixels.data(), image.pixels.size(), narrow.pixels.data());  // rounded, as PNG
  writeFileAtomically(path, encodeJpeg(narrow, quality, path.string()));
}

std::string opencvVersion() { return CV_VERSION; }

}  // namespace surrogate::image
