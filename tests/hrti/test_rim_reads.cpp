// refineRim reads only the tiles of the median near the ring its profiles sample (hrti/rim_fit.h,
// rimReads): the refined circles keep the bits of a refinement that reads each pass's whole
// window, on a generated capture's upper quartile (texture and a sphere's highlights inside the
// circles) and on real photographs' (tests/data/real-rti/SOURCE.md), for circles of every size,
// margins wider than the radius, and circles cut by the frame's edge; and the parts read cover
// every pixel within the profiles' reach of the ring, and leave out the inside of a large circle.
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/stack.h"
#include "generator/capture_generator.h"
#include "generator/scene.h"
#include "hrti/rim_fit.h"
#include "hrti/sphere_detection.h"
#include "hrti/stack_median.h"

using namespace surrogate;
using namespace surrogate::hrti;

namespace {

// The upper quartile, as sphere detection's rim takes it.
constexpr double kQuartile = 0.75;

MemoryImageStack generatedStack() {
  generator::GeneratorOptions o;
  o.images = 12;
  o.width = 480;
  o.height = 360;
  o.spheres = 1;
  o.sphereRadius = 90;
  o.seed = 7;
  o.strongTexture = true;
  const generator::CaptureTruth t = generator::planCapture(o);
  const generator::Scene scene(o, t);
  std::vector<Image> lum;
  for (int i = 0; i < o.images; ++i) lum.push_back(luminance(generator::renderShot(scene, o, t, i)));
  return MemoryImageStack(std::move(lum));
}

// A real set's photographs as 16-bit luminance (the mean of the channels).
MemoryImageStack realStack(const std::string& set) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SURROGATE_SOURCE_DIR) /
                                                           "tests/data/real-rti" / set))
    for (const char* image : {".png", ".jpg", ".JPG"})
      if (e.path().extension() == image) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Image> lum;
  for (const auto& f : files) {
    const cv::Mat bgr = cv::imread(f.string(), cv::IMREAD_COLOR);
    REQUIRE(!bgr.empty());
    Image im(bgr.cols, bgr.rows, 1);
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x) {
        const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
        im.pixels[std::size_t(y) * bgr.cols + x] = static_cast<std::uint16_t>((p[0] + p[1] + p[2]) * 257 / 3);
      }
    lum.push_back(im);
  }
  REQUIRE(lum.size() >= 4);
  return MemoryImageStack(std::move(lum));
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Random circles over the frame (and past its edges), every size up to the frame's, each refined
// from a fresh median reading only the ring, and from one reading whole windows. Returns how many
// circles were refined to a fitted circle (confidence above 0).
int compareRefinements(const ImageStack& stack, unsigned seed, int trials) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int w = stack.width(), h = stack.height();
  int fitted = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const double r = 8 + unit(rng) * 0.6 * std::min(w, h);
    const double cx = -0.2 * r + unit(rng) * (w + 0.4 * r), cy = -0.2 * r + unit(rng) * (h + 0.4 * r);
    const double margin = trial % 5 == 0 ? 1.2 * r : 4 + unit(rng) * 0.3 * r;
    const bool ofVisible = trial % 2 == 1;
    // Each from its own median: the ring-only refinement meets tiles never computed.
    const StackMedian ring(stack, 160, 2, StackMedian::kCoarseBudget, kQuartile);
    const StackMedian whole(stack, 160, 2, StackMedian::kCoarseBudget, kQuartile);
    ring.prepare(rimReads(ring, cx, cy, r, margin));
    const DetectedSphere a = refineRim(ring, cx, cy, r, margin, ofVisible);
    const DetectedSphere b = hrti::detail::refineRimWholeWindow(whole, cx, cy, r, margin, ofVisible);
    INFO("circle " << cx << ", " << cy << ", " << r << " margin " << margin);
    CHECK(sameBits(a.cx, b.cx));
    CHECK(sameBits(a.cy, b.cy));
    CHECK(sameBits(a.r, b.r));
    CHECK(sameBits(a.confidence, b.confidence));
    CHECK(sameBits(a.centreSigmaPx, b.centreSigmaPx));
    CHECK(sameBits(a.radiusSigmaPx, b.radiusSigmaPx));
    fitted += a.confidence > 0;
  }
  return fitted;
}

}  // namespace

TEST_CASE("rim reads: the ring's tiles give the whole windows' circles, on a generated capture") {
  const MemoryImageStack stack = generatedStack();
  CHECK(compareRefinements(stack, 59, 60) > 20);
}

TEST_CASE("rim reads: the ring's tiles give the whole windows' circles, on real photographs") {
  for (const char* set : {"chrome", "lightprobe-1"}) {
    INFO(set);
    const MemoryImageStack stack = realStack(set);
    CHECK(compareRefinements(stack, 61, 30) > 10);
  }
}

TEST_CASE("rim reads: every pixel within the profiles' reach of the ring, not the inside of a large circle") {
  const MemoryImageStack stack(std::vector<Image>(3, Image(1200, 800, 1)));
  const StackMedian median(stack, 160, 1);
  // The profiles' samples reach 6 pixels along each axis (interpolation, Sobel, blur).
  constexpr double kReach = 6 * M_SQRT2;
  struct Circle {
    double cx, cy, r, margin;
  };
  for (const Circle& c : {Circle{600.3, 400.7, 384, 28}, Circle{100.5, 700.2, 150, 160}, Circle{1190, 10, 60, 10},
                          Circle{640, 390, 24, 7}}) {
    const std::vector<Rect> reads = rimReads(median, c.cx, c.cy, c.r, c.margin);
    std::vector<char> covered(std::size_t(1200) * 800, 0);
    long area = 0;
    for (const Rect& q : reads) {
      area += long(q.w) * q.h;
      for (int y = q.y; y < q.y + q.h; ++y)
        for (int x = q.x; x < q.x + q.w; ++x) covered[std::size_t(y) * 1200 + x] = 1;
    }
    // The window read whole: the circle's square with the margin, 4 pixels and the blur's 4.
    const int x0 = std::max(0, static_cast<int>(c.cx - c.r - c.margin - 3) - 4);
    const int y0 = std::max(0, static_cast<int>(c.cy - c.r - c.margin - 3) - 4);
    const int x1 = std::min(1200, static_cast<int>(c.cx + c.r + c.margin + 4) + 4);
    const int y1 = std::min(800, static_cast<int>(c.cy + c.r + c.margin + 4) + 4);
    long missed = 0, outside = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const double d = std::hypot(x - c.cx, y - c.cy);
        missed += d >= std::max(0.0, c.r - c.margin) - kReach && d <= c.r + c.margin + kReach &&
                  !covered[std::size_t(y) * 1200 + x];
      }
    for (std::size_t i = 0; i < covered.size(); ++i) {
      const int x = static_cast<int>(i % 1200), y = static_cast<int>(i / 1200);
      outside += covered[i] && !(x >= x0 && x < x1 && y >= y0 && y < y1);
    }
    INFO("circle " << c.cx << ", " << c.cy << ", " << c.r << " margin " << c.margin);
    CHECK(missed == 0);
    CHECK(outside == 0);
    if (c.r > 300) CHECK(area < 0.6 * double(x1 - x0) * (y1 - y0));
  }
}
