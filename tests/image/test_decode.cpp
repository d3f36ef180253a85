#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <thread>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("surrogate-test-image-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void requireErrorNaming(const fs::path& p) {
  try {
    image::decodeImage(p, image::RawDecodeSettings());
    FAIL("decoded " << p);
  } catch (const Error& e) {
    CHECK(e.file() == p.string());
    CHECK(e.exitCode() == 1);
  }
}
}  // namespace

TEST_CASE("a real Canon EOS D30 raw decodes to linear 16-bit RGB, deterministically, from two threads") {
  const fs::path crw = fixture("raw-real/canon-eos-d30.crw");
  image::DecodeReport report;
  const Image a = image::decodeImage(crw, image::RawDecodeSettings(), &report);
  CHECK(a.width > 2000);
  CHECK(a.height > 1300);
  CHECK(a.channels == 3);
  CHECK(a.transfer == Transfer::Linear);
  CHECK(report.decoder.find("LibRaw") == 0);
  CHECK(report.whiteLevel > 0);
  Image b, c;
  std::thread t1([&] { b = image::decodeImage(crw, image::RawDecodeSettings()); });
  std::thread t2([&] { c = image::decodeImage(crw, image::RawDecodeSettings()); });
  t1.join();
  t2.join();
  CHECK(a.pixels == b.pixels);
  CHECK(a.pixels == c.pixels);
  const image::ImageProbe probe = image::probeImage(crw);
  CHECK(probe.kind == image::SourceKind::CameraRaw);
  CHECK(probe.width == a.width);
  CHECK(probe.height == a.height);
}

TEST_CASE("files LibRaw cannot decode are refused by name with the reason") {
  requireErrorNaming(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  requireErrorNaming(fixture("raw-metadata/exiv2-canon-powershot-s40.crw"));
  try {
    image::decodeImage(fixture("raw-metadata/Canon-R6-pruned.CR3"), image::RawDecodeSettings());
  } catch (const Error& e) {
    CHECK_THAT(e.message(), Catch::Contains("LibRaw"));
  }
}

TEST_CASE("every malformed file is refused by name, without a crash") {
  for (const auto& entry : fs::directory_iterator(fixture("bad-inputs"))) {
    if (entry.path().extension() == ".md") continue;
    INFO(entry.path().filename().string());
    requireErrorNaming(entry.path());
    CHECK_THROWS_AS(image::probeImage(entry.path()), Error);
  }
}

TEST_CASE("truncated, empty and fake images are refused by name") {
  const fs::path dir = tempDir("bad");
  Image im(64, 48, 3);
  for (std::size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = static_cast<std::uint16_t>((i * 997) % 65536);
  im.bitsPerSample = 8;
  image::writeJpeg(im, dir / "whole.jpg", 90);
  fs::copy_file(dir / "whole.jpg", dir / "half.jpg");
  fs::resize_file(dir / "half.jpg", fs::file_size(dir / "whole.jpg") / 2);
  requireErrorNaming(dir / "half.jpg");
  CHECK_THROWS_AS(image::probeImage(dir / "half.jpg"), Error);
  std::ofstream(dir / "empty.jpg").close();
  requireErrorNaming(dir / "empty.jpg");
  std::ofstream(dir / "text.jpg") << "not an image at all";
  requireErrorNaming(dir / "text.jpg");
  fs::copy_file(fixture("raw-real/canon-eos-d30.crw"), dir / "cut.crw");
  fs::resize_file(dir / "cut.crw", fs::file_size(dir / "cut.crw") / 3);
  requireErrorNaming(dir / "cut.crw");
  fs::remove_all(dir);
}

TEST_CASE("PNG and 16-bit TIFF decode exactly, in RGB order; JPEG within its loss") {
  const fs::path dir = tempDir("roundtrip");
  cv::Mat bgr16(20, 30, CV_16UC3);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) bgr16.at<cv::Vec3w>(y, x) = cv::Vec3w(100 * x, 1000 * y, 60000);  // B, G, R
  cv::imwrite((dir / "a.tif").string(), bgr16);
  cv::imwrite((dir / "a.png").string(), bgr16);
  for (const char* name : {"a.tif", "a.png"}) {
    const Image im = image::decodeImage(dir / name, image::RawDecodeSettings());
    REQUIRE(im.channels == 3);
    CHECK(im.bitsPerSample == 16);
    CHECK(im.at(5, 7, 0) == 60000);   // red
    CHECK(im.at(5, 7, 1) == 7000);    // green
    CHECK(im.at(5, 7, 2) == 500);     // blue
  }
  cv::Mat red(16, 16, CV_8UC3, cv::Scalar(0, 0, 255));
  cv::imwrite((dir / "red.jpg").string(), red);
  const Image j = image::decodeImage(dir / "red.jpg", image::RawDecodeSettings());
  CHECK(j.bitsPerSample == 8);
  CHECK(j.at(8, 8, 0) > 250 * 257);
  CHECK(j.at(8, 8, 2) < 5 * 257);
  fs::remove_all(dir);
}

TEST_CASE("raw decode settings round-trip through parameters and reject unknown values") {
  image::RawDecodeSettings s;
  s.demosaic = "DCB";
  s.whiteBalance = "daylight";
  const auto back = image::RawDecodeSettings::fromParameters(s.toParameters());
  CHECK(back.demosaic == "DCB");
  CHECK(back.whiteBalance == "daylight");
  CHECK_THROWS_AS(image::RawDecodeSettings::fromParameters({{"demosaic", "magic"}}), Error);
  CHECK_THROWS_AS(image::RawDecodeSettings::fromParameters({{"sharpen", "yes"}}), Error);
}

TEST_CASE("sRGB encoding maps 0, mid-grey and 1 to the standard values") {
  Image lin(3, 1, 1);
  lin.transfer = Transfer::Linear;
  lin.pixels = {0, 11915 /* 0.1818 linear */, 65535};
  const Image s = image::srgbEncode(lin);
  CHECK(s.transfer == Transfer::Srgb);
  CHECK(s.pixels[0] == 0);
  CHECK(s.pixels[2] == 65535);
  CHECK(s.pixels[1] / 65535.0 == Approx(0.4635).margin(0.001));
}
