// Whether a frame moved against the others (docs/hrti-math.md, "Checks on the lights"): a
// camera knocked or turned on its tripod, a sphere or object bumped between two shots. Every
// pixel of the fit assumes the same point of the object in every frame, and the light's
// direction assumes the sphere's circle of the stack.
//
//   1. every frame reduced by an integer factor f to about kWidth pixels wide (the mean of f
//      pixels of the middle row of each f x f block: reading one row in f keeps it cheap), and
//      the per-pixel median of the reduced frames (the lower of two middle values); the
//      gradient magnitude (Sobel) of each: edges stay where they are when the light moves, the
//      shading does not;
//   2. each quarter of each frame's gradient registered to the median's quarter by phase
//      correlation (hrti/phase_correlation.h, Hann window; the median's spectra computed once):
//      four shifts, each that of the quarter's strongest edges, so applied at the centroid of
//      the median's gradient there;
//   3. one rigid motion (a shift and a turn under kMaxTurn about the frame's centre) fitted to
//      the four shifts by least squares, or to the three that agree best when one does not (a
//      quarter with a moving shadow or nothing in it): accepted when every shift it uses is
//      within kAgreePx reduced pixels of it, or kAgreeShare of the motion, at most kAgreeMaxPx.
//      A quarter whose correlation peaks under kMinResponse is not used, nor quarters whose
//      mean peak is under kMinMeanResponse (three weak peaks can agree by chance). None
//      agreeing, the frame is not measured (not flagged);
//   4. the frame's movement: the largest displacement of that motion at those centroids, in
//      full-resolution pixels.
//
// Measured (reduced pixels): frames that did not move, at most 0.75 on the real light probes and
// the generated captures but one of 36 at 2.8 (a quarter's cast shadow absorbed as a turn), 1.7
// on the chrome ball (f = 1); a probe frame shifted 40 px measures 20 (f = 2), one turned 3
// degrees about the frame's centre 11.8 (24 px; `surrogate lights` on lightprobe-1's frame 5
// turned, as tests/e2e/test_bad_frames_e2e.cpp makes it). Frames whose quarters disagree (cast
// shadows that move with the light) are not measured. The phase correlations take most of the
// time: a 300 x 200 quarter (frames of 1200x800) 1.1 ms on one thread, two DFTs.
//
//   const std::vector<FrameMotion> m = registerFrames(luminance, threads);
//   if (m[i].measured && m[i].largestPx > movedLimitPx(width)) ...   // frame i moved
#pragma once

#include <vector>

#include "core/stack.h"

namespace surrogate::hrti {

struct RegistrationLimits {
  static constexpr int kWidth = 512;        // reduced frames' width
  static constexpr double kAgreePx = 1.0;   // reduced pixels: shifts that agree with one motion,
  static constexpr double kAgreeShare = 0.35;  // or within this share of its largest displacement,
  static constexpr double kAgreeMaxPx = 3.0;    // but never more than this
  static constexpr double kMaxTurn = 0.1;       // radians: a larger turn fitted is no fit
  static constexpr double kMinResponse = 0.05;  // a quarter's phase correlation peak, to be used,
  static constexpr double kMinMeanResponse = 0.1;  // and the mean peak of the quarters fitted
  static constexpr double kMovedPx = 3.5;   // reduced pixels: a frame moved beyond this
};

struct FrameMotion {
  bool measured = false;    // three or four quarters agree on one rigid motion
  double dx = 0, dy = 0;    // the shift, full-resolution pixels (x right, y down)
  double rotationDeg = 0;   // about the frame's centre, clockwise on screen positive
  double largestPx = 0;     // the largest displacement at the quarters' centres, full resolution
};

// Which phase correlation measures the quarters' shifts: Surrogate's own (hrti/phase_correlation.h,
// HighlightDetection version 12 on), or OpenCV's cv::phaseCorrelate, which records made with
// HighlightDetection version 11 and earlier were measured with and are re-executed with.
enum class PhaseCorrelator { Own, OpenCv };

// Every frame of a one-channel stack against the stack's median. Fewer than three frames:
// none measured.
std::vector<FrameMotion> registerFrames(const ImageStack& luminance, int threads,
                                        PhaseCorrelator correlator = PhaseCorrelator::Own);

// The reduction factor registerFrames uses for a frame `width` wide, and the limit in
// full-resolution pixels beyond which a frame moved: kMovedPx reduced pixels.
int registrationFactor(int width);
double movedLimitPx(int width);

}  // namespace surrogate::hrti
