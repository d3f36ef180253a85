// Strict decoding: a decoder's warning that the data is damaged refuses the image with the
// library's own words (DamagedImageError), unless damage is accepted; then the image decodes
// as the library can and the words are in the report. Sizes declared by headers are checked
// before any pixel is allocated.
#include <atomic>
#include <chrono>
#include <thread>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "damage.h"
#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

Image texture(int w, int h) {
  Image im(w, h, 3);
  im.bitsPerSample = 8;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        im.at(x, y, c) = static_cast<std::uint16_t>(((x * (c + 3) + y * 7 + (x * y) % 13) % 256) * 257);
  return im;
}

image::DecodeOptions accepting() {
  image::DecodeOptions o;
  o.acceptDamage = true;
  return o;
}

// Refused as damaged, naming the file, with `words` (the library's) in the message; returns it.
std::string refusedAsDamaged(const fs::path& p, const std::string& library, const std::string& words) {
  INFO(p.filename().string());
  try {
    image::decodeImage(p, image::RawDecodeSettings());
  } catch (const image::DamagedImageError& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == p.string());
    CHECK(e.library() == library);
    CHECK_THAT(e.message(), Catch::Contains(words));
    REQUIRE_FALSE(e.warnings().empty());
    return e.message();
  }
  FAIL("not refused as damaged: " << p);
  return {};
}

// Accepted: decodes, and the report carries the library's words.
Image acceptedWith(const fs::path& p, const std::string& words) {
  INFO(p.filename().string());
  image::DecodeReport report;
  Image im = image::decodeImage(p, image::RawDecodeSettings(), &report, accepting());
  REQUIRE_FALSE(report.decoderWarnings.empty());
  CHECK_THAT(report.decoderWarnings.front(), Catch::Contains(words));
  return im;
}

}  // namespace

TEST_CASE("a JPEG with half its data missing and its end marker re-appended is refused with libjpeg's words") {
  const fs::path dir = test::scratchDir("half-jpeg");
  image::writeJpeg(texture(160, 300), dir / "whole.jpg", 92);
  test::writeBytes(dir / "half.jpg", test::halfJpeg(test::readBytes(dir / "whole.jpg")));
  CHECK(image::probeImage(dir / "half.jpg").height == 300);  // the structure is whole
  image::DecodeReport sound;
  image::decodeImage(dir / "whole.jpg", image::RawDecodeSettings(), &sound);
  CHECK(sound.decoderWarnings.empty());

  const std::string message = refusedAsDamaged(dir / "half.jpg", "libjpeg", "premature end of data segment");
  CHECK_THAT(message, Catch::Contains("Corrupt JPEG data"));
  const Image im = acceptedWith(dir / "half.jpg", "libjpeg: Corrupt JPEG data: premature end of data segment");
  CHECK(im.height == 300);
  // What libjpeg made up: the bottom rows are flat grey (128).
  CHECK(im.at(80, 299, 0) == 128 * 257);
  fs::remove_all(dir);
}

TEST_CASE("bit-flipped JPEGs that libjpeg warns about are refused, and none crashes") {
  const fs::path dir = test::scratchDir("flipped-jpeg");
  image::writeJpeg(texture(96, 64), dir / "whole.jpg", 90);
  const std::string whole = test::readBytes(dir / "whole.jpg");
  int warned = 0;
  for (std::uint32_t seed = 1; seed <= 30; ++seed) {
    const fs::path p = dir / ("flip" + std::to_string(seed) + ".jpg");
    test::writeBytes(p, test::flipJpegBits(whole, seed, 6));
    INFO(p.filename().string());
    try {
      image::decodeImage(p, image::RawDecodeSettings());
    } catch (const image::DamagedImageError& e) {
      ++warned;
      CHECK(e.library() == "libjpeg");
      image::DecodeReport report;
      CHECK_NOTHROW(image::decodeImage(p, image::RawDecodeSettings(), &report, accepting()));
      CHECK_FALSE(report.decoderWarnings.empty());
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);  // libjpeg gave up: refused, never accepted
    }
  }
  // Flipped bits in entropy-coded data are not always detectable (a flip can make another
  // valid code); most are.
  CHECK(warned >= 10);
  fs::remove_all(dir);
}

TEST_CASE("a PNG with a broken chunk CRC is refused with libpng's words") {
  const fs::path dir = test::scratchDir("png-crc");
  cv::Mat m(40, 50, CV_16UC3);
  cv::randu(m, 0, 65535);
  REQUIRE(cv::imwrite((dir / "whole.png").string(), m));
  const std::string whole = test::readBytes(dir / "whole.png");
  test::writeBytes(dir / "idat.png", test::pngWithBadCrc(whole, "IDAT"));
  refusedAsDamaged(dir / "idat.png", "libpng", "CRC error");
  // Accepted, the data is used as it is: here only the CRC was damaged.
  const Image accepted = acceptedWith(dir / "idat.png", "libpng: IDAT: CRC error");
  CHECK(accepted.pixels == image::decodeImage(dir / "whole.png", image::RawDecodeSettings()).pixels);
  fs::remove_all(dir);
}

TEST_CASE("a TIFF whose last strip is cut short is refused with libtiff's words") {
  const fs::path dir = test::scratchDir("tiff-strip");
  cv::Mat m(64, 48, CV_16UC3);
  cv::randu(m, 0, 65535);
  REQUIRE(cv::imwrite((dir / "whole.tif").string(), m, {cv::IMWRITE_TIFF_COMPRESSION, 1}));
  test::writeBytes(dir / "short.tif", test::tiffWithShortStrip(test::readBytes(dir / "whole.tif")));
  CHECK(image::probeImage(dir / "short.tif").width == 48);  // every byte is in the file
  const std::string message = refusedAsDamaged(dir / "short.tif", "libtiff", "libtiff reports");
  const Image im = acceptedWith(dir / "short.tif", "libtiff: ");
  CHECK(im.height == 64);
  CHECK(im.at(47, 63, 0) == 0);  // the missing part of the last strip stays black
  fs::remove_all(dir);
}

TEST_CASE("a DNG with a corrupt lossless-JPEG tile is refused with LibRaw's words") {
  const fs::path dir = test::scratchDir("dng-tile");
  const test::LosslessDng dng = test::losslessDng(64, 48);
  test::writeBytes(dir / "sound.dng", dng.bytes);
  image::DecodeReport report;
  const Image sound = image::decodeImage(dir / "sound.dng", image::RawDecodeSettings(), &report);
  CHECK(sound.width == 64);
  CHECK(report.decoderWarnings.empty());
  test::writeBytes(dir / "tile.dng", test::dngWithCorruptTile(dng, 5));
  refusedAsDamaged(dir / "tile.dng", "LibRaw", "corrupt raw data");
  const Image accepted = acceptedWith(dir / "tile.dng", "LibRaw: corrupt raw data");
  CHECK(accepted.width == 64);
  CHECK(accepted.pixels != sound.pixels);
  fs::remove_all(dir);
}

TEST_CASE("headers declaring huge sizes are refused before any pixel is allocated") {
  const fs::path dir = test::scratchDir("huge");
  image::writeJpeg(texture(16, 16), dir / "small.jpg", 90);
  const std::string small = test::readBytes(dir / "small.jpg");
  const auto start = std::chrono::steady_clock::now();
  // 900 Mpx: more than Surrogate reads at all.
  test::writeBytes(dir / "absurd.jpg", test::jpegDeclaring(small, 30000, 30000));
  CHECK_THAT(test::inputErrorOf(dir / "absurd.jpg", [&] { image::probeImage(dir / "absurd.jpg"); }),
             Catch::Contains("30000x30000") && Catch::Contains("500 Mpx"));
  test::inputErrorOf(dir / "absurd.jpg", [&] { image::decodeImage(dir / "absurd.jpg", image::RawDecodeSettings()); });
  test::writeBytes(dir / "absurd.png", test::pngDeclaring(40000, 40000));
  CHECK_THAT(test::inputErrorOf(dir / "absurd.png", [&] { image::probeImage(dir / "absurd.png"); }),
             Catch::Contains("40000x40000"));
  // 400 Mpx: a size Surrogate reads, but not where the caller expects 256 pixels.
  test::writeBytes(dir / "large.jpg", test::jpegDeclaring(small, 20000, 20000));
  test::writeBytes(dir / "large.png", test::pngDeclaring(20000, 20000));
  CHECK(image::probeImage(dir / "large.jpg").width == 20000);
  CHECK(image::probeImage(dir / "large.png").width == 20000);
  image::DecodeOptions small256;
  small256.maxPixels = 256;
  for (const char* name : {"large.jpg", "large.png"})
    CHECK_THAT(test::inputErrorOf(dir / name, [&] { image::decodeImage(dir / name, image::RawDecodeSettings(), nullptr, small256); }),
               Catch::Contains("20000x20000"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(seconds < 1.0);
  fs::remove_all(dir);
}

TEST_CASE("decoders running in parallel keep their warnings apart") {
  const fs::path dir = test::scratchDir("parallel-warnings");
  image::writeJpeg(texture(120, 200), dir / "whole.jpg", 90);
  test::writeBytes(dir / "half.jpg", test::halfJpeg(test::readBytes(dir / "whole.jpg")));
  cv::Mat m(64, 48, CV_16UC3);
  cv::randu(m, 0, 65535);
  REQUIRE(cv::imwrite((dir / "whole.tif").string(), m, {cv::IMWRITE_TIFF_COMPRESSION, 1}));
  test::writeBytes(dir / "short.tif", test::tiffWithShortStrip(test::readBytes(dir / "whole.tif")));
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 20; ++i) {
        const bool damaged = (i + t) % 2 == 0;
        const fs::path p = dir / ((t % 2 ? std::string(damaged ? "short" : "whole") + ".tif"
                                         : std::string(damaged ? "half" : "whole") + ".jpg"));
        image::DecodeReport report;
        image::decodeImage(p, image::RawDecodeSettings(), &report, accepting());
        if (report.decoderWarnings.empty() == damaged) ++wrong;
      }
    });
  for (std::thread& t : threads) t.join();
  CHECK(wrong == 0);
  fs::remove_all(dir);
}
