// The audit's difference pictures (docs/hrti-math.md, "Difference image"): made at the worst
// image and at the photographs asked for, in false colour at a full scale chosen from the data,
// the same bytes at any thread count. Colours are pinned to values worked out by hand from
// ColorBrewer's RdBu stops.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "audit/audit.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "image/write.h"
#include "prior_rti.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kImages = 16;
// The image whose prior light is tilted far off: not the last, and (checked below) not the one
// nearest the viewing axis, where the difference image used to be made.
constexpr int kTilted = 5;
constexpr double kTiltDegrees = 20;

std::string imageName(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "IMG_%04d.jpg", i + 1);
  return name;
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Capture {
  TempDir dir{"audit-difference"};
  std::vector<test::Light> lights = test::auditLights(kImages);
  test::Surface surface{48, 40};
  std::vector<Image> photos = test::lambertPhotos(surface, lights);
  MemoryImageStack stack{photos};
  audit::AuditInputs in;

  Capture() {
    std::vector<test::Light> prior = lights;
    prior[kTilted] = test::tilted(prior[kTilted], kTiltDegrees);
    const fs::path lp = dir.path() / "stela.lp", ptm = dir.path() / "stela.ptm";
    std::ostringstream text;
    text << kImages << "\n" << std::setprecision(17);
    for (int i = 0; i < kImages; ++i)
      text << imageName(i) << " " << prior[i][0] << " " << prior[i][1] << " " << prior[i][2] << "\n";
    test::writeText(lp.string(), text.str());
    test::writeText(ptm.string(), test::ptmText(test::fitPrior(photos, prior), test::BiasRule::WithZero));
    in.priorLightFiles = {lp};
    in.priorModels = {ptm};
    in.photographs.stack = &stack;
    for (int i = 0; i < kImages; ++i) in.photographs.files.push_back(dir.path() / imageName(i));
    in.surrogateLights = lights;
  }

  audit::AuditReport run(const std::string& folder, int threads, std::vector<int> at = {}) {
    audit::AuditOptions options;
    options.differenceFolder = dir.path() / folder;
    fs::create_directories(options.differenceFolder);
    options.threads = threads;
    options.differenceAt = std::move(at);
    return audit::runAudit(in, options);
  }
};

// A grey image of `levels` everywhere (16-bit units, as an 8-bit source widened).
Image grey(int w, int h, int levels) {
  Image im(w, h, 3);
  for (auto& v : im.pixels) v = static_cast<std::uint16_t>(levels * 257);
  return im;
}

void setGrey(Image& im, int x, int y, int levels) {
  for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<std::uint16_t>(levels * 257);
}

// The RGB colour at (x, y) of a PNG read back by OpenCV (which gives BGR).
std::array<int, 3> rgbAt(const cv::Mat& bgr, int x, int y) {
  const cv::Vec3b v = bgr.at<cv::Vec3b>(y, x);
  return {v[2], v[1], v[0]};
}

}  // namespace

TEST_CASE("the audit's difference image is at the image with the lowest PSNR, not the last nor the nearest the axis") {
  Capture cap;
  int nearestAxis = 0;
  for (int i = 1; i < kImages; ++i)
    if (cap.lights[i][2] > cap.lights[nearestAxis][2]) nearestAxis = i;
  REQUIRE(nearestAxis != kTilted);
  REQUIRE(kTilted != kImages - 1);

  const audit::AuditReport report = cap.run("one", 1);
  const audit::ModelCheck& m = report.models.at(0);
  REQUIRE(m.prior.computed);
  REQUIRE(m.prior.images.size() == kImages);
  // The lowest PSNR is the tilted image's, and it is strictly the lowest.
  for (int i = 0; i < kImages; ++i)
    if (i != kTilted) CHECK(m.prior.images[i].psnr > m.prior.images[kTilted].psnr);
  CHECK(m.prior.worstImage == imageName(kTilted));

  REQUIRE(m.differences.size() == 1);
  const audit::DifferenceImage& d = m.differences[0];
  CHECK(d.worst);
  CHECK(d.image == imageName(kTilted));
  CHECK(d.file == cap.dir.path() / "one" / "stela-difference.png");
  // At the prior's (tilted) light of that image.
  const test::Light tilted = test::tilted(cap.lights[kTilted], kTiltDegrees);
  REQUIRE(d.light.has_value());
  for (int k = 0; k < 3; ++k) CHECK((*d.light)[k] == Approx(tilted[k]).margin(1e-9));
  CHECK(d.fullScale >= audit::kMinDifferenceScale);
  CHECK(d.description.find("the photograph " + imageName(kTilted) + " at its prior light") != std::string::npos);
  // Each photograph's prior light is kept with its error, for the report's plot.
  REQUIRE(m.prior.images[kTilted].light.has_value());
  CHECK((*m.prior.images[kTilted].light)[2] == Approx(tilted[2]).margin(1e-9));

  // The picture: the map at the model's size, the legend below, at least 560 pixels wide.
  const cv::Mat png = cv::imread(d.file.string(), cv::IMREAD_UNCHANGED);
  REQUIRE(png.type() == CV_8UC3);
  CHECK(png.cols == 560);
  CHECK(png.rows > 40 + 60);
}

TEST_CASE("the audit makes a difference image at each photograph asked for") {
  Capture cap;
  const audit::AuditReport report = cap.run("named", 1, {0, 9});
  const audit::ModelCheck& m = report.models.at(0);
  REQUIRE(m.differences.size() == 3);
  CHECK(m.differences[0].worst);
  CHECK(m.differences[1].image == "IMG_0001.jpg");
  CHECK(m.differences[2].image == "IMG_0010.jpg");
  CHECK_FALSE(m.differences[1].worst);
  CHECK(m.differences[1].file == cap.dir.path() / "named" / "stela-difference-IMG_0001.png");
  CHECK(m.differences[2].file == cap.dir.path() / "named" / "stela-difference-IMG_0010.png");
  for (const auto& d : m.differences) CHECK(fs::exists(d.file));
  // At their own prior lights (those not tilted are the true ones).
  REQUIRE(m.differences[1].light.has_value());
  for (int k = 0; k < 3; ++k) CHECK((*m.differences[1].light)[k] == Approx(cap.lights[0][k]).margin(1e-9));
  const auto lines = audit::auditLines(report);
  std::string all;
  for (const auto& l : lines) all += l + "\n";
  CHECK(all.find("difference image (worst image): ") != std::string::npos);
  CHECK(all.find("stela-difference-IMG_0010.png") != std::string::npos);
}

TEST_CASE("the audit's difference images are the same bytes with 1 and 2 threads") {
  Capture cap;
  const audit::AuditReport one = cap.run("t1", 1, {2});
  const audit::AuditReport two = cap.run("t2", 2, {2});
  REQUIRE(one.models.at(0).differences.size() == 2);
  REQUIRE(two.models.at(0).differences.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string a = bytesOf(one.models[0].differences[k].file), b = bytesOf(two.models[0].differences[k].file);
    CHECK(!a.empty());
    CHECK(a == b);
    CHECK(one.models[0].differences[k].fullScale == two.models[0].differences[k].fullScale);
  }
}

TEST_CASE("the audit's false colours: neutral at 0, red for a brighter prior, blue for a darker one") {
  // Worked out by hand from RdBu: a difference of d at full scale S lies at 5 (1 + d / S) along
  // the 11 stops, mixed linearly and rounded half up.
  using C = std::array<std::uint8_t, 3>;
  CHECK(audit::differenceColour(0, 16) == C{247, 247, 247});
  CHECK(audit::differenceColour(16, 16) == C{103, 0, 31});
  CHECK(audit::differenceColour(40, 16) == C{103, 0, 31});  // clamped beyond the end
  CHECK(audit::differenceColour(-16, 16) == C{5, 48, 97});
  // +10 of 20: 7.5 along, halfway from (244, 165, 130) to (214, 96, 77).
  CHECK(audit::differenceColour(10, 20) == C{229, 131, 104});
  // +10 of 16: 8.125 along, an eighth from (214, 96, 77) to (178, 24, 43).
  CHECK(audit::differenceColour(10, 16) == C{210, 87, 73});
  // -10 of 16: 1.875 along, seven eighths from (33, 102, 172) to (67, 147, 195).
  CHECK(audit::differenceColour(-10, 16) == C{63, 141, 192});

  // The full scale: the 99th percentile of |d| rounded up to a round number, at least 4.
  CHECK(audit::differenceScale({0, 0, 0}) == 4);
  CHECK(audit::differenceScale(std::vector<std::int32_t>(100, -257 * 13)) == 16);
  CHECK(audit::differenceScale(std::vector<std::int32_t>(100, 257 * 255)) == 255);
}

TEST_CASE("the audit's difference picture read back from its PNG holds the colours worked out by hand") {
  // 20 x 10 pixels: three 16 levels brighter in the prior, one 10 brighter, one 10 darker, the
  // rest equal. |d| at or below 10 for 197 of 200 pixels, 16 for the rest: the 99th percentile
  // (rank 198) is 16, a round number already.
  const Image photo = grey(20, 10, 100);
  Image prior = photo;
  setGrey(prior, 1, 1, 116);
  setGrey(prior, 2, 1, 116);
  setGrey(prior, 3, 1, 116);
  setGrey(prior, 5, 5, 110);
  setGrey(prior, 6, 5, 90);
  const audit::DifferencePicture picture =
      audit::differencePicture(prior, photo, "prior minus photograph IMG_0003.jpg, light (0.100, 0.200, 0.975)");
  CHECK(picture.fullScale == 16);
  TempDir dir("audit-difference-colours");
  const fs::path file = dir.path() / "difference.png";
  image::writePng(picture.picture, file);
  const cv::Mat png = cv::imread(file.string(), cv::IMREAD_COLOR);
  REQUIRE(png.cols == 560);
  CHECK(rgbAt(png, 0, 0) == std::array<int, 3>{247, 247, 247});
  CHECK(rgbAt(png, 1, 1) == std::array<int, 3>{103, 0, 31});
  CHECK(rgbAt(png, 5, 5) == std::array<int, 3>{210, 87, 73});
  CHECK(rgbAt(png, 6, 5) == std::array<int, 3>{63, 141, 192});
  // Beside the narrow map: mid-grey; below it, the legend: the ramp, whose first and last
  // columns are near its ends' colours, and dark text.
  CHECK(rgbAt(png, 100, 5) == std::array<int, 3>{160, 160, 160});
  const std::array<int, 3> left = rgbAt(png, 20, 10 + 18), right = rgbAt(png, 20 + 511, 10 + 18);
  CHECK(left[2] > left[0]);    // blue end
  CHECK(right[0] > right[2]);  // red end
  int dark = 0;
  for (int y = 10 + 30; y < png.rows; ++y)
    for (int x = 0; x < png.cols; ++x) dark += rgbAt(png, x, y)[0] < 100;
  CHECK(dark > 200);  // the ticks' numbers and the caption
}

TEST_CASE("the audit refuses a difference image at a photograph its light file does not name") {
  Capture cap;
  // The light file without IMG_0004.jpg.
  std::ostringstream text;
  text << kImages - 1 << "\n" << std::setprecision(17);
  for (int i = 0; i < kImages; ++i)
    if (i != 3) text << imageName(i) << " " << cap.lights[i][0] << " " << cap.lights[i][1] << " " << cap.lights[i][2] << "\n";
  test::writeText(cap.in.priorLightFiles.at(0).string(), text.str());
  audit::AuditOptions options;
  options.differenceFolder = cap.dir.path();
  options.differenceAt = {3};
  try {
    audit::runAudit(cap.in, options);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK(e.file() == "IMG_0004.jpg");
    CHECK(e.message().find("has no light in stela.lp") != std::string::npos);
  }
  // Without any light file the prior is rendered nowhere, and no difference image is made.
  cap.in.priorLightFiles.clear();
  CHECK(audit::runAudit(cap.in, options).models.at(0).differences.empty());
}
