// The strongest cells of a Hough accumulator, one after another: each is the largest value
// and the first cell holding it in row order (as cv::minMaxLoc gives it), and the disc
// around a found cell is cleared before the next is looked for (as cv::circle fills it).
//
// Why not cv::minMaxLoc for each: the sphere search asks for three or four maxima of every
// radius's accumulator (about a hundred radii at 1200x800), and each minMaxLoc read the whole
// accumulator again, 7 % of the CPU time of `surrogate lights` there. Each row's maximum is
// kept instead, and after a clearing only the rows the disc touched are read again.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace surrogate::hrti {

class AccumulatorPeaks {
 public:
  // `acc`: CV_32F, one channel, finite values; written by clearDisc, read throughout.
  explicit AccumulatorPeaks(cv::Mat& acc);

  // The largest value in the accumulator and (into *at) the first cell holding it in row
  // order.
  double strongest(cv::Point* at) const;

  // Sets the filled disc of `radius` around `centre` to 0 (cv::circle, thickness -1).
  void clearDisc(cv::Point centre, int radius);

 private:
  void measureRows(int first, int last);  // rowMax_ of rows [first, last)

  cv::Mat& acc_;
  std::vector<float> rowMax_;
};

}  // namespace surrogate::hrti
