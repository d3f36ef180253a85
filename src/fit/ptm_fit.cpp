// PtmFit: LRGB and RGB .ptm from an ImageStack (the method is described in fit.h).
#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/parallel.h"
#include "core/resident.h"
#include "fit/channel_fit.h"
#include "fit/conditioning.h"
#include "fit/error_kernels.h"
#include "fit/fit.h"
#include "fit/near_fit.h"
#include "fit/pseudo_inverse.h"
#include "fit/quantise.h"
#include "fit/row_kernels.h"
#include "fit/stream_fit.h"

namespace surrogate::fit {

namespace {

std::vector<double> ptmDesign(const std::vector<std::array<double, 3>>& lights) {
  std::vector<double> a;
  for (const auto& l : lights) {
    const auto w = ptmBasis(l[0], l[1]);
    a.insert(a.end(), w.begin(), w.end());
  }
  return a;
}

std::uint8_t chromaByte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
}

// Pixels per block of the LRGB accumulation: its six coefficients, colour sums and sample sums
// (10 doubles a pixel) take 20 KiB, in the first-level cache.
constexpr int kAccumulateBlock = 256;

// LRGB (docs/formats.md, "LRGB: colour and luminance"): weighted mean colour, relative luminance.
class LrgbFitter : public RowFitter {
 public:
  LrgbFitter(const std::vector<double>& p, const std::vector<std::array<double, 3>>& lights,
             formats::PtmFile* out)
      : n_(static_cast<int>(lights.size())), out_(out) {
    // a_k = 255 / S * sum_i P[k][i] * (R_i + G_i + B_i) / 257: fold 255/257 into P.
    for (double v : p) p_.push_back(v * (255.0 / 257.0));
    double total = 0;
    for (const auto& l : lights) {
      const double e = std::asin(std::clamp(l[2], -1.0, 1.0)) / (M_PI / 2) - 0.5;
      weight_.push_back(std::max(0.0, 0.25 - e * e));
      total += weight_.back();
    }
    if (!(total > 0)) {  // every light grazing or overhead: plain mean
      std::fill(weight_.begin(), weight_.end(), 1.0);
      total = n_;
    }
    for (double& w : weight_) w /= total * 257.0;  // mean in 0..255 units
    for (const auto& l : lights) {
      const auto w = ptmBasis(l[0], l[1]);
      basis_.insert(basis_.end(), w.begin(), w.end());
    }
    for (double b : basis_) basisF_.push_back(static_cast<float>(b));
  }

  int ranges() const override { return 6; }
  // Scratch layout (doubles): acc 6w | chroma 3w | mean 3w | sum w | decoded 6w. Pass 2 reuses
  // mean for the colour bytes in planes and sum for the squared errors.
  // The near model's scratch, if any, follows (nearScratch).
  std::size_t scratchDoubles(int width) const override {
    return 19 * std::size_t(width) + (near_ ? near_->scratchDoubles(width) : 0);
  }
  // Lights at known positions: the rows are fitted and measured by `near` (fit/near_fit.h).
  void useNear(const NearModel* near) { near_ = near; }
  void measureErrorsIn(ErrorMeasure errors) { errors_ = errors; }

  // The stored colour bytes are final after pass 1: they are written to the result here.
  void measure(const RowView& row, double* scratch, double* lo, double* hi) const override {
    const int w = row.width;
    fitRow(row, scratch);
    for (int k = 0; k < 6; ++k) rangeOf(scratch + k * w, w, &lo[k], &hi[k]);
    const double* chroma = scratch + 6 * w;
    std::copy(chroma, chroma + 3 * w, out_->rgb.begin() + static_cast<std::size_t>(row.y) * w * 3);
    if (kept_) {
      float* to = kept_ + static_cast<std::size_t>(row.y) * 6 * w;
      for (int j = 0; j < 6 * w; ++j) to[j] = static_cast<float>(scratch[j]);
    }
  }

  std::size_t keptPerRow(int width) const override { return std::size_t(6) * width; }
  void keep(float* rows) override { kept_ = rows; }

  void setRanges(const std::vector<double>& lo, const std::vector<double>& hi) override {
    for (int k = 0; k < 6; ++k) {
      q_[k] = choosePtmQuantisation(lo[k], hi[k]);
      out_->scale[k] = q_[k].scale;
      out_->bias[k] = q_[k].bias;
    }
  }

  void quantise(const RowView& row, double* scratch, double* sqErr) const override {
    const int w = row.width;
    double* acc = scratch;
    double* chroma = scratch + 6 * w;
    double* decoded = scratch + 13 * w;
    const std::size_t base = static_cast<std::size_t>(row.y) * w;
    // Rounded to float, as RtiFit version 2 kept them between the passes (fit.h). Kept, the
    // colour bytes are those pass 1 stored, fitRow's chroma exactly (whole numbers).
    if (kept_) {
      const float* from = kept_ + base * 6;
      for (int j = 0; j < 6 * w; ++j) acc[j] = from[j];
      const std::uint8_t* stored = out_->rgb.data() + base * 3;
      for (int j = 0; j < 3 * w; ++j) chroma[j] = stored[j];
    } else {
      fitRow(row, scratch);
      for (int j = 0; j < 6 * w; ++j) acc[j] = static_cast<float>(acc[j]);
    }
    // The bytes go where fitRow kept the sums (8w bytes), free until the errors are measured.
    auto* bytes = reinterpret_cast<std::uint8_t*>(scratch + 12 * w);
    for (int k = 0; k < 6; ++k) quantisePtm(acc + k * w, w, q_[k], bytes + k * w, decoded + k * w);
    std::uint8_t* dst = out_->coefficients.data() + base * 6;
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 6; ++k) dst[x * 6 + k] = bytes[k * w + x];
    // The colour bytes in three planes (where fitRow kept the means), for the error kernel.
    double* planes = scratch + 9 * w;
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) planes[c * w + x] = chroma[3 * x + c];
    if (!near_ && errors_ == ErrorMeasure::Lanes) return measureSingle(row, planes, decoded, sqErr);
    double* d2 = scratch + 12 * w;  // where fitRow kept the sums
    if (near_) {
      std::fill(sqErr, sqErr + n_, 0.0);
      return near_->errorsLrgb(row, planes, planes + w, planes + 2 * w, decoded, nearScratch(scratch, w), sqErr);
    }
    for (int i = 0; i < n_; ++i) {
      withSamples(row, [&](auto images) {
        squaredErrorsLrgb(planes, planes + w, planes + 2 * w, decoded, w, &basis_[static_cast<std::size_t>(i) * 6],
                          images[i], w, d2);
      });
      double err = 0;
      for (int x = 0; x < w; ++x) err += d2[x];  // in pixel order, whichever kernel ran
      sqErr[i] = err;
    }
  }

 private:
  // Fills acc (6 x w, the luminance coefficients) and chroma (3w, the stored colour bytes as
  // doubles) at the start of `scratch`.
  void fitRow(const RowView& row, double* scratch) const {
    const int w = row.width;
    const std::size_t m = static_cast<std::size_t>(w) * 3;
    double* acc = scratch;
    double* chroma = scratch + 6 * w;
    double* mean = scratch + 9 * w;
    double* sum = scratch + 12 * w;
    std::fill(acc, acc + 6 * w, 0.0);
    std::fill(mean, mean + m, 0.0);
    // Blocks of pixels, each through every photograph: the block's sums stay in the cache
    // (each value still adds the photographs in order, as the whole row at once would).
    if (near_) near_->fitLrgb(row, acc, mean, nearScratch(scratch, w));
    else withSamples(row, [&](auto images) {
      for (int x0 = 0; x0 < w; x0 += kAccumulateBlock)
        accumulateLrgb(images, n_, w, x0, std::min(w, x0 + kAccumulateBlock), p_.data(), weight_.data(), acc, mean,
                       sum);
    });
    for (int x = 0; x < w; ++x) {
      double total = 0;
      for (int c = 0; c < 3; ++c) {
        chroma[3 * x + c] = chromaByte(mean[3 * x + c]);
        total += chroma[3 * x + c];
      }
      for (int k = 0; k < 6; ++k) acc[k * w + x] = total > 0 ? acc[k * w + x] / total : 0.0;
    }
  }

  static double* nearScratch(double* scratch, int w) { return scratch + 19 * std::size_t(w); }

  // The errors in single precision (fit/error_kernels.h), from float copies of the decoded
  // luminance coefficients and of the colour bytes (planes), a row's at a time.
  void measureSingle(const RowView& row, const double* planes, const double* decoded, double* sqErr) const {
    const std::size_t w = static_cast<std::size_t>(row.width);
    thread_local std::vector<float> copies;
    copies.resize(9 * w);
    const float* lum[6];
    const float* colour[3];
    for (int k = 0; k < 9; ++k) {
      const double* from = k < 6 ? decoded + k * w : planes + (k - 6) * w;
      float* to = copies.data() + k * w;
      for (std::size_t x = 0; x < w; ++x) to[x] = static_cast<float>(from[x]);
      (k < 6 ? lum[k] : colour[k - 6]) = to;
    }
    for (int i = 0; i < n_; ++i)
      withSamples(row, [&](auto images) {
        sqErr[i] = lrgbSquaredErrorSum(lum, colour, &basisF_[static_cast<std::size_t>(i) * 6], images[i], w);
      });
  }

  int n_;
  formats::PtmFile* out_;
  std::vector<double> p_, weight_, basis_;
  std::vector<float> basisF_;  // basis_ rounded to float, for the single-precision errors
  PtmQuantisation q_[6];
  const NearModel* near_ = nullptr;
  ErrorMeasure errors_ = ErrorMeasure::Lanes;
  float* kept_ = nullptr;  // pass 1's coefficients, rounded to float (RowFitter::keep)
};

// RGB: one polynomial per channel, coefficients in 0..255 units, scale/bias shared.
class RgbPtmFitter : public ChannelFitter {
 public:
  RgbPtmFitter(std::vector<double> p, std::vector<double> basis, int n, formats::PtmFile* out)
      : ChannelFitter(std::move(p), std::move(basis), n, 6, 1.0), out_(out) {}
  void setRanges(const std::vector<double>& lo, const std::vector<double>& hi) override {
    for (int k = 0; k < 6; ++k) {
      q_[k] = choosePtmQuantisation(lo[k], hi[k]);
      out_->scale[k] = q_[k].scale;
      out_->bias[k] = q_[k].bias;
    }
  }

 protected:
  void quantiseRow(int k, int y, const double* a, std::size_t m, std::uint8_t* bytes,
                   double* decoded) const override {
    quantisePtm(a, m, q_[k], bytes, decoded);
    const std::size_t w = out_->width, plane = static_cast<std::size_t>(out_->height) * w;
    for (int c = 0; c < 3; ++c) {  // one plane of 6 coefficients per channel
      std::uint8_t* dst = out_->coefficients.data() + ((c * plane + y * w) * 6 + k);
      for (std::size_t x = 0; x < w; ++x) dst[x * 6] = bytes[3 * x + c];
    }
  }

 private:
  formats::PtmFile* out_;
  PtmQuantisation q_[6];
};

}  // namespace

formats::PtmFile fitPtm(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                        const FitOptions& options, FitStatistics* stats) {
  return fitPtmSpaced(stack, lights, options, 0, stats);
}

formats::PtmFile fitPtmSpaced(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const FitOptions& options, int spacing, FitStatistics* stats) {
  if (!isPtm(options.basis)) {
    throw Error(ErrorKind::Usage, "--basis", "fit",
                std::string("the basis ") + basisName(options.basis) +
                    " makes an .rti file, not a .ptm");
  }
  const auto l = checkedLights(stack, lights, options.basis);
  const int n = static_cast<int>(l.size());
  const std::vector<double> design = ptmDesign(l);
  // Plain least squares, or damped toward the lower order when the lights condition it poorly.
  const Conditioning conditioning = conditionedInverse(design, n, options.basis);
  const PseudoInverse& pinv = conditioning.inverse;
  // Lights at known positions: per-pixel inverses in the fit's units (as the fitters scale P).
  std::unique_ptr<NearModel> near;
  if (hasNearLights(l, options)) {
    near = std::make_unique<NearModel>(
        stack.width(), stack.height(), l, options.nearLights, options.basis,
        options.basis == Basis::PtmLrgb ? 255.0 / 257.0 : 1.0 / 257.0,
        spacing > 0 ? spacing : nearNodeSpacing(stack.width(), stack.height(), options.nearLights), options.threads, stack.transfer());
    near->measureErrorsIn(options.errors);
  }
  const std::size_t nearBytes = near ? near->bytes() : 0;

  formats::PtmFile ptm;
  ptm.width = stack.width();
  ptm.height = stack.height();
  int passes = 0;
  std::vector<double> sqErr;
  const int threads = effectiveThreads(options.threads);  // to back the model's memory
  if (options.basis == Basis::PtmLrgb) {
    ptm.format = formats::PtmFile::Format::Lrgb;
    resizeResident(ptm.coefficients, ptm.texels() * 6, threads);
    resizeResident(ptm.rgb, ptm.texels() * 3, threads);
    LrgbFitter fitter(pinv.matrix, l, &ptm);
    fitter.useNear(near.get());
    fitter.measureErrorsIn(options.errors);
    sqErr = streamFit(stack, fitter, options, ptm.coefficients.size() + ptm.rgb.size() + nearBytes, &passes);
  } else {
    ptm.format = formats::PtmFile::Format::Rgb;
    resizeResident(ptm.coefficients, ptm.texels() * 18, threads);
    std::vector<double> p = pinv.matrix;
    for (double& v : p) v /= 257.0;  // 16-bit samples -> 0..255 units
    RgbPtmFitter fitter(std::move(p), design, n, &ptm);
    fitter.useNear(near.get());
    fitter.measureErrorsIn(options.errors);
    sqErr = streamFit(stack, fitter, options, ptm.coefficients.size() + nearBytes, &passes);
  }
  const Conditioning& used = near ? near->conditioning() : conditioning;
  finishStatistics(sqErr, ptm.texels(), used.inverse.rank, passes, stats);
  recordConditioning(used, l, stats);
  return ptm;
}

}  // namespace surrogate::fit
