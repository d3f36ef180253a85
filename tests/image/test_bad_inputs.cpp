// Malformed files (proof-of-concept files of past Exiv2 security issues, tests/data/bad-inputs):
// probing and decoding refuse each one with an Input error naming it, never crash or hang.
#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
namespace fs = std::filesystem;

TEST_CASE("every malformed file is refused by name by probe and decode") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::fixture("bad-inputs"))) {
    if (entry.path().extension() == ".md") continue;
    INFO(entry.path().filename().string());
    ++files;
    test::inputErrorOf(entry.path(), [&] { image::probeImage(entry.path()); });
    test::inputErrorOf(entry.path(), [&] { image::decodeImage(entry.path(), image::RawDecodeSettings()); });
  }
  CHECK(files == 7);
}
