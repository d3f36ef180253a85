// The sRGB transfer function (IEC 61966-2-1) applied to 16-bit linear values.
#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;

TEST_CASE("sRGB encoding gives the standard's values") {
  Image lin(5, 1, 1);
  lin.transfer = Transfer::Linear;
  lin.bitsPerSample = 16;
  // 0; the linear toe (12.92 L below 0.0031308); 18% grey; 50%; white.
  lin.pixels = {0, 100, 11796, 32768, 65535};
  const Image s = image::srgbEncode(lin);
  CHECK(s.transfer == Transfer::Srgb);
  CHECK(s.bitsPerSample == 16);
  CHECK(s.pixels[0] == 0);
  CHECK(s.pixels[1] == 1292);                                // 12.92 * 100, exactly
  CHECK(s.pixels[2] / 65535.0 == Approx(0.4613).margin(0.0005));  // 0.18 -> 0.461
  CHECK(s.pixels[3] / 65535.0 == Approx(0.7354).margin(0.0005));  // 0.5 -> 0.735
  CHECK(s.pixels[4] == 65535);
}

TEST_CASE("sRGB encoding is monotonic over all 65536 values") {
  Image lin(65536, 1, 1);
  lin.transfer = Transfer::Linear;
  for (int i = 0; i < 65536; ++i) lin.pixels[i] = static_cast<std::uint16_t>(i);
  const Image s = image::srgbEncode(lin);
  bool monotonic = true;
  for (int i = 1; i < 65536; ++i) monotonic = monotonic && s.pixels[i] >= s.pixels[i - 1];
  CHECK(monotonic);
}
