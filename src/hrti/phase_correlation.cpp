#include "hrti/phase_correlation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/cpu_features.h"

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
// margins zero). A float product rounds the same however it is computed (cv::multiply's too),
// and this loop saves cv::multiply's dispatch on every quarter.
void windowed(const cv::Mat& image, const cv::Mat& window, cv::Size padded, cv::Mat& out) {
  if (out.size() != padded || out.type() != CV_32F) out = cv::Mat::zeros(padded, CV_32F);
  for (int y = 0; y < image.rows; ++y) {
    const float* in = image.ptr<float>(y);
    float* to = out.ptr<float>(y);
    if (window.empty()) {
      std::copy(in, in + image.cols, to);
      continue;
    }
    const float* w = window.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) to[x] = in[x] * w[x];
  }
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

#if defined(__x86_64__) && defined(__GNUC__)
// Two complex bins of a conj(b), four floats of each (real and imaginary parts side by side), as
// cv::mulSpectrums(.., conjB = true) computes them (in double, rounded to float) and brought to
// unit magnitude as unitComplex does from those floats: the same products, sums, roundings,
// square roots and quotients lane by lane (addsub subtracts in the real lanes and adds in the
// imaginary ones), so the same bits.
__attribute__((target("avx2"))) __m128 unitCrossAvx2(__m128 a, __m128 b) {
  const __m256d guard = _mm256_set1_pd(kGuard);
  const __m256d signIm = _mm256_set_pd(-0.0, 0.0, -0.0, 0.0);  // b's imaginary lanes negated: conj(b)
  const __m256d va = _mm256_cvtps_pd(a);
  const __m256d vb = _mm256_xor_pd(_mm256_cvtps_pd(b), signIm);
  // (aRe bRe, aIm bRe) and (aRe bIm, aIm bIm) -> (aRe bRe - aIm bIm, aIm bRe + aRe bIm)
  const __m256d byRe = _mm256_mul_pd(va, _mm256_movedup_pd(vb));
  const __m256d byIm = _mm256_mul_pd(va, _mm256_permute_pd(vb, 0xF));
  const __m256d c = _mm256_cvtps_pd(_mm256_cvtpd_ps(_mm256_addsub_pd(byRe, _mm256_permute_pd(byIm, 0x5))));
  const __m256d parts = _mm256_mul_pd(c, c);
  const __m256d squared = _mm256_hadd_pd(parts, parts);  // re^2 + im^2 in both lanes of a bin
  const __m256d scale = _mm256_div_pd(_mm256_sqrt_pd(squared), _mm256_add_pd(squared, guard));
  return _mm256_cvtpd_ps(_mm256_mul_pd(c, scale));
}

// `pairs` complex bins of unitCrossAvx2. An odd last bin goes through the same code in the lower
// half: GCC 12 compiles a scalar version of these lines without the rounding to float between the
// product and the normalisation (a last bit off).
__attribute__((target("avx2"))) void unitCrossRowAvx2(const float* a, const float* b, float* out, int pairs) {
  int k = 0;
  for (; k + 4 <= 2 * pairs; k += 4)
    _mm_storeu_ps(out + k, unitCrossAvx2(_mm_loadu_ps(a + k), _mm_loadu_ps(b + k)));
  if (k < 2 * pairs) {
    // The last two floats as the low half of a vector: loadl/storel read and write 8 bytes at
    // any alignment (a double's load and store there, as before, asked for 8-byte alignment).
    const auto two = [](const float* p) {
      return _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
    };
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + k), _mm_castps_si128(unitCrossAvx2(two(a + k), two(b + k))));
  }
}
#endif

// The cross-power spectrum of two packed CCS spectra of one size (cv::dft of a real image at
// least 2 x 2), a conj(b) brought to unit magnitude (kGuard above): cv::mulSpectrums(a, b, out,
// 0, true) then normaliseCcs, which it is without AVX2. With AVX2 in one pass (the two took
// about a fifth of the phase correlations' time), the packed columns' complex bins gathered for
// the rows' code.
void crossPower(const cv::Mat& a, const cv::Mat& b, cv::Mat& out) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (cpuHasAvx2()) {
    const int rows = a.rows, cols = a.cols;
    out.create(rows, cols, CV_32F);
    const bool evenCols = cols % 2 == 0, evenRows = rows % 2 == 0;
    const int columnPairs = (rows - 1) / 2;
    std::vector<float> ca(2 * static_cast<std::size_t>(columnPairs)), cb(ca.size()), co(ca.size());
    for (int c : {0, cols - 1}) {
      if (c == cols - 1 && !evenCols) break;
      for (int k = 0; k < 2 * columnPairs; ++k) {
        ca[static_cast<std::size_t>(k)] = a.at<float>(1 + k, c);
        cb[static_cast<std::size_t>(k)] = b.at<float>(1 + k, c);
      }
      unitCrossRowAvx2(ca.data(), cb.data(), co.data(), columnPairs);
      for (int k = 0; k < 2 * columnPairs; ++k) out.at<float>(1 + k, c) = co[static_cast<std::size_t>(k)];
      // The real bins as cv::mulSpectrums and normaliseCcs make them: a float product, in memory.
      for (int y : {0, rows - 1}) {
        if (y == rows - 1 && !evenRows) break;
        float& v = out.at<float>(y, c);
        v = a.at<float>(y, c) * b.at<float>(y, c);
        unitReal(v);
      }
    }
    const int pairs = ((evenCols ? cols - 1 : cols) - 1) / 2;
    for (int y = 0; y < rows; ++y)
      unitCrossRowAvx2(a.ptr<float>(y) + 1, b.ptr<float>(y) + 1, out.ptr<float>(y) + 1, pairs);
    return;
  }
#endif
  cv::mulSpectrums(a, b, out, 0, /*conjB=*/true);
  normaliseCcs(out);
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
  crossPower(spectrum_, s.spectrum, s.product);
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
