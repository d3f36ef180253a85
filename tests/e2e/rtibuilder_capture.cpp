#include "rtibuilder_capture.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace audit_e2e {

// truth/lights.lp as the generator writes it: a count, then "path x y z" per image.
std::vector<TrueLight> trueLights(const fs::path& capture) {
  std::ifstream in(capture / "truth" / "lights.lp");
  int n = 0;
  in >> n;
  std::vector<TrueLight> out(n);
  for (TrueLight& t : out) in >> t.image >> t.light[0] >> t.light[1] >> t.light[2];
  return out;
}

namespace {

std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }

}  // namespace

// The photographs as 16-bit RGB (8-bit values widened *257), decoded with OpenCV.
std::vector<Image> photographs(const fs::path& capture, const std::vector<TrueLight>& lights) {
  std::vector<Image> out;
  for (const TrueLight& t : lights) {
    const cv::Mat bgr = cv::imread((capture / t.image).string(), cv::IMREAD_COLOR);
    REQUIRE(!bgr.empty());
    Image im(bgr.cols, bgr.rows, 3);
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x)
        for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<std::uint16_t>(bgr.at<cv::Vec3b>(y, x)[2 - c] * 257);
    out.push_back(std::move(im));
  }
  return out;
}

namespace {

// The prior PTM: the independent writer's file (tests/audit/prior_rti.h, each plane's range
// widened to include 0), with the constant term a5 written as a writer that clamps every bias
// to 128 would: the scale of the plane's range kept, so that every texel above half of it
// saturates at byte 255.
constexpr int kClampedBias = 128;
std::string clampedBiasPtm(const test::PriorPtm& p) {
  const std::string text = test::ptmText(p, test::BiasRule::WithZero);
  std::vector<std::string> header;
  std::size_t at = 0;
  for (int line = 0; line < 6; ++line) {
    const std::size_t end = text.find('\n', at);
    header.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  std::istringstream scales(header[4]), biases(header[5]);
  std::array<double, 6> scale{};
  std::array<int, 6> bias{};
  for (int k = 0; k < 6; ++k) scales >> scale[k];
  for (int k = 0; k < 6; ++k) biases >> bias[k];
  bias[5] = kClampedBias;
  std::string payload = text.substr(at);
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const std::size_t texel = static_cast<std::size_t>(p.h - 1 - y) * p.w + x;  // bottom row first
      const double byte = std::lround(p.a[y * p.w + x][5] / scale[5] + kClampedBias);
      payload[texel * 6 + 5] = static_cast<char>(static_cast<std::uint8_t>(std::clamp(byte, 0.0, 255.0)));
    }
  std::string out;
  for (int line = 0; line < 5; ++line) out += header[line] + "\n";
  for (int k = 0; k < 6; ++k) out += std::to_string(bias[k]) + (k < 5 ? " " : "\n");
  return out + payload;
}

}  // namespace

// The capture with RTIBuilder's prior work: stela.lp, stela.ptm, stela_log.xml. The PTM's
// constant term is clamped (clampedBiasPtm) unless `clampBias` is false.
fs::path rtibuilderCapture(const std::string& name, bool clampBias) {
  const fs::path capture = e2e::freshDir(name) / "capture";
  const e2e::CommandResult g = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture) +
                                             " --images " + std::to_string(kImages) +
                                             " --width 400 --height 300 --sphere-radius 45 --seed 7 --formats jpeg");
  REQUIRE(g.exitCode == 0);
  const std::vector<TrueLight> truth = trueLights(capture);
  REQUIRE(truth.size() == kImages);
  std::vector<test::Light> prior;
  std::ostringstream lp;
  lp.precision(9);
  lp << kImages << "\r\n";
  for (int i = 0; i < kImages; ++i) {
    prior.push_back(kTilted.count(i) ? test::tilted(truth[i].light, kTiltDegrees) : truth[i].light);
    lp << "jpeg-exports\\" << fileName(truth[i].image) << " " << prior[i][0] << " " << prior[i][1] << " "
       << prior[i][2] << "\r\n";
  }
  lp << "\r\n";
  fs::create_directories(capture / "assembly-files");
  fs::create_directories(capture / "finished-files");
  test::writeText((capture / "assembly-files" / "stela.lp").string(), lp.str());
  test::writeText((capture / "assembly-files" / "stela_log.xml").string(),
                  "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\r\n<RTIBuilderLog version=\"2.0.2\">\r\n"
                  "  <step name=\"PTMFitter\" basis=\"LRGB\"/>\r\n</RTIBuilderLog>\r\n");
  const test::PriorPtm ptm = test::fitPrior(photographs(capture, truth), prior);
  test::writeText((capture / "finished-files" / "stela.ptm").string(),
                  clampBias ? clampedBiasPtm(ptm) : test::ptmText(ptm, test::BiasRule::WithZero));
  return capture;
}

}  // namespace audit_e2e
