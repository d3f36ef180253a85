// No phantom chart: findChart on real photographs that hold no ColorChecker (the RTI and
// photometric-stereo sets kept in tests/data/real-rti: a glossy sphere with a room mirrored in
// it, a chrome ball on black, a ceramic cat) finds nothing. A phantom would recolour a whole
// capture, so every image of each set is searched, in colour and grey.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "colour/chart_detection.h"
#include "image/decode.h"
#include "image/raw_settings.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

// A grey image as RGB (the objects set is grey; a capture stack is RGB).
Image asRgb(const Image& im) {
  if (im.channels == 3) return im;
  Image out(im.width, im.height, 3);
  out.transfer = im.transfer;
  out.bitsPerSample = im.bitsPerSample;
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) out.pixels[3 * i + c] = im.pixels[i];
  return out;
}

}  // namespace

TEST_CASE("findChart finds no chart in real photographs without one", "[colour][chart][real]") {
  const fs::path root = fs::path(SURROGATE_SOURCE_DIR) / "tests" / "data" / "real-rti";
  int searched = 0;
  for (const char* set : {"lightprobe-1", "lightprobe-2", "chrome", "objects"}) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(root / set)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".JPG" || ext == ".png") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    REQUIRE(files.size() >= 12);
    for (const fs::path& f : files) {
      INFO(f.string());
      const Image im = asRgb(image::decodeImage(f.string(), image::RawDecodeSettings{}));
      CHECK_FALSE(colour::findChart(im).has_value());
      ++searched;
    }
  }
  CHECK(searched >= 48);
}
