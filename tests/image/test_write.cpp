// PNG, JPEG and TIFF writing: exact round trips, deterministic bytes, no partial files. OpenCV's
// imencode and imread, which wrote and read these files before, are the independent reference.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "damage.h"
#include "fixtures.h"
#include "core/atomic_file.h"
#include "image/decode.h"
#include "image/write.h"
#include "image/write_any.h"

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

TEST_CASE("a PNG whose compressed rows span several IDAT chunks reads back exactly in OpenCV") {
  // Noise hardly compresses: 800 x 600 x 3 16-bit samples make about 2.9 MB of stream, three
  // chunks of at most 1 MiB (src/image/png_encoder.cpp); grey 8-bit makes one.
  const fs::path dir = test::scratchDir("write-idat");
  cv::RNG rng(19);
  for (const int channels : {3, 1}) {
    for (const int bits : {16, 8}) {
      Image im(800, 600, channels);
      im.bitsPerSample = bits;
      for (std::uint16_t& v : im.pixels) v = static_cast<std::uint16_t>(bits == 16 ? rng.uniform(0, 65536) : 257 * rng.uniform(0, 256));
      const fs::path file = dir / ("noise" + std::to_string(channels) + "-" + std::to_string(bits) + ".png");
      image::writePng(im, file);
      const cv::Mat back = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
      REQUIRE(back.rows == 600);
      REQUIRE(back.cols == 800);
      REQUIRE(back.channels() == channels);
      REQUIRE(back.depth() == (bits == 16 ? CV_16U : CV_8U));
      bool same = true;
      for (int y = 0; y < 600; ++y)
        for (int x = 0; x < 800; ++x)
          for (int c = 0; c < channels; ++c) {
            const int oc = channels == 3 ? 2 - c : 0;  // OpenCV reads BGR
            const unsigned expected = bits == 16 ? im.at(x, y, c) : im.at(x, y, c) / 257;
            const unsigned got = bits == 16 ? back.ptr<std::uint16_t>(y)[x * channels + oc]
                                            : back.ptr<std::uint8_t>(y)[x * channels + oc];
            same = same && got == expected;
          }
      CHECK(same);
    }
  }
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

namespace {
// A noisy 8-bit picture (smooth ramps plus a hash), so the encoder's every stage has work.
Image8 noisy(int w, int h, int channels) {
  Image8 im;
  im.width = w;
  im.height = h;
  im.channels = channels;
  im.pixels.resize(std::size_t(w) * h * channels);
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    im.pixels[i] = static_cast<std::uint8_t>((i * 7 + (i / 97) * 13 + ((i * 2654435761u) >> 27)) & 0xff);
  return im;
}

std::string opencvJpeg(const Image8& im, int quality) {
  const cv::Mat m(im.height, im.width, CV_MAKETYPE(CV_8U, im.channels), const_cast<std::uint8_t*>(im.pixels.data()));
  cv::Mat bgr;  // a copy: `im` stays as it is
  if (im.channels == 3) cv::cvtColor(m, bgr, cv::COLOR_RGB2BGR);
  else bgr = m.clone();
  std::vector<unsigned char> out;
  REQUIRE(cv::imencode(".jpg", bgr, out, {cv::IMWRITE_JPEG_QUALITY, quality}));
  return std::string(out.begin(), out.end());
}
}  // namespace

TEST_CASE("encodeJpeg gives the bytes OpenCV's imencode gave, RGB and grey, at several qualities") {
  for (const int channels : {3, 1})
    for (const int quality : {50, 88, 95, 100}) {
      INFO("channels " << channels << ", quality " << quality);
      const Image8 im = noisy(67, 41, channels);  // sizes not multiples of the 16-pixel MCU
      CHECK(image::encodeJpeg(im, quality, "test") == opencvJpeg(im, quality));
    }
  CHECK_THROWS_AS(image::encodeJpeg(noisy(4, 4, 3), 101, "test"), Error);
  CHECK_THROWS_AS(image::encodeJpeg(Image8(), 90, "test"), Error);
}

TEST_CASE("a TIFF round-trips exactly through OpenCV's reader, 8 and 16 bits, RGB and grey") {
  const fs::path dir = test::scratchDir("write-tiff");
  for (const int bits : {8, 16}) {
    const Image im = ramp(bits);
    image::writeTiff(im, dir / "rgb.tif");
    const cv::Mat back = cv::imread((dir / "rgb.tif").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(back.rows == im.height);
    REQUIRE(back.cols == im.width);
    REQUIRE(back.channels() == 3);
    CHECK(back.depth() == (bits == 8 ? CV_8U : CV_16U));
    int wrong = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const int expected = bits == 8 ? (im.at(x, y, c) + 128) / 257 : im.at(x, y, c);
          const int got = bits == 8 ? back.at<cv::Vec3b>(y, x)[2 - c] : back.at<cv::Vec3w>(y, x)[2 - c];
          wrong += got != expected;
        }
    CHECK(wrong == 0);
  }
  Image grey(5, 3, 1);
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = static_cast<std::uint16_t>(i * 4000);
  image::writeTiff(grey, dir / "grey.tif");
  image::writeTiff(grey, dir / "grey2.tif");
  const cv::Mat g = cv::imread((dir / "grey.tif").string(), cv::IMREAD_UNCHANGED);
  REQUIRE(g.type() == CV_16UC1);
  CHECK(g.at<std::uint16_t>(2, 4) == 14 * 4000);
  CHECK(readFile(dir / "grey.tif", "test") == readFile(dir / "grey2.tif", "test"));  // no time stamp
  // Only the files: no temporary left behind; a folder that does not exist is an error.
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 3);
  CHECK_THROWS_AS(image::writeTiff(grey, dir / "missing" / "x.tif"), Error);
  fs::remove_all(dir);
}

TEST_CASE("decodePicture reads PNG and JPEG bytes as decodeImage reads their files, and refuses the rest") {
  const fs::path dir = test::scratchDir("decode-picture");
  const Image im = ramp(16);
  image::writePng(im, dir / "a.png");
  const std::string png = readFile(dir / "a.png", "test");
  const image::DecodedPixels p =
      image::decodePicture(reinterpret_cast<const std::uint8_t*>(png.data()), png.size(), "a.png", 1000);
  CHECK_FALSE(p.isNarrow());
  CHECK(p.wide.pixels == im.pixels);
  const Image8 rgb = noisy(30, 20, 3);
  const std::string jpeg = image::encodeJpeg(rgb, 90, "test");
  test::writeBytes(dir / "b.jpg", jpeg);
  const image::DecodedPixels j =
      image::decodePicture(reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size(), "b.jpg", 1000);
  REQUIRE(j.isNarrow());
  CHECK(j.widened().pixels == image::decodeImage(dir / "b.jpg", image::RawDecodeSettings()).pixels);
  // Too many pixels for the caller, cut short, or not a picture: Error(Input) naming it.
  test::inputErrorOf("a.png", [&] {
    image::decodePicture(reinterpret_cast<const std::uint8_t*>(png.data()), png.size(), "a.png", 399);
  });
  test::inputErrorOf("b.jpg", [&] {
    image::decodePicture(reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size() / 2, "b.jpg", 1000);
  });
  const std::string text = "GIF89a, or anything else";
  test::inputErrorOf("c", [&] {
    image::decodePicture(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), "c", 1000);
  });
  fs::remove_all(dir);
}
