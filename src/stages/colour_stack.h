// The images the fit reads, colour-corrected: each pixel decoded to linear light, mapped by
// the chart's model (colour/correction_model.h), clipped to 0..1 and encoded back as the
// stack was (sRGB or linear). Computed as rows are read, like the other pre-processed views
// (stack_views.h): no copy of the photographs, the same values at any thread count.
//
//   auto corrected = std::make_shared<ColourStack>(decoded, model);
#pragma once

#include <memory>
#include <vector>

#include "colour/correction_model.h"
#include "core/stack.h"

namespace surrogate::stages {

class ColourStack : public ImageStack {
 public:
  // `inner` must be RGB (3 channels).
  ColourStack(std::shared_ptr<const ImageStack> inner, colour::ColourModel model);
  int size() const override { return inner_->size(); }
  int width() const override { return inner_->width(); }
  int height() const override { return inner_->height(); }
  int channels() const override { return 3; }
  Transfer transfer() const override { return inner_->transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;

 private:
  std::shared_ptr<const ImageStack> inner_;
  colour::ColourModel model_;
  std::vector<double> toLinear_;        // 16-bit sample -> linear 0..1
  std::vector<std::uint16_t> encode_;   // linear on kEncodeSteps + 1 points -> 16-bit sample
};

}  // namespace surrogate::stages
