// PNG and JPEG writing: exact round trips, deterministic bytes, no partial files.
#include "fixtures.h"
#include "core/atomic_file.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
Image ramp(int bits) {
  Image im(40, 10, 3);
  im.bitsPerSample = bits;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      im.at(x, y, 0) = static_cast<std::uint16_t>(x * 1601);
      im.at(x, y, 1) = static_cast<std::uint16_t>(y * 7000);
      im.at(x, y, 2) = static_cast<std::uint16_t>(65535 - x * 1601);
    }
  return im;
}
}  // namespace

TEST_CASE("a 16-bit PNG round-trips exactly and its bytes are the same every time") {
  const fs::path dir = test::scratchDir("write16");
  const Image im = ramp(16);
  image::writePng(im, dir / "a.png");
  image::writePng(im, dir / "b.png");
  const Image back = image::decodeImage(dir / "a.png", image::RawDecodeSettings());
  CHECK(back.bitsPerSample == 16);
  CHECK(back.channels == 3);
  CHECK(back.pixels == im.pixels);
  CHECK(readFile(dir / "a.png", "test") == readFile(dir / "b.png", "test"));
  // Only the two files: no temporary left behind.
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 2);
  fs::remove_all(dir);
}

TEST_CASE("an 8-bit PNG rounds 16-bit values to the nearest 8-bit value") {
  const fs::path dir = test::scratchDir("write8");
  Image im(4, 1, 1);
  im.bitsPerSample = 8;
  im.pixels = {0, 257 * 10 + 128, 257 * 10 + 129, 65535};  // 10.498 -> 10, 10.502 -> 11
  image::writePng(im, dir / "grey.png");
  const Image back = image::decodeImage(dir / "grey.png", image::RawDecodeSettings());
  CHECK(back.bitsPerSample == 8);
  CHECK(back.pixels == std::vector<std::uint16_t>{0, 10 * 257, 11 * 257, 65535});
  fs::remove_all(dir);
}

TEST_CASE("a JPEG preview reads back close to what was written") {
  const fs::path dir = test::scratchDir("write-jpeg");
  Image flat(16, 16, 3);
  for (int i = 0; i < 256; ++i) {
    flat.pixels[3 * i] = 200 * 257;
    flat.pixels[3 * i + 1] = 100 * 257;
    flat.pixels[3 * i + 2] = 50 * 257;
  }
  image::writeJpeg(flat, dir / "p.jpg", 95);
  const Image back = image::decodeImage(dir / "p.jpg", image::RawDecodeSettings());
  CHECK(std::abs(back.at(8, 8, 0) / 257 - 200) <= 3);
  CHECK(std::abs(back.at(8, 8, 1) / 257 - 100) <= 3);
  CHECK(std::abs(back.at(8, 8, 2) / 257 - 50) <= 3);
  CHECK_THROWS_AS(image::writeJpeg(flat, dir / "q.jpg", 0), Error);
  fs::remove_all(dir);
}

TEST_CASE("writing an empty image is an error and leaves no file") {
  const fs::path dir = test::scratchDir("write-empty");
  CHECK_THROWS_AS(image::writePng(Image(), dir / "x.png"), Error);
  CHECK(fs::is_empty(dir));
  fs::remove_all(dir);
}
