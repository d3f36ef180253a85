// hrti::PhaseReference (hrti/phase_correlation.h): the shift's sign is cv::phaseCorrelate's (an
// image whose content moved right and down measures positive), whole and sub-pixel shifts are
// measured, and the response means what cv::phaseCorrelate's does (about 1 for a perfect match,
// near 0 for unrelated images), which RegistrationLimits' kMinResponse is set against.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <catch2/catch.hpp>

#include "hrti/phase_correlation.h"

using surrogate::hrti::PhaseReference;
using surrogate::hrti::PhaseShift;
using surrogate::hrti::PhaseWorkspace;

namespace {

// Smooth random texture, edges everywhere (as a gradient image has).
cv::Mat texture(cv::Size size, int seed) {
  cv::Mat a(size, CV_32F);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(a, cv::RNG::UNIFORM, 0, 1);
  cv::GaussianBlur(a, a, cv::Size(0, 0), 2);
  return a;
}

// `a`'s content moved by (dx, dy), wrapping around (sub-pixel by linear interpolation).
cv::Mat moved(const cv::Mat& a, double dx, double dy) {
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat out;
  cv::warpAffine(a, out, m, a.size(), cv::INTER_LINEAR, cv::BORDER_WRAP);
  return out;
}

}  // namespace

TEST_CASE("phase correlation measures a shift with cv::phaseCorrelate's sign and response") {
  // 300 x 200: a quarter of a 1200 x 800 frame reduced twice; 275 x 250 padded to 288 x 250;
  // 225 x 150 padded to an odd width.
  for (const cv::Size size : {cv::Size(300, 200), cv::Size(275, 250), cv::Size(225, 150)}) {
    INFO(size.width << " x " << size.height);
    const cv::Mat reference = texture(size, size.width);
    cv::Mat window;
    cv::createHanningWindow(window, size, CV_32F);
    const PhaseReference ref(reference, window);
    PhaseWorkspace scratch;

    const PhaseShift same = ref.correlate(reference, scratch);
    CHECK(same.shift.x == Approx(0).margin(1e-3));
    CHECK(same.shift.y == Approx(0).margin(1e-3));
    CHECK(same.response > 0.9);

    for (const cv::Point2d d : {cv::Point2d(3, -2), cv::Point2d(-7, 5), cv::Point2d(1.5, 0.25)}) {
      INFO("moved by " << d.x << ", " << d.y);
      const cv::Mat image = moved(reference, d.x, d.y);
      const PhaseShift s = ref.correlate(image, scratch);
      // The centroid of the peak's neighbourhood pulls a half-pixel shift about 0.35 px outward
      // (cv::phaseCorrelate's as much).
      CHECK(s.shift.x == Approx(d.x).margin(0.4));
      CHECK(s.shift.y == Approx(d.y).margin(0.4));
      double response = 0;
      const cv::Point2d cv = cv::phaseCorrelate(reference.clone(), image.clone(), window, &response);
      // OpenCV 4.6 reads an odd padded width half a pixel off (its quadrant swap).
      const double offset = cv::getOptimalDFTSize(size.width) % 2 ? 0.5 : 0;
      CHECK(s.shift.x == Approx(cv.x - offset).margin(1e-3));
      CHECK(s.shift.y == Approx(cv.y).margin(1e-3));
      if (offset == 0) CHECK(s.response == Approx(response).margin(1e-3));
      CHECK(s.response > 0.3);
    }

    // Unrelated images: a weak peak, as cv::phaseCorrelate's.
    const cv::Mat other = texture(size, 7);
    const PhaseShift unrelated = ref.correlate(other, scratch);
    CHECK(unrelated.response < 0.15);
    double response = 0;
    cv::phaseCorrelate(reference.clone(), other.clone(), window, &response);
    CHECK(unrelated.response == Approx(response).margin(1e-3));
    // A quarter with nothing in it: no NaN.
    const PhaseShift flat = ref.correlate(cv::Mat::zeros(size, CV_32F), scratch);
    CHECK(std::isfinite(flat.shift.x));
    CHECK(std::isfinite(flat.response));
  }
}
