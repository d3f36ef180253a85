// Truncated, empty and fake exports are refused by name before OpenCV sees them (OpenCV would
// decode a truncated JPEG with grey rows and only a warning).
#include <fstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

Image noise(int w, int h) {
  Image im(w, h, 3);
  im.bitsPerSample = 8;
  for (std::size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = static_cast<std::uint16_t>((i * 7919) % 65536);
  return im;
}

fs::path truncatedCopy(const fs::path& whole, const fs::path& to, std::uintmax_t size) {
  fs::copy_file(whole, to, fs::copy_options::overwrite_existing);
  fs::resize_file(to, size);
  return to;
}

std::string decodeError(const fs::path& p) {
  test::inputErrorOf(p, [&] { image::probeImage(p); });
  return test::inputErrorOf(p, [&] { image::decodeImage(p, image::RawDecodeSettings()); });
}

}  // namespace

TEST_CASE("a JPEG cut in half, or missing only its end marker, is refused as truncated") {
  const fs::path dir = test::scratchDir("truncated-jpeg");
  image::writeJpeg(noise(64, 48), dir / "whole.jpg", 90);
  CHECK_NOTHROW(image::decodeImage(dir / "whole.jpg", image::RawDecodeSettings()));
  const auto size = fs::file_size(dir / "whole.jpg");
  CHECK_THAT(decodeError(truncatedCopy(dir / "whole.jpg", dir / "half.jpg", size / 2)),
             Catch::Contains("truncated"));
  CHECK_THAT(decodeError(truncatedCopy(dir / "whole.jpg", dir / "no-eoi.jpg", size - 2)),
             Catch::Contains("truncated"));
  CHECK_THAT(decodeError(truncatedCopy(dir / "whole.jpg", dir / "header-only.jpg", 300)),
             Catch::Contains("truncated"));
  fs::remove_all(dir);
}

TEST_CASE("bytes after a JPEG's end marker (camera padding) are accepted") {
  const fs::path dir = test::scratchDir("padded-jpeg");
  image::writeJpeg(noise(32, 16), dir / "padded.jpg", 90);
  std::ofstream(dir / "padded.jpg", std::ios::binary | std::ios::app) << std::string(100, '\0');
  CHECK(image::probeImage(dir / "padded.jpg").width == 32);
  CHECK(image::decodeImage(dir / "padded.jpg", image::RawDecodeSettings()).height == 16);
  fs::remove_all(dir);
}

TEST_CASE("truncated PNG and TIFF files are refused") {
  const fs::path dir = test::scratchDir("truncated-other");
  cv::Mat m(64, 64, CV_16UC3);
  cv::randu(m, 0, 65535);
  REQUIRE(cv::imwrite((dir / "whole.png").string(), m));
  REQUIRE(cv::imwrite((dir / "whole.tif").string(), m, {cv::IMWRITE_TIFF_COMPRESSION, 1}));
  CHECK_THAT(decodeError(truncatedCopy(dir / "whole.png", dir / "cut.png", fs::file_size(dir / "whole.png") / 2)),
             Catch::Contains("truncated"));
  // Half a TIFF loses either its directory (libtiff cannot read it) or strips the directory
  // points to (data past the end): refused either way.
  const fs::path cutTif = truncatedCopy(dir / "whole.tif", dir / "cut.tif", fs::file_size(dir / "whole.tif") / 2);
  decodeError(cutTif);
  fs::remove_all(dir);
}

TEST_CASE("empty files and text named like an image are refused by name") {
  const fs::path dir = test::scratchDir("fake");
  std::ofstream(dir / "empty.jpg").close();
  CHECK_THAT(decodeError(dir / "empty.jpg"), Catch::Contains("empty"));
  std::ofstream(dir / "text.jpg") << "not an image at all";
  CHECK_THAT(decodeError(dir / "text.jpg"), Catch::Contains("unsupported file format"));
  std::ofstream(dir / "text.cr2") << "not a raw file either";
  decodeError(dir / "text.cr2");
  decodeError(dir / "missing.png");
  fs::remove_all(dir);
}
