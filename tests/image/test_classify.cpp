// What kind of file an image is: by content first, extension second.
#include <fstream>

#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
using surrogate::test::fixture;
namespace fs = std::filesystem;

namespace {
void writeBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}
}  // namespace

TEST_CASE("raw extensions are recognised whatever their case") {
  CHECK(image::isCameraRawExtension("a/IMG_0001.CR2"));
  CHECK(image::isCameraRawExtension("x.nef"));
  CHECK(image::isCameraRawExtension("x.Dng"));
  CHECK(image::isCameraRawExtension("x.cr3"));
  CHECK_FALSE(image::isCameraRawExtension("x.jpg"));
  CHECK_FALSE(image::isCameraRawExtension("x.tif"));
  CHECK_FALSE(image::isCameraRawExtension("dng"));
}

TEST_CASE("real camera files are classified by their content") {
  CHECK(image::classifyImageFile(fixture("raw-real/canon-eos-d30.crw")) == image::SourceKind::CameraRaw);
  CHECK(image::classifyImageFile(fixture("raw-metadata/Canon-R6-pruned.CR3")) == image::SourceKind::CameraRaw);
  CHECK(image::classifyImageFile(fixture("raw-metadata/IMG_1361.dng")) == image::SourceKind::CameraRaw);
  CHECK(image::classifyImageFile(fixture("raw-metadata/DSC_3079.jpg")) == image::SourceKind::Jpeg);
}

TEST_CASE("content wins over a misleading extension") {
  const fs::path dir = test::scratchDir("classify");
  // A DNG renamed .tif is still a raw mosaic (its DNGVersion tag says so).
  fs::copy_file(fixture("raw-metadata/IMG_1361.dng"), dir / "renamed.tif");
  CHECK(image::classifyImageFile(dir / "renamed.tif") == image::SourceKind::CameraRaw);
  // A CRW without an extension is recognised by its CIFF signature.
  fs::copy_file(fixture("raw-real/canon-eos-d30.crw"), dir / "no-extension");
  CHECK(image::classifyImageFile(dir / "no-extension") == image::SourceKind::CameraRaw);
  writeBytes(dir / "really-a-png.jpg", std::string("\x89PNG\r\n\x1A\n", 8) + std::string(40, '\0'));
  CHECK(image::classifyImageFile(dir / "really-a-png.jpg") == image::SourceKind::Png);
  writeBytes(dir / "plain.tif", std::string("II*\0", 4) + std::string(40, '\0'));
  CHECK(image::classifyImageFile(dir / "plain.tif") == image::SourceKind::Tiff);
  fs::remove_all(dir);
}

TEST_CASE("missing, empty and non-image files are refused by name") {
  const fs::path dir = test::scratchDir("classify-bad");
  const fs::path missing = dir / "missing.jpg";
  CHECK_THAT(test::inputErrorOf(missing, [&] { image::classifyImageFile(missing); }),
             Catch::Contains("does not exist"));
  writeBytes(dir / "empty.jpg", "");
  CHECK_THAT(test::inputErrorOf(dir / "empty.jpg", [&] { image::classifyImageFile(dir / "empty.jpg"); }),
             Catch::Contains("empty"));
  writeBytes(dir / "text.jpg", "not an image at all");
  CHECK_THAT(test::inputErrorOf(dir / "text.jpg", [&] { image::classifyImageFile(dir / "text.jpg"); }),
             Catch::Contains("unsupported file format"));
  CHECK_THAT(test::inputErrorOf(dir, [&] { image::classifyImageFile(dir); }),
             Catch::Contains("not a regular file"));
  fs::remove_all(dir);
}
