#include "hrti/phase_correlation.h"

#include <cmath>

namespace surrogate::hrti {

namespace {

constexpr int kCentroidRadius = 2;  // the 5 x 5 neighbourhood of the peak
// The cross-power spectrum P is divided by |P| + kGuard / |P|, i.e. scaled by |P| / (|P|^2 +
// kGuard): where |P| is far above sqrt(kGuard) (3.5e-4) this is P / |P|, a zero magnitude stays
// 0, and magnitudes at the level of float round-off (the highest frequencies of a smooth image,
// which a 0..1 gradient image's windowed spectrum leaves near 1e-6) are kept near 0 instead of
// being raised to unit weight, where they bury the peak in noise. cv::phaseCorrelate weighs
// them the same way, and RegistrationLimits' responses were set against it.
constexpr double kGuard = 1.1920929e-07;  // FLT_EPSILON, in units of |P|^2

// `image` (its size) times the window, into the top left of `padded` (its right and bottom
// margins zero).
void windowed(const cv::Mat& image, const cv::Mat& window, cv::Size padded, cv::Mat& out) {
  if (out.size() != padded || out.type() != CV_32F) out = cv::Mat::zeros(padded, CV_32F);
  cv::Mat inner = out(cv::Rect(0, 0, image.cols, image.rows));
  if (window.empty())
    image.copyTo(inner);
  else
    cv::multiply(image, window, inner);
}

void unitReal(float& v) {
  const double squared = double(v) * v;
  v = static_cast<float>(v * std::sqrt(squared) / (squared + kGuard));
}

void unitComplex(float& re, float& im) {
  const double squared = double(re) * re + double(im) * im;
  const double scale = std::sqrt(squared) / (squared + kGuard);
  re = static_cast<float>(re * scale);
  im = static_cast<float>(im * scale);
}

// Every value of a packed CCS spectrum (cv::dft of a real image at least 2 x 2) brought to unit
// magnitude (kGuard above). Columns 0 and, for an even width, the last hold the spectrum's
// columns 0 and N/2 packed down the column: a real value in row 0 (and, for an even height, in
// the last row), real and imaginary parts in rows (1, 2), (3, 4), ...; the columns between hold
// real and imaginary parts side by side.
void normaliseCcs(cv::Mat& spectrum) {
  const int rows = spectrum.rows, cols = spectrum.cols;
  const bool evenCols = cols % 2 == 0, evenRows = rows % 2 == 0;
  for (int c : {0, cols - 1}) {
    if (c == cols - 1 && !evenCols) break;
    unitReal(spectrum.at<float>(0, c));
    for (int y = 1; y + 1 < rows; y += 2) unitComplex(spectrum.at<float>(y, c), spectrum.at<float>(y + 1, c));
    if (evenRows) unitReal(spectrum.at<float>(rows - 1, c));
  }
  const int pairsEnd = evenCols ? cols - 1 : cols;
  for (int y = 0; y < rows; ++y) {
    float* row = spectrum.ptr<float>(y);
    for (int x = 1; x + 1 < pairsEnd; x += 2) unitComplex(row[x], row[x + 1]);
  }
}

// Index i of an n-long circular axis as a signed offset in [-n/2, n/2).
int signedIndex(int i, int n) { return i < n / 2 ? i : i - n; }

}  // namespace

PhaseReference::PhaseReference(const cv::Mat& reference, const cv::Mat& window) : window_(window) {
  CV_Assert(reference.type() == CV_32F && reference.rows >= 2 && reference.cols >= 2);
  CV_Assert(window.empty() || (window.type() == CV_32F && window.size() == reference.size()));
  padded_ = cv::Size(cv::getOptimalDFTSize(reference.cols), cv::getOptimalDFTSize(reference.rows));
  cv::Mat padded;
  windowed(reference, window_, padded_, padded);
  cv::dft(padded, spectrum_, 0, reference.rows);
}

PhaseShift PhaseReference::correlate(const cv::Mat& image, PhaseWorkspace& s) const {
  CV_Assert(image.type() == CV_32F && image.cols <= padded_.width && image.rows <= padded_.height);
  windowed(image, window_, padded_, s.padded);
  // The rows below the image are zero: the DFT skips them in its first pass.
  cv::dft(s.padded, s.spectrum, 0, image.rows);
  cv::mulSpectrums(spectrum_, s.spectrum, s.product, 0, /*conjB=*/true);
  normaliseCcs(s.product);
  cv::idft(s.product, s.surface, cv::DFT_REAL_OUTPUT);

  cv::Point peak;
  cv::minMaxLoc(s.surface, nullptr, nullptr, nullptr, &peak);
  const int rows = s.surface.rows, cols = s.surface.cols;
  double sum = 0, sumX = 0, sumY = 0;
  for (int dy = -kCentroidRadius; dy <= kCentroidRadius; ++dy) {
    const float* row = s.surface.ptr<float>(((peak.y + dy) % rows + rows) % rows);
    for (int dx = -kCentroidRadius; dx <= kCentroidRadius; ++dx) {
      const double v = row[((peak.x + dx) % cols + cols) % cols];
      sum += v;
      sumX += v * dx;
      sumY += v * dy;
    }
  }
  PhaseShift out;
  out.response = sum / (double(rows) * cols);
  // The surface peaks at minus the shift (R carries the image's conjugate).
  const double offsetX = sum != 0 ? sumX / sum : 0, offsetY = sum != 0 ? sumY / sum : 0;
  out.shift = {-(signedIndex(peak.x, cols) + offsetX), -(signedIndex(peak.y, rows) + offsetY)};
  return out;
}

}  // namespace surrogate::hrti
