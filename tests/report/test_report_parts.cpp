// The report's building blocks: escaping, coverage analysis, the hemisphere plot and the
// PTM copy for the relighting view.
#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>
#include <vector>

#include "core/base64.h"
#include "core/error.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "report/embed.h"
#include "report/explain.h"
#include "report/hemisphere.h"
#include "report/html.h"
#include "report/relight_section.h"

using namespace surrogate;
using namespace surrogate::report;

namespace {
int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

LightPoint light(double elevation, double azimuth, std::optional<double> rmse = std::nullopt) {
  LightPoint p;
  p.image = "original-captures/IMG_" + std::to_string(static_cast<int>(azimuth)) + ".dng";
  p.elevationDeg = elevation;
  p.azimuthDeg = azimuth;
  p.rmse = rmse;
  return p;
}
}  // namespace

TEST_CASE("scriptString cannot close the script element it is embedded in") {
  const std::string s = scriptString("</script><script>alert(1)</script>\"\\\n\xe2\x80\xa8");
  CHECK(s.find('<') == std::string::npos);
  CHECK(s.find('>') == std::string::npos);
  CHECK(s.find("\\u2028") != std::string::npos);
  CHECK(s.front() == '"');
  CHECK(s.back() == '"');
}

TEST_CASE("coverage: a capture without lights below 20 degrees is missing raking light") {
  std::vector<LightPoint> lights;
  for (int a = 0; a < 360; a += 30) lights.push_back(light(35 + a / 30, a));
  const Coverage c = analyseCoverage(lights);
  CHECK(c.missingRaking);
  CHECK(c.azimuthGaps.empty());
  CHECK(c.lowestElevationDeg == Approx(35));
  REQUIRE_FALSE(c.sentences().empty());
  CHECK_THAT(c.sentences().front(), Catch::Contains("No light below 20"));
}

TEST_CASE("coverage: a well spread capture has no gap") {
  std::vector<LightPoint> lights;
  for (int a = -180; a < 180; a += 45) {
    lights.push_back(light(15, a));
    lights.push_back(light(45, a + 20));
    lights.push_back(light(75, a + 10));
  }
  const Coverage c = analyseCoverage(lights);
  CHECK_FALSE(c.missingRaking);
  CHECK_FALSE(c.missingHigh);
  CHECK(c.azimuthGaps.empty());
  CHECK(c.sentences().empty());
}

TEST_CASE("coverage: an empty half of the azimuth circle is found, across the 180 degree seam") {
  // Lights from -90 to +90 (the right half): nothing from 90 round to 270.
  std::vector<LightPoint> lights;
  for (int a = -90; a <= 90; a += 30) lights.push_back(light(10, a));
  lights.push_back(light(80, 0));
  const Coverage c = analyseCoverage(lights);
  REQUIRE(c.azimuthGaps.size() == 1);
  CHECK(c.azimuthGaps[0].fromDeg == Approx(90));
  CHECK(c.azimuthGaps[0].toDeg == Approx(270));
  CHECK(c.azimuthGaps[0].widthDeg() == Approx(180));
  CHECK_THAT(c.sentences().front(), Catch::Contains("between azimuth 90\u00b0 and 270\u00b0"));
}

TEST_CASE("coverage: one light leaves the whole circle as a gap, no light gives no finding") {
  const Coverage one = analyseCoverage({light(40, 10)});
  REQUIRE(one.azimuthGaps.size() == 1);
  CHECK_THAT(one.sentences()[1], Catch::Contains("360"));
  CHECK(analyseCoverage({}).sentences().empty());
}

TEST_CASE("the hemisphere plot has one point per light, placed by elevation and azimuth") {
  const std::vector<LightPoint> lights = {light(90, 0, 1.0), light(0, 0, 5.0), light(0, 90, 3.0),
                                          light(45, 180)};
  const std::string svg = hemisphereSvg(lights, analyseCoverage(lights));
  CHECK(count(svg, "class=\"light\"") == 4);
  // Centre (180,180), radius 150: zenith at the centre, azimuth 0 to the right, 90 at the top.
  CHECK(svg.find("cx=\"180\" cy=\"180\" r=\"6\"") != std::string::npos);
  CHECK(svg.find("cx=\"330\" cy=\"180\" r=\"6\"") != std::string::npos);
  CHECK(svg.find("cx=\"180\" cy=\"30\" r=\"6\"") != std::string::npos);
  CHECK(svg.find("cx=\"105\" cy=\"180\" r=\"6\"") != std::string::npos);
  // Lowest residual dark, highest yellow, no residual grey.
  CHECK(svg.find("fill=\"" + residualColour(0) + "\" data-image") != std::string::npos);
  CHECK(svg.find("fill=\"" + residualColour(1) + "\" data-image") != std::string::npos);
  CHECK(svg.find("fill=\"#999999\"") != std::string::npos);
}

TEST_CASE("the hemisphere plot escapes image names") {
  LightPoint p = light(30, 0);
  p.image = "a\"><script>alert(1)</script>.jpg";
  const std::string svg = hemisphereSvg({p}, analyseCoverage({p}));
  CHECK(svg.find("<script>") == std::string::npos);
  CHECK(svg.find("&lt;script&gt;") != std::string::npos);
}

namespace {
// A PTM of 4x2 texels, scale 1 and bias 0, its bytes zero.
formats::PtmFile smallPtm(formats::PtmFile::Format format) {
  formats::PtmFile ptm;
  ptm.format = format;
  ptm.width = 4;
  ptm.height = 2;
  ptm.scale = {1, 1, 1, 1, 1, 1};
  ptm.bias = {0, 0, 0, 0, 0, 0};
  const bool lrgb = format == formats::PtmFile::Format::Lrgb;
  ptm.coefficients.resize(ptm.texels() * (lrgb ? 6 : 18));
  ptm.rgb.resize(lrgb ? ptm.texels() * 3 : 0);
  return ptm;
}

// The block averages of a plane of width x height texels, `values` bytes each (texel-
// interleaved), written block by block: every value of a block of step x step texels (fewer at
// the right and bottom edges) summed over its texels, rounded half up.
std::string referenceBlockAverages(const std::uint8_t* plane, int width, int height, int values, int step) {
  std::string out;
  for (int by = 0; by * step < height; ++by)
    for (int bx = 0; bx * step < width; ++bx)
      for (int v = 0; v < values; ++v) {
        int sum = 0, n = 0;
        for (int y = by * step; y < std::min(height, (by + 1) * step); ++y)
          for (int x = bx * step; x < std::min(width, (bx + 1) * step); ++x, ++n) sum += plane[(y * width + x) * values + v];
        out += static_cast<char>((sum + n / 2) / n);
      }
  return out;
}
}  // namespace

TEST_CASE("the relighting copy of a PTM averages each coefficient over blocks") {
  formats::PtmFile ptm = smallPtm(formats::PtmFile::Format::Lrgb);
  for (std::size_t t = 0; t < ptm.texels(); ++t) {
    for (int k = 0; k < 6; ++k) ptm.coefficients[t * 6 + k] = static_cast<std::uint8_t>(t * 10 + k);
    for (int c = 0; c < 3; ++c) ptm.rgb[t * 3 + c] = static_cast<std::uint8_t>(100 + t);
  }
  const std::string full = relightJson(formats::serializePtm(ptm), 0, "t.ptm");
  CHECK_THAT(full, Catch::Contains("\"width\":4,\"height\":2"));
  CHECK_THAT(full, Catch::Contains("\"format\":\"lrgb\""));
  // At full size the copy is the model's own bytes (rows top-first, as set above).
  const std::string coefficients(ptm.coefficients.begin(), ptm.coefficients.end()), rgb(ptm.rgb.begin(), ptm.rgb.end());
  CHECK_THAT(full, Catch::Contains("\"coefficients\":\"" + base64(coefficients) + "\",\"rgb\":\"" + base64(rgb) + "\"}"));
  CHECK(relightJson(ptm, 0) == full);

  // maxSide 2: blocks of 2x2 texels -> 2x1. Block 0 holds texels 0,1,4,5: k=0 mean 25.
  const std::string half = relightJson(formats::serializePtm(ptm), 2, "t.ptm");
  CHECK_THAT(half, Catch::Contains("\"width\":2,\"height\":1"));
  std::string expected;
  for (int block = 0; block < 2; ++block)
    for (int k = 0; k < 6; ++k) expected += static_cast<char>(25 + block * 20 + k);
  CHECK_THAT(half, Catch::Contains("\"coefficients\":\"" + base64(expected) + "\""));
}

TEST_CASE("the relighting copy of an RGB PTM averages each channel's plane over blocks") {
  formats::PtmFile ptm = smallPtm(formats::PtmFile::Format::Rgb);
  // Plane c, texel t, coefficient k at (c * 8 + t) * 6 + k.
  for (std::size_t i = 0; i < ptm.coefficients.size(); ++i) ptm.coefficients[i] = static_cast<std::uint8_t>(i * 5 % 256);
  const std::string json = relightJson(formats::serializePtm(ptm), 2, "t.ptm");
  CHECK_THAT(json, Catch::Contains("\"format\":\"rgb\",\"width\":2,\"height\":1"));
  // Blocks of 2x2 texels, plane after plane.
  std::string expected;
  for (int c = 0; c < 3; ++c) expected += referenceBlockAverages(&ptm.coefficients[c * 8 * 6], 4, 2, 6, 2);
  CHECK_THAT(json, Catch::Contains("\"coefficients\":\"" + base64(expected) + "\""));
  CHECK(relightJson(ptm, 2) == json);
  // At full size, the three planes as they are, and no colour field of LRGB's.
  const std::string full = relightJson(ptm, 4);
  const std::string planes(ptm.coefficients.begin(), ptm.coefficients.end());
  CHECK_THAT(full, Catch::Contains("\"width\":4,\"height\":2"));
  CHECK_THAT(full, Catch::Contains("\"coefficients\":\"" + base64(planes) + "\",\"rgb\":\"\"}"));
  CHECK(relightJson(formats::serializePtm(ptm), 4, "t.ptm") == full);
}

TEST_CASE("embedPicture rejects bytes that are not a picture, and PNG headers claiming huge images") {
  CHECK_FALSE(embedPicture("not an image", 100).has_value());
  CHECK_FALSE(embedPicture("", 100).has_value());
  // A PNG signature and IHDR claiming 100000 x 100000 pixels, and nothing else.
  std::string bomb("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0\x08\x02\0\0\0", 29);
  CHECK_FALSE(embedPicture(bomb, 100).has_value());
}

namespace {
// An HSH model of order 2 (4 terms) whose byte i is byteAt(i).
formats::HshFile orderTwoHsh(int width, int height, std::vector<float> scale, std::vector<float> bias,
                             std::uint8_t (*byteAt)(std::size_t)) {
  formats::HshFile hsh;
  hsh.width = width;
  hsh.height = height;
  hsh.terms = 4;
  hsh.scale = std::move(scale);
  hsh.bias = std::move(bias);
  hsh.coefficients.resize(hsh.texels() * 3 * 4);
  for (std::size_t i = 0; i < hsh.coefficients.size(); ++i) hsh.coefficients[i] = byteAt(i);
  return hsh;
}
}  // namespace

TEST_CASE("the relighting copy of an HSH model keeps the .rti layout and averages over blocks") {
  // ((y*w + x)*3 + c)*terms + k = t*12 + c*4 + k
  const formats::HshFile hsh = orderTwoHsh(4, 2, {1, 2, 3, 4}, {-0.5f, 0, 0.25f, 0},
                                           [](std::size_t i) { return static_cast<std::uint8_t>(i % 200); });
  const std::string bytes = formats::serializeRti(hsh);
  const std::string full = relightJson(bytes, 0, "t.rti");
  CHECK_THAT(full, Catch::Contains("\"model\":\"hsh\",\"basis\":\"hsh2\",\"terms\":4,\"width\":4,\"height\":2"));
  CHECK_THAT(full, Catch::Contains("\"scale\":[1,2,3,4],\"bias\":[-0.5,0,0.25,0]"));
  const std::string original(hsh.coefficients.begin(), hsh.coefficients.end());
  CHECK_THAT(full, Catch::Contains("\"coefficients\":\"" + base64(original) + "\""));

  // maxSide 2: blocks of 2x2 texels -> 2x1; block 0 holds texels 0, 1, 4, 5.
  const std::string half = relightJson(bytes, 2, "t.rti");
  CHECK_THAT(half, Catch::Contains("\"width\":2,\"height\":1,\"originalWidth\":4,\"originalHeight\":2"));
  std::string expected;
  for (int block = 0; block < 2; ++block)
    for (int j = 0; j < 12; ++j) {
      const int t0 = block * 2, texels[4] = {t0, t0 + 1, t0 + 4, t0 + 5};
      int sum = 0;
      for (int t : texels) sum += hsh.coefficients[t * 12 + j];
      expected += static_cast<char>((sum + 2) / 4);
    }
  CHECK_THAT(half, Catch::Contains("\"coefficients\":\"" + base64(expected) + "\""));
  CHECK_THROWS_AS(relightJson("#HSH1.2\n3\n", 0, "broken.rti"), Error);
}

TEST_CASE("the relighting copy averages the partial blocks at the right and bottom edges over their own texels") {
  // 7x4 texels, maxSide 3: blocks of 3x3 -> 3x2 blocks; the last column of blocks is 1 texel
  // wide, the last row 1 texel high.
  const formats::HshFile hsh = orderTwoHsh(7, 4, {1, 1, 1, 1}, {0, 0, 0, 0},
                                           [](std::size_t i) { return static_cast<std::uint8_t>(i * 37 % 256); });
  const std::string json = relightJson(formats::serializeRti(hsh), 3, "t.rti");
  CHECK_THAT(json, Catch::Contains("\"width\":3,\"height\":2"));
  const std::string expected = referenceBlockAverages(hsh.coefficients.data(), 7, 4, 12, 3);
  CHECK_THAT(json, Catch::Contains("\"coefficients\":\"" + base64(expected) + "\""));
  // The same model in memory gives the same copy.
  CHECK(relightJson(hsh, 3) == json);
}

TEST_CASE("the hemisphere plot labels azimuths -180..180 as the light table does, and elevation rings apart") {
  LightPoint p;
  p.image = "IMG_0001.dng";
  p.elevationDeg = 40;
  p.azimuthDeg = -52;
  const std::string svg = hemisphereSvg({p}, analyseCoverage({p}));
  for (const char* label : {">\u2212135\u00b0<", ">\u221290\u00b0<", ">\u221245\u00b0<", ">0\u00b0<", ">45\u00b0<",
                            ">90\u00b0<", ">135\u00b0<", ">180\u00b0<"})
    CHECK_THAT(svg, Catch::Contains(label));
  for (const char* label : {">225\u00b0<", ">270\u00b0<", ">315\u00b0<"}) CHECK(svg.find(label) == std::string::npos);
  // Elevation rings carry "el" and their own class, unlike the azimuth labels.
  CHECK_THAT(svg, Catch::Contains("class=\"axis elevation\""));
  CHECK_THAT(svg, Catch::Contains(">el 30\u00b0<"));
  CHECK_THAT(svg, Catch::Contains("azimuth -52\u00b0"));
}

TEST_CASE("the relighting copy's block side is the smallest whole factor within the side and the bytes") {
  // 1200x800 PTM (LRGB), 9 bytes a texel: 2 gives 600x400 = 2.16 MB, 3 gives 400x267 = 0.96 MB.
  CHECK(relightBlockSide(1200, 800, 9, 1200, 1'500'000) == 3);
  CHECK(relightBlockSide(1200, 800, 9, 1200, 2'160'000) == 2);
  CHECK(relightBlockSide(1200, 800, 9, 1200, 2'159'999) == 3);
  // No limit on bytes: the side alone, as --relight-side.
  CHECK(relightBlockSide(1200, 800, 9, 1200, 0) == 1);
  CHECK(relightBlockSide(2500, 7, 9, 1200, 0) == 3);
  // The side's factor when it is the larger one.
  CHECK(relightBlockSide(2500, 7, 9, 1200, 1'500'000) == 3);
  // A small model stays whole (the test captures' 400x300 HSH of order 2: 1.44 MB).
  CHECK(relightBlockSide(400, 300, 12, 1200, kRelightModelBytes) == 1);
  // A budget below one texel: one block for the whole model, never more.
  CHECK(relightBlockSide(30, 20, 27, 0, 1) == 30);

  // The copy made holds what the factor says: 1200x800 averaged by 3.
  formats::PtmFile ptm;
  ptm.width = 1200;
  ptm.height = 800;
  ptm.coefficients.assign(ptm.texels() * 6, 100);
  ptm.rgb.assign(ptm.texels() * 3, 50);
  const std::string json = relightJson(ptm, 1200, 1'500'000);
  CHECK_THAT(json, Catch::Contains("\"width\":400,\"height\":267,\"originalWidth\":1200,\"originalHeight\":800"));
}

TEST_CASE("the relighting view starts at the normalised mean of the captured lights' directions") {
  // Four lights at 30 degrees elevation around the circle: the mean points at the camera.
  auto start = meanLightDirection({light(30, 0), light(30, 90), light(30, 180), light(30, -90)});
  REQUIRE(start);
  CHECK((*start)[0] == Approx(0).margin(1e-12));
  CHECK((*start)[1] == Approx(0).margin(1e-12));
  CHECK((*start)[2] == Approx(1));
  // Two lights at 20 degrees, azimuth 0 and 90: (cos20, cos20, 2 sin20) normalised, by hand:
  // cos20 = 0.9396926, sin20 = 0.3420201, length sqrt(2 * 0.8830222 + 4 * 0.1169778) = 1.494641;
  // the start is at azimuth 45 and elevation asin(0.6840403 / 1.494641) = 27.236 degrees, inside
  // the captured lights' range, not at 45 degrees above them.
  start = meanLightDirection({light(20, 0), light(20, 90)});
  REQUIRE(start);
  CHECK((*start)[0] == Approx(0.9396926 / 1.494641).epsilon(1e-6));
  CHECK((*start)[1] == Approx((*start)[0]));
  CHECK(std::asin((*start)[2]) * 180 / 3.14159265358979 == Approx(27.236).epsilon(1e-4));
  // No light, or lights that cancel out (grazing from opposite sides): no start.
  CHECK_FALSE(meanLightDirection({}));
  CHECK_FALSE(meanLightDirection({light(0, 0), light(0, 180)}));
}

TEST_CASE("each figure's sentence judges it by the named thresholds") {
  // PSNR: 30 dB and above good, 25 to 30 fair, below 25 worrying; the sentence names the scale.
  CHECK_THAT(explainPsnr(kGoodPsnrDb), Catch::StartsWith("<span class=\"ok explain\">Good"));
  CHECK_THAT(explainPsnr(29.99), Catch::StartsWith("<span class=\"warning explain\">Fair"));
  CHECK_THAT(explainPsnr(kPoorPsnrDb), Catch::StartsWith("<span class=\"warning explain\">"));
  CHECK_THAT(explainPsnr(24.9), Catch::StartsWith("<span class=\"bad explain\">Worrying"));
  CHECK_THAT(explainPsnr(26), Catch::Contains("30 dB and above is good, below 25 dB worrying"));
  // In a word for the summary, the sentence as its tooltip.
  CHECK(judgePsnr(31) == "<span class=\"ok explain\" title=\"Good: the model reproduces the photographs closely; "
                         "higher is closer (30 dB and above is good, below 25 dB worrying).\">good</span>");
  CHECK_THAT(judgePsnr(26), Catch::EndsWith("\">fair</span>"));
  CHECK_THAT(judgePsnr(20), Catch::EndsWith("\">worrying</span>"));
  // RMSE in levels of 255, judged as the PSNR it gives: 20 log10(255 / 8) = 30.07 dB (good),
  // 20 log10(255 / 12.71) = 26.05 dB (fair), 20 log10(255 / 15) = 24.6 dB (worrying).
  CHECK_THAT(explainRmse(8), Catch::StartsWith("<span class=\"ok explain\">"));
  CHECK_THAT(explainRmse(12.71), Catch::Contains("warning explain\">On average a pixel of the model differs from the "
                                                 "photograph by 12.7 of 255 levels (5 %)"));
  CHECK_THAT(explainRmse(15), Catch::StartsWith("<span class=\"bad explain\">"));
  // Rim and moving highlight: 0.8 good, 0.5 the detection's own minimum.
  CHECK_THAT(explainRimConfidence(0.93), Catch::Contains("ok explain"));
  CHECK_THAT(explainRimConfidence(0.6), Catch::Contains("warning explain"));
  CHECK_THAT(explainRimConfidence(0.4), Catch::Contains("bad explain"));
  CHECK_THAT(explainEvidence(0.8), Catch::Contains("ok explain"));
  CHECK_THAT(explainEvidence(0.79), Catch::Contains("warning explain"));
  CHECK_THAT(explainEvidence(0.49), Catch::Contains("bad explain"));
  // Normals: 12704 of 960000 pixels (1.32 %) is usual; above 5 % it is a warning.
  CHECK_THAT(explainNormalFallback(12704, 960000), Catch::Contains("ok explain\">12704 pixels (1.32 %)"));
  CHECK_THAT(explainNormalFallback(12704, 960000), Catch::Contains("Up to 5 % is usual"));
  CHECK_THAT(explainNormalFallback(60000, 960000), Catch::Contains("warning explain\">60000 pixels (6.25 %)"));
}
