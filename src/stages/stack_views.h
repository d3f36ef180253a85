// Pre-processed views of an ImageStack: cropped, re-balanced, reduced.
//
// Each view computes its rows on demand from the stack it wraps, so pre-processing a capture
// costs no memory beyond the rows being read and never writes a copy of the photographs; the
// fit streams through the views by row bands as it streams through the decoded stack. Every
// view is a pure function of the wrapped pixels (integer arithmetic or fixed tables), so the
// values are identical at any thread count and on re-execution.
//
//   auto cropped = std::make_shared<CropStack>(decoded, PixelRect{40, 30, 300, 200});
//   auto reduced = std::make_shared<AreaResizeStack>(cropped, 150, 100);
//   fitPtm(*reduced, lights, options);
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/stack.h"
#include "pipeline/decoded_stack.h"
#include "stages/preprocess.h"

namespace surrogate::stages {

// The rectangle `rect` of every image (which must lie inside the images).
class CropStack : public ImageStack {
 public:
  CropStack(std::shared_ptr<const ImageStack> inner, PixelRect rect);
  int size() const override { return inner_->size(); }
  int width() const override { return rect_.width; }
  int height() const override { return rect_.height; }
  int channels() const override { return inner_->channels(); }
  Transfer transfer() const override { return inner_->transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;

 private:
  std::shared_ptr<const ImageStack> inner_;
  PixelRect rect_;
};

// Rec. 709 luminance of every decoded image (core/image.h luminanceOfPixels: the same values as
// `luminance` of the image), computed from the stored samples as rows are read; a grey stack
// is its own luminance. What sphere and highlight detection read.
class LuminanceStack : public ImageStack {
 public:
  explicit LuminanceStack(std::shared_ptr<const pipeline::DecodedStack> decoded);
  int size() const override { return decoded_->size(); }
  int width() const override { return decoded_->width(); }
  int height() const override { return decoded_->height(); }
  int channels() const override { return 1; }
  Transfer transfer() const override { return decoded_->transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;
  void readWindow(int index, int x0, int y0, int x1, int y1, std::uint16_t* out) const override;

 private:
  std::shared_ptr<const pipeline::DecodedStack> decoded_;
};

// A grey stack as RGB: each sample three times.
class GreyAsRgbStack : public ImageStack {
 public:
  explicit GreyAsRgbStack(std::shared_ptr<const ImageStack> grey);
  int size() const override { return grey_->size(); }
  int width() const override { return grey_->width(); }
  int height() const override { return grey_->height(); }
  int channels() const override { return 3; }
  Transfer transfer() const override { return grey_->transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;

 private:
  std::shared_ptr<const ImageStack> grey_;
};

// Per-channel tables applied to every sample: out = table[c][in]. Used for white-balance gains
// and the change of encoding (sRGB <-> linear).
class TableStack : public ImageStack {
 public:
  using Table = std::vector<std::uint16_t>;  // 65536 entries
  TableStack(std::shared_ptr<const ImageStack> inner, std::array<Table, 3> tables, Transfer transfer);
  int size() const override { return inner_->size(); }
  int width() const override { return inner_->width(); }
  int height() const override { return inner_->height(); }
  int channels() const override { return inner_->channels(); }
  Transfer transfer() const override { return transfer_; }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;

 private:
  std::shared_ptr<const ImageStack> inner_;
  std::array<Table, 3> tables_;
  Transfer transfer_;
};

// The tables of a gain per channel: each input value is decoded to linear light (from sRGB
// when `input` is Srgb), multiplied by its channel's gain, clipped to full scale, and encoded
// as `output` (rounded to 16 bits).
std::array<TableStack::Table, 3> gainTables(const std::array<double, 3>& gains, Transfer input,
                                            Transfer output);

// Linear light of a 16-bit sample (sRGB decoding, IEC 61966-2-1), 0..1; identity scaled for
// Transfer::Linear.
double toLinear(std::uint16_t value, Transfer transfer);
// The same for a value 0..1 of such a stack (clamped; rounded to 16 bits first), such as a
// median's image mean or a highlight's peak: exposures are compared in linear light.
double linearOf(double value, Transfer transfer);

// Reduces every image to width x height (at most the input's) by area averaging in linear
// light: each output pixel is the mean of the input pixels it covers, each weighted by the
// exact fraction of its area inside (integer weights), then encoded back as the input was.
class AreaResizeStack : public ImageStack {
 public:
  AreaResizeStack(std::shared_ptr<const ImageStack> inner, int width, int height);
  int size() const override { return inner_->size(); }
  int width() const override { return width_; }
  int height() const override { return height_; }
  int channels() const override { return inner_->channels(); }
  Transfer transfer() const override { return inner_->transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;

 private:
  struct Span {  // input pixels [first, first + weights.size()) with their integer weights
    int first;
    std::vector<std::int64_t> weights;
  };
  static std::vector<Span> spans(int in, int out);
  std::shared_ptr<const ImageStack> inner_;
  int width_, height_;
  std::vector<Span> xSpans_, ySpans_;
  // 16-bit sample -> linear light scaled to 2^24, strictly increasing; the mean goes back to
  // the sample whose linear value is nearest (binary search: integers only).
  std::vector<std::int64_t> toLinear_;
  // bucketStart_[b]: the first sample whose linear value is >= b * 256 (where the search for
  // a mean starts; a few steps at most).
  std::vector<std::uint16_t> bucketStart_;
};

}  // namespace surrogate::stages
