// JPEG, TIFF and PNG through libjpeg, libtiff and libpng: exact values, RGB order, depth kept,
// pixels as stored.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
// OpenCV writes BGR: (B, G, R) = (100x, 1000y, 60000) must read back as R 60000, B 100x.
cv::Mat gradientBgr16() {
  cv::Mat m(20, 30, CV_16UC3);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) m.at<cv::Vec3w>(y, x) = cv::Vec3w(100 * x, 1000 * y, 60000);
  return m;
}
}  // namespace

TEST_CASE("16-bit TIFF and PNG decode exactly, in RGB order") {
  const fs::path dir = test::scratchDir("export16");
  const cv::Mat bgr = gradientBgr16();
  for (const char* name : {"a.tif", "a.png"}) {
    INFO(name);
    REQUIRE(cv::imwrite((dir / name).string(), bgr));
    image::DecodeReport report;
    const Image im = image::decodeImage(dir / name, image::RawDecodeSettings(), &report);
    REQUIRE(im.width == 30);
    REQUIRE(im.height == 20);
    REQUIRE(im.channels == 3);
    CHECK(im.bitsPerSample == 16);
    CHECK(im.transfer == Transfer::Srgb);
    CHECK(report.decoder == (fs::path(name).extension() == ".tif" ? "libtiff " + image::libtiffVersion()
                                                                  : "libpng " + image::libpngVersion()));
    CHECK(report.decoderWarnings.empty());
    CHECK(report.blackLevel == -1);
    bool exact = true;
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 30; ++x)
        exact = exact && im.at(x, y, 0) == 60000 && im.at(x, y, 1) == 1000 * y && im.at(x, y, 2) == 100 * x;
    CHECK(exact);
    const image::ImageProbe probe = image::probeImage(dir / name);
    CHECK(probe.width == 30);
    CHECK(probe.height == 20);
  }
  fs::remove_all(dir);
}

TEST_CASE("8-bit images are widened by 257, grey stays grey, alpha is dropped") {
  const fs::path dir = test::scratchDir("export8");
  cv::Mat grey(4, 5, CV_8UC1);
  for (int i = 0; i < 20; ++i) grey.data[i] = static_cast<uchar>(i * 13);
  REQUIRE(cv::imwrite((dir / "grey.png").string(), grey));
  const Image g = image::decodeImage(dir / "grey.png", image::RawDecodeSettings());
  CHECK(g.channels == 1);
  CHECK(g.bitsPerSample == 8);
  CHECK(g.at(4, 3) == 19 * 13 * 257);
  CHECK(g.at(0, 0) == 0);

  cv::Mat bgra(3, 3, CV_8UC4, cv::Scalar(10, 20, 255, 7));  // B, G, R, A
  REQUIRE(cv::imwrite((dir / "rgba.png").string(), bgra));
  const Image c = image::decodeImage(dir / "rgba.png", image::RawDecodeSettings());
  REQUIRE(c.channels == 3);
  CHECK(c.at(1, 1, 0) == 65535);
  CHECK(c.at(1, 1, 1) == 20 * 257);
  CHECK(c.at(1, 1, 2) == 10 * 257);
  fs::remove_all(dir);
}

TEST_CASE("a pure red JPEG decodes with red high, within JPEG's loss") {
  const fs::path dir = test::scratchDir("export-jpeg");
  REQUIRE(cv::imwrite((dir / "red.jpg").string(), cv::Mat(16, 16, CV_8UC3, cv::Scalar(0, 0, 255))));
  const Image j = image::decodeImage(dir / "red.jpg", image::RawDecodeSettings());
  CHECK(j.bitsPerSample == 8);
  CHECK(j.at(8, 8, 0) > 250 * 257);
  CHECK(j.at(8, 8, 1) < 5 * 257);
  CHECK(j.at(8, 8, 2) < 5 * 257);
  fs::remove_all(dir);
}

TEST_CASE("a camera JPEG keeps its stored pixel layout whatever its orientation tag says") {
  // exiv2-nikon-d70.jpg carries Orientation 6 ("right, top"); its stored image is 150x91.
  const Image im = image::decodeImage(test::fixture("raw-metadata/exiv2-nikon-d70.jpg"), image::RawDecodeSettings());
  CHECK(im.width == 150);
  CHECK(im.height == 91);
  const image::ImageProbe probe = image::probeImage(test::fixture("raw-metadata/DSC_3079.jpg"));
  CHECK(probe.kind == image::SourceKind::Jpeg);
  CHECK(probe.width == 720);
  CHECK(probe.height == 1280);
}
