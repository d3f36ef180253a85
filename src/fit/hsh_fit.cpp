// HshFit: .rti HSH from an ImageStack (the method is described in fit.h).
#include <memory>

#include "core/error.h"
#include "core/parallel.h"
#include "core/resident.h"
#include "fit/channel_fit.h"
#include "fit/conditioning.h"
#include "fit/fit.h"
#include "fit/near_fit.h"
#include "fit/pseudo_inverse.h"
#include "fit/quantise.h"
#include "fit/row_kernels.h"

namespace surrogate::fit {

namespace {

class HshFitter : public ChannelFitter {
 public:
  HshFitter(std::vector<double> p, std::vector<double> basis, int n, int terms,
            formats::HshFile* out)
      : ChannelFitter(std::move(p), std::move(basis), n, terms, 255.0), out_(out), q_(terms) {}
  void setRanges(const std::vector<double>& lo, const std::vector<double>& hi) override {
    for (std::size_t k = 0; k < q_.size(); ++k) {
      q_[k] = chooseHshQuantisation(lo[k], hi[k]);
      out_->scale[k] = q_[k].scale;
      out_->bias[k] = q_[k].bias;
    }
  }

 protected:
  void quantiseRow(int k, int y, const double* a, std::size_t m, std::uint8_t* bytes,
                   double* decoded) const override {
    quantiseHsh(a, m, q_[k], bytes, decoded);
    const std::size_t terms = out_->terms;
    std::uint8_t* dst = out_->coefficients.data() + static_cast<std::size_t>(y) * m * terms + k;
    for (std::size_t j = 0; j < m; ++j) dst[j * terms] = bytes[j];  // sample j = pixel j / 3, channel j % 3
  }

 private:
  formats::HshFile* out_;
  std::vector<HshQuantisation> q_;
};

}  // namespace

formats::HshFile fitHsh(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                        const FitOptions& options, FitStatistics* stats) {
  return fitHshSpaced(stack, lights, options, 0, stats);
}

formats::HshFile fitHshSpaced(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const FitOptions& options, int spacing, FitStatistics* stats) {
  if (isPtm(options.basis)) {
    throw Error(ErrorKind::Usage, "--basis", "fit",
                std::string("the basis ") + basisName(options.basis) +
                    " makes a .ptm file, not an .rti");
  }
  const int terms = basisTerms(options.basis);
  const auto l = checkedLights(stack, lights, options.basis);
  const int n = static_cast<int>(l.size());
  std::vector<double> design(static_cast<std::size_t>(n) * terms);
  for (int i = 0; i < n; ++i) hshBasis(l[i][0], l[i][1], l[i][2], terms, &design[i * terms]);
  // Plain least squares, or damped toward the lower order when the lights condition it poorly.
  const Conditioning conditioning = conditionedInverse(design, n, options.basis);
  const PseudoInverse& pinv = conditioning.inverse;
  // Lights at known positions: per-pixel inverses in the fit's units (as p below).
  std::unique_ptr<NearModel> near;
  if (hasNearLights(l, options)) {
    near = std::make_unique<NearModel>(
        stack.width(), stack.height(), l, options.nearLights, options.basis, 1.0 / 65535.0,
        spacing > 0 ? spacing : nearNodeSpacing(stack.width(), stack.height(), options.nearLights), options.threads, stack.transfer());
    near->measureErrorsIn(options.errors);
  }

  formats::HshFile hsh;
  hsh.width = stack.width();
  hsh.height = stack.height();
  hsh.terms = terms;
  hsh.scale.assign(terms, 0.0f);
  hsh.bias.assign(terms, 0.0f);
  resizeResident(hsh.coefficients, hsh.texels() * 3 * terms, effectiveThreads(options.threads));
  std::vector<double> p = pinv.matrix;
  for (double& v : p) v /= 65535.0;  // 16-bit samples -> 0..1 units
  HshFitter fitter(std::move(p), design, n, terms, &hsh);
  fitter.useNear(near.get());
  fitter.measureErrorsIn(options.errors);
  int passes = 0;
  const std::vector<double> sqErr =
      streamFit(stack, fitter, options, hsh.coefficients.size() + (near ? near->bytes() : 0), &passes);
  const Conditioning& used = near ? near->conditioning() : conditioning;
  finishStatistics(sqErr, hsh.texels(), used.inverse.rank, passes, stats);
  recordConditioning(used, l, stats);
  return hsh;
}

}  // namespace surrogate::fit
