// RawDecodeSettings as recorded in the carrier: complete, round-tripping, and strict.
#include <algorithm>

#include "fixtures.h"
#include "image/decode.h"

using namespace surrogate;
using Parameters = std::vector<std::pair<std::string, std::string>>;

namespace {
std::string valueOf(const Parameters& p, const std::string& name) {
  const auto it = std::find_if(p.begin(), p.end(), [&](const auto& kv) { return kv.first == name; });
  return it == p.end() ? "<absent>" : it->second;
}
}  // namespace

TEST_CASE("the defaults are deterministic, linear and unrotated") {
  const Parameters p = image::RawDecodeSettings().toParameters();
  CHECK(valueOf(p, "demosaic") == "AHD");
  CHECK(valueOf(p, "whiteBalance") == "camera");
  CHECK(valueOf(p, "outputColorSpace") == "srgb");
  CHECK(valueOf(p, "highlightMode") == "0");
  CHECK(valueOf(p, "noAutoBright") == "true");
  CHECK(valueOf(p, "adjustMaximumThreshold") == "0");
  CHECK(valueOf(p, "orientation") == "as-stored");
  CHECK(valueOf(p, "gamma") == "linear");
  CHECK(valueOf(p, "outputBits") == "16");
  CHECK(valueOf(p, "halfSize") == "false");
}

TEST_CASE("every setting survives toParameters and fromParameters") {
  image::RawDecodeSettings s;
  s.demosaic = "DCB";
  s.dcbIterations = 2;
  s.dcbEnhance = true;
  s.medianPasses = 3;
  s.fourColorRgb = true;
  s.greenMatching = true;
  s.noiseThreshold = 125.5;
  s.whiteBalance = "none";
  s.outputColorSpace = "raw";
  s.colorMatrix = "embedded";
  s.highlightMode = 2;
  s.blackLevel = 128;
  s.whiteLevel = 4000;
  s.adjustMaximumThreshold = 0.75;
  s.noAutoBright = false;
  s.orientation = "camera";
  s.halfSize = true;
  const Parameters recorded = s.toParameters();
  const image::RawDecodeSettings back = image::RawDecodeSettings::fromParameters(recorded);
  CHECK(back.toParameters() == recorded);
  CHECK(back.noiseThreshold == 125.5);
  CHECK(back.adjustMaximumThreshold == 0.75);
}

TEST_CASE("missing names keep their defaults") {
  const auto s = image::RawDecodeSettings::fromParameters({{"demosaic", "linear"}});
  CHECK(s.demosaic == "linear");
  CHECK(s.whiteBalance == "camera");
  CHECK(s.toParameters().size() == image::RawDecodeSettings().toParameters().size());
}

TEST_CASE("unknown names, unknown values and other fixed values are usage errors") {
  const Parameters bad[] = {
      {{"demosaic", "magic"}},        {{"sharpen", "yes"}},        {{"whiteBalance", "auto"}},
      {{"highlightMode", "12"}},      {{"highlightMode", "2x"}},   {{"halfSize", "1"}},
      {{"gamma", "2.2"}},             {{"outputBits", "8"}},       {{"noiseThreshold", "-1"}},
      {{"orientation", "rotated"}},   {{"adjustMaximumThreshold", "1.5"}},
  };
  for (const Parameters& p : bad) {
    INFO(p[0].first << "=" << p[0].second);
    try {
      image::RawDecodeSettings::fromParameters(p);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK_THAT(e.file(), Catch::Contains(p[0].first));
    }
  }
}
