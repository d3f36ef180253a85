// Phase correlation of images against one fixed reference (hrti/frame_registration.h registers
// every frame's quarters to the same median quarters): the translation between two images is
// where the inverse transform of their cross-power spectrum, normalised to unit magnitude,
// peaks.
//
//   1. the reference multiplied by the window (Hann), zero-padded right and bottom to a size the
//      DFT is fast at (cv::getOptimalDFTSize), and its spectrum (real DFT, packed CCS) kept;
//   2. each image: windowed and padded the same way, one forward DFT, the cross-power spectrum
//      R = F_ref conj(F_image) / |F_ref conj(F_image)| (magnitudes at the level of float
//      round-off, and zero, kept near zero: phase_correlation.cpp, kGuard), one inverse DFT,
//      unscaled: a perfect match peaks at the number of pixels;
//   3. the integer peak, read with the circular wrap (index p stands for the shift -p, taken in
//      (-N/2, N/2]), refined by the weighted centroid of the 5 x 5 neighbourhood of the peak
//      (wrapping around the edges);
//   4. the response: the sum of that neighbourhood over the number of pixels, 1 for a perfect
//      match (it can pass 1 a little: the neighbourhood's side lobes), near 0 for none.
//
// The shift is the image's against the reference, cv::phaseCorrelate(reference, image)'s sign:
// an image whose content is the reference's moved right and down gives a positive x and y. The
// reference's transform is done once instead of at every call. Sizes whose padded width or height
// is odd (a 225 px wide quarter) are read without the half-pixel offset cv::phaseCorrelate
// (OpenCV 4.6) gives them: two equal images measure (0, 0).
//
//   const PhaseReference ref(referenceQuarter, window);
//   PhaseWorkspace scratch;                                      // one per thread
//   const PhaseShift s = ref.correlate(imageQuarter, scratch);  // s.shift, s.response
#pragma once

#include <opencv2/core.hpp>

namespace surrogate::hrti {

struct PhaseShift {
  cv::Point2d shift;      // the image's content against the reference's, pixels (x right, y down)
  double response = 0;    // the peak's share, about 0..1
};

// Buffers of one thread's correlations, reused from call to call.
struct PhaseWorkspace {
  cv::Mat padded, spectrum, product, surface;
};

class PhaseReference {
 public:
  // `reference` and `window` CV_32F of one size, at least 2 x 2; the window may be empty (none).
  PhaseReference(const cv::Mat& reference, const cv::Mat& window);

  // `image` CV_32F of the reference's size (a view into a larger image is fine).
  PhaseShift correlate(const cv::Mat& image, PhaseWorkspace& scratch) const;

 private:
  cv::Mat window_;
  cv::Size padded_;
  cv::Mat spectrum_;  // the windowed, padded reference's, packed CCS
};

}  // namespace surrogate::hrti
