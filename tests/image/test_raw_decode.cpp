// Camera raw decoding through LibRaw on real camera files: deterministic, thread-safe, and
// clear refusals for what LibRaw 0.20 cannot decode.
#include <thread>

#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
using surrogate::test::fixture;
namespace fs = std::filesystem;

namespace {
const fs::path kD30 = fixture("raw-real/canon-eos-d30.crw");
}  // namespace

TEST_CASE("a real Canon EOS D30 raw decodes to linear 16-bit RGB with its levels reported") {
  image::DecodeReport report;
  const Image im = image::decodeImage(kD30, image::RawDecodeSettings(), &report);
  // LibRaw keeps a few margin pixels around the 2160x1440 that the EXIF declares.
  CHECK(im.width == 2176);
  CHECK(im.height == 1448);
  CHECK(im.channels == 3);
  CHECK(im.bitsPerSample == 16);
  CHECK(im.transfer == Transfer::Linear);
  CHECK(report.decoder == "LibRaw " + image::librawVersion());
  CHECK(report.blackLevel == 127);
  CHECK(report.whiteLevel == 4095);  // 12-bit sensor
  // The level subtracted per channel (R, G, B, G2): LibRaw measures this camera's masked
  // pixels per channel, and its greens and blue sit one level above red.
  CHECK(report.channelBlackLevels == std::vector<int>{127, 128, 128, 128});
  REQUIRE(report.whiteBalanceMultipliers.size() == 4);
  CHECK(report.whiteBalanceMultipliers[0] == Approx(1.0));  // normalised to the smallest
  CHECK(report.whiteBalanceMultipliers[2] > report.whiteBalanceMultipliers[1]);  // blue gain, daylight-ish
  CHECK(report.warnings.empty());
  const image::ImageProbe probe = image::probeImage(kD30);
  CHECK(probe.kind == image::SourceKind::CameraRaw);
  CHECK(probe.width == im.width);
  CHECK(probe.height == im.height);
}

TEST_CASE("decoding the same raw twice, and from two threads at once, is bit-identical") {
  const image::RawDecodeSettings settings;
  const Image first = image::decodeImage(kD30, settings);
  const Image second = image::decodeImage(kD30, settings);
  CHECK(first.pixels == second.pixels);
  Image a, b;
  std::thread ta([&] { a = image::decodeImage(kD30, settings); });
  std::thread tb([&] { b = image::decodeImage(kD30, settings); });
  ta.join();
  tb.join();
  CHECK(a.pixels == first.pixels);
  CHECK(b.pixels == first.pixels);
}

TEST_CASE("the settings change the pixels as they say") {
  image::RawDecodeSettings half;
  half.halfSize = true;
  half.whiteBalance = "none";
  image::DecodeReport report;
  const Image im = image::decodeImage(kD30, half, &report);
  CHECK(im.width == 2176 / 2);
  CHECK(im.height == 1448 / 2);
  for (double m : report.whiteBalanceMultipliers) CHECK(m == Approx(1.0));
}

TEST_CASE("an iPhone DNG pruned of its pixel data is refused as truncated, not decoded black") {
  // LibRaw 0.20 alone decodes this file to 4032x3024 zeros without an error; its tile table
  // points past the end of the 64 KB file.
  const fs::path dng = fixture("raw-metadata/IMG_1361.dng");
  const std::string message = test::inputErrorOf(dng, [&] { image::decodeImage(dng, image::RawDecodeSettings()); });
  CHECK_THAT(message, Catch::Contains("truncated"));
  test::inputErrorOf(dng, [&] { image::probeImage(dng); });
}

TEST_CASE("a Canon CR3 is refused with the LibRaw version it needs") {
  const fs::path cr3 = fixture("raw-metadata/Canon-R6-pruned.CR3");
  const std::string message = test::inputErrorOf(cr3, [&] { image::decodeImage(cr3, image::RawDecodeSettings()); });
  CHECK_THAT(message, Catch::Contains("cannot decode this camera format"));
  CHECK_THAT(message, Catch::Contains("CR3 needs LibRaw >= 0.21"));
  test::inputErrorOf(cr3, [&] { image::probeImage(cr3); });
}

TEST_CASE("a pruned PowerShot S40 CRW is refused as truncated or damaged") {
  const fs::path crw = fixture("raw-metadata/exiv2-canon-powershot-s40.crw");
  CHECK_THAT(test::inputErrorOf(crw, [&] { image::decodeImage(crw, image::RawDecodeSettings()); }),
             Catch::Contains("truncated"));
}

TEST_CASE("a truncated copy of a real raw is refused as truncated") {
  const fs::path dir = test::scratchDir("raw-cut");
  const fs::path cut = dir / "cut.crw";
  fs::copy_file(kD30, cut);
  fs::resize_file(cut, fs::file_size(kD30) / 3);
  CHECK_THAT(test::inputErrorOf(cut, [&] { image::decodeImage(cut, image::RawDecodeSettings()); }),
             Catch::Contains("truncated"));
  fs::remove_all(dir);
}
