// hrti::registerFrames (hrti/frame_registration.h): a frame moved against the others is measured
// as moved, the others not, and the motions are the same bits whatever the number of threads
// (the reduced frames, the median's quarters and the frames are shared among the workers).
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "hrti/frame_registration.h"

using surrogate::Image;
using surrogate::MemoryImageStack;
using surrogate::hrti::FrameMotion;
using surrogate::hrti::registerFrames;

namespace {

constexpr int kWidth = 1200, kHeight = 800;  // reduced twice (registrationFactor)
constexpr int kFrames = 7, kMovedFrame = 3;
constexpr double kMoveX = 20, kMoveY = -12;  // full-resolution pixels

// A smooth random scene (edges everywhere), each frame lit a little differently (a brightness
// ramp that turns with the frame), frame kMovedFrame shifted by (kMoveX, kMoveY).
MemoryImageStack scene() {
  cv::Mat base(kHeight, kWidth, CV_32F);
  cv::RNG rng(7);
  rng.fill(base, cv::RNG::UNIFORM, 0, 1);
  cv::GaussianBlur(base, base, cv::Size(0, 0), 4);
  cv::normalize(base, base, 0.1, 0.8, cv::NORM_MINMAX);
  std::vector<Image> images;
  for (int i = 0; i < kFrames; ++i) {
    cv::Mat frame = base;
    if (i == kMovedFrame) {  // into a new image: `frame` shares base's pixels
      const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, kMoveX, 0, 1, kMoveY);
      cv::Mat shifted;
      cv::warpAffine(base, shifted, m, base.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
      frame = shifted;
    }
    Image im(kWidth, kHeight, 1);
    const double angle = i * 0.9;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const double light = 0.9 + 0.1 * (std::cos(angle) * x / kWidth + std::sin(angle) * y / kHeight);
        im.at(x, y) = static_cast<std::uint16_t>(std::lround(std::min(1.0, frame.at<float>(y, x) * light) * 65535));
      }
    images.push_back(std::move(im));
  }
  return MemoryImageStack(std::move(images));
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("registerFrames measures the moved frame, and the same bits on 1, 2 and 3 threads") {
  const MemoryImageStack stack = scene();
  const std::vector<FrameMotion> one = registerFrames(stack, 1);
  REQUIRE(one.size() == static_cast<std::size_t>(kFrames));
  const double limit = surrogate::hrti::movedLimitPx(kWidth);
  for (int i = 0; i < kFrames; ++i) {
    INFO("frame " << i);
    REQUIRE(one[i].measured);
    if (i == kMovedFrame) {
      CHECK(one[i].largestPx > limit);
      CHECK(one[i].dx == Approx(kMoveX).margin(2));
      CHECK(one[i].dy == Approx(kMoveY).margin(2));
    } else {
      CHECK(one[i].largestPx < limit);
    }
  }
  for (int threads : {2, 3}) {
    const std::vector<FrameMotion> many = registerFrames(stack, threads);
    REQUIRE(many.size() == one.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      INFO("frame " << i << ", " << threads << " threads");
      CHECK(many[i].measured == one[i].measured);
      CHECK(sameBits(many[i].dx, one[i].dx));
      CHECK(sameBits(many[i].dy, one[i].dy));
      CHECK(sameBits(many[i].rotationDeg, one[i].rotationDeg));
      CHECK(sameBits(many[i].largestPx, one[i].largestPx));
    }
  }
}
