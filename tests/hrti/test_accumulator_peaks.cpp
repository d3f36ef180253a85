// AccumulatorPeaks (hrti/accumulator_peaks.h) against what it replaces: cv::minMaxLoc for the
// strongest cell, cv::circle to clear its disc, on accumulators with many equal values (the
// first cell in row order must win, as minMaxLoc's) and on views into a larger matrix.
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <random>

#include "hrti/accumulator_peaks.h"

using surrogate::hrti::AccumulatorPeaks;

namespace {

struct Peak {
  double value;
  cv::Point at;
};

// What the sphere search did before: minMaxLoc, then the disc cleared, `count` times.
std::vector<Peak> peaksByMinMaxLoc(cv::Mat acc, int count, int radius) {
  std::vector<Peak> out;
  for (int i = 0; i < count; ++i) {
    Peak p{};
    cv::minMaxLoc(acc, nullptr, &p.value, nullptr, &p.at);
    out.push_back(p);
    cv::circle(acc, p.at, radius, cv::Scalar(0), -1);
  }
  return out;
}

std::vector<Peak> peaksByRows(cv::Mat& acc, int count, int radius) {
  AccumulatorPeaks peaks(acc);
  std::vector<Peak> out;
  for (int i = 0; i < count; ++i) {
    Peak p{};
    p.value = peaks.strongest(&p.at);
    out.push_back(p);
    peaks.clearDisc(p.at, radius);
  }
  return out;
}

void requireSame(const std::vector<Peak>& a, const std::vector<Peak>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].value == b[i].value);
    CHECK(a[i].at == b[i].at);
  }
}

}  // namespace

TEST_CASE("AccumulatorPeaks finds the cells minMaxLoc finds, the first in row order among equals") {
  std::mt19937 rng(19);
  for (int trial = 0; trial < 300; ++trial) {
    const int w = 1 + static_cast<int>(rng() % 90), h = 1 + static_cast<int>(rng() % 70);
    const int radius = 2 + static_cast<int>(rng() % 12);
    cv::Mat acc(h, w, CV_32F);
    // Few distinct values, so that the largest is held by many cells.
    const int levels = 1 + static_cast<int>(rng() % 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) acc.at<float>(y, x) = static_cast<float>(rng() % (levels + 1));
    const std::vector<Peak> expected = peaksByMinMaxLoc(acc.clone(), 5, radius);
    cv::Mat mine = acc.clone();
    INFO("trial " << trial << ", " << w << "x" << h << ", radius " << radius);
    requireSame(peaksByRows(mine, 5, radius), expected);
  }
}

TEST_CASE("AccumulatorPeaks works on a view into a larger matrix and clears only the disc") {
  cv::Mat whole(60, 80, CV_32F);
  cv::randu(whole, 0.0, 1.0);
  cv::GaussianBlur(whole, whole, cv::Size(5, 5), 1.0);  // smooth, as the sphere search's
  cv::Mat view = whole(cv::Rect(7, 5, 50, 40));
  const cv::Mat before = whole.clone();
  const std::vector<Peak> expected = peaksByMinMaxLoc(view.clone(), 4, 6);
  requireSame(peaksByRows(view, 4, 6), expected);
  // Outside the view nothing changed.
  cv::Mat outside = cv::Mat::ones(whole.size(), CV_8U);
  outside(cv::Rect(7, 5, 50, 40)).setTo(0);
  CHECK(cv::norm(whole, before, cv::NORM_INF, outside) == 0);
}

TEST_CASE("AccumulatorPeaks reports zero once everything is cleared") {
  cv::Mat acc = cv::Mat::zeros(10, 10, CV_32F);
  acc.at<float>(3, 4) = 2.5f;
  AccumulatorPeaks peaks(acc);
  cv::Point at;
  CHECK(peaks.strongest(&at) == 2.5);
  CHECK(at == cv::Point(4, 3));
  peaks.clearDisc(at, 2);
  CHECK(peaks.strongest(&at) == 0);
  CHECK(at == cv::Point(0, 0));  // the first of the equal zeros, as minMaxLoc
}
