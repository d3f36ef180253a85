// readWebLayout on learned layouts Surrogate did not write: one as relight-cli writes it
// (members and number format of relight's RtiBuilder::saveJSON, planes coded as YCbCr), and
// damaged ones, refused naming info.json and saying what is read.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "fit/learned_relightable.h"
#include "publish/learned_layout.h"
#include "publish/web_reader.h"
#include "learned_decoder.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path d = fs::temp_directory_path() / ("learned-reader-" + name + "-" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void writeText(const fs::path& f, const std::string& t) { std::ofstream(f, std::ios::binary | std::ios::trunc) << t; }

// relight's info.json for an rbf model of 12 lights and 9 planes, 20 x 10 texels, as
// RtiBuilder::saveJSON prints it: no space after "type":, 3-decimal lights, sigma and
// pixelSizeInMM, the basis wrapped every 80 numbers, QTextStream's 6 significant digits.
std::string relightInfo(int nplanes, const std::string& colorspace = "mrgb") {
  std::ostringstream s;
  s << "{\n\"width\": 20, \"height\": 10,\n\"format\": \"jpg\",\n\"pixelSizeInMM\": 0.05,\n\"type\":\"rbf\",\n"
    << "\"colorspace\":\"" << colorspace << "\",\n\"sigma\": 0.125,\n\"lights\": [";
  for (int i = 0; i < 12; ++i) {
    const double e = i < 6 ? 0.5 : 1.0, phi = i * M_PI / 3;
    char b[96];
    std::snprintf(b, sizeof b, "%.3f, %.3f, %.3f", std::cos(e) * std::cos(phi), std::cos(e) * std::sin(phi), std::sin(e));
    s << b << (i < 11 ? ", " : "");
  }
  s << "],\n\"nplanes\": " << nplanes << ",\n\"quality\": 95,\n\"basis\": [\n";
  const int count = (nplanes + 1) * 12 * 3;
  for (int i = 0; i < count; ++i) {
    if (i != 0) s << "," << (i % 80 == 0 ? "\n" : "");
    s << (i < 36 ? 110 + (i * 13) % 90 : 97 + (i * 7) % 61);
  }
  s << "],\n\"materials\": [\n{\n \"range\": [";
  for (int p = 0; p < nplanes; ++p) s << (p ? "," : "") << 412.345 + p;
  s << "],\n \"scale\": [";
  for (int p = 0; p < nplanes; ++p) s << (p ? "," : "") << 1.23457;
  s << "],\n \"bias\": [";
  for (int p = 0; p < nplanes; ++p) s << (p ? "," : "") << 0.498039;
  s << "] }\n]\n}\n";
  return s.str();
}

// Three planes as relight's encoder leaves them: ordinary JPEGs (YCbCr), smooth.
void relightPlanes(const fs::path& dir) {
  for (int j = 0; j < 3; ++j) {
    cv::Mat bgr(10, 20, CV_8UC3);
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 20; ++x)
        for (int c = 0; c < 3; ++c)
          bgr.at<cv::Vec3b>(y, x)[2 - c] = static_cast<std::uint8_t>(120 + 40 * std::sin(0.2 * x + j + c) + 3 * y);
    cv::imwrite((dir / ("plane_" + std::to_string(j) + ".jpg")).string(), bgr, {cv::IMWRITE_JPEG_QUALITY, 100});
  }
}

// A copy of a good relight-style layout with info.json replaced by `info`; the Error reading it.
Error refusal(const std::string& info) {
  const fs::path dir = freshDir("bad");
  relightPlanes(dir);
  writeText(dir / "info.json", info);
  try {
    publish::readWebLayout(dir);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == (dir / "info.json").string());
    return e;
  }
  FAIL("the layout was read");
  throw;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a learned layout written as relight-cli writes it is read and drawn as the independent decoder draws it") {
  const fs::path dir = freshDir("relight");
  writeText(dir / "info.json", relightInfo(9));
  relightPlanes(dir);
  const publish::WebLayoutModel web = publish::readWebLayout(dir);
  REQUIRE(web.isLearned);
  const fit::LearnedModel& m = web.learned;
  CHECK(m.kind == fit::LearnedKind::Rbf);
  CHECK(m.width == 20);
  CHECK(m.height == 10);
  CHECK(m.planes == 9);
  REQUIRE(m.lights.size() == 12);
  CHECK(m.lights[1][0] == Approx(0.439).margin(1e-12));  // cos(0.5) cos(60 degrees), 3 decimals
  REQUIRE(m.basis.size() == 360);
  CHECK(m.basis[80] == 97 + (80 * 7) % 61);  // the first number after relight's line break
  CHECK(m.range[8] == Approx(420.345f));
  CHECK(m.scale[0] == 1.23457f);
  CHECK(m.bias[0] == 0.498039f);
  const learnedtest::Layout layout = learnedtest::readLayout(dir);
  const auto model = fit::makeRelightable(web.learned);
  for (const std::array<double, 3>& light : {std::array<double, 3>{0, 0, 1}, {0.6, 0.3, 0.74}, {-0.7, 0.2, 0.69}}) {
    const std::vector<int> decoded = learnedtest::renderAt(layout, light);
    const Image relit = model->render(light, {});
    int worst = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) worst = std::max(worst, std::abs(decoded[i] - relit.pixels[i] / 257));
    CHECK(worst <= 1);
  }
  CHECK(model->basis() == "rbf");
  const publish::WebLayoutSummary s = publish::describeWebLayout(dir / "info.json");
  CHECK(s.basis == "rbf");
  CHECK(s.nodes == 12);
}

TEST_CASE("learned layouts that cannot be drawn are refused naming info.json and saying what is read") {
  const std::string good = relightInfo(9);
  CHECK_THAT(refusal(replaced(good, "\"basis\": [\n110,", "\"basis\": [\n")).message(), Catch::Contains("\"basis\" has 359 values where 360 are needed"));
  CHECK_THAT(refusal(relightInfo(8)).message(), Catch::Contains("\"nplanes\" is 8, not a multiple of 3"));
  CHECK_THAT(refusal(replaced(good, "\"range\": [412.345", "\"range\": [0")).message(), Catch::Contains("range[0] is 0"));
  CHECK_THAT(refusal(replaced(good, "\"basis\": [\n110", "\"basis\": [\n256")).message(), Catch::Contains("whole number 0..255"));
  const Error mycc = refusal(replaced(good, "\"colorspace\":\"mrgb\"", "\"colorspace\":\"mycc\""));
  CHECK_THAT(mycc.message(), Catch::Contains("\"mycc\"") && Catch::Contains("mrgb"));
  CHECK_THAT(refusal(replaced(good, "\"lights\": [", "\"lightz\": [")).message(), Catch::Contains("no \"lights\""));
  const std::string bilinear = replaced(good, "\"type\":\"rbf\"", "\"type\":\"bilinear\"");
  CHECK_THAT(refusal(bilinear).message(), Catch::Contains("without a \"resolution\""));
  // every refusal says what would be read
  CHECK_THAT(refusal(relightInfo(8)).message(), Catch::Contains("Surrogate reads learned layouts"));
}
