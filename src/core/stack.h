// ImageStack: read access to the N same-sized photographs of a capture by row bands.
//
// Sphere detection (per-pixel median) and fitting (per-pixel least squares) need every image's
// value at a pixel, but never all N full images at once: they stream over bands of rows.
//
//   for (int y0 = 0; y0 < stack.height(); y0 += band) {
//     int y1 = std::min(stack.height(), y0 + band);
//     for (int i = 0; i < stack.size(); ++i) stack.readRows(i, y0, y1, buffer[i].data());
//     ... per-pixel work on the band ...
//   }
//
// Implementations: MemoryImageStack (16-bit images in memory: tests, models re-rendered by the
// audit), the pipeline's DecodedStack (the decoded photographs at their source's depth, in
// memory or in a temporary file) and the views over it in stages/stack_views.h. readRows must
// be safe to call from several threads at once.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace surrogate {

class ImageStack {
 public:
  virtual ~ImageStack() = default;
  virtual int size() const = 0;      // number of images
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;  // 1 (luminance) or 3 (RGB)
  virtual Transfer transfer() const = 0;
  // Copies rows [y0, y1) of image `index` into `out`, interleaved like Image::pixels:
  // (y1 - y0) * width() * channels() samples.
  virtual void readRows(int index, int y0, int y1, std::uint16_t* out) const = 0;
  // Copies columns [x0, x1) of rows [y0, y1) of image `index` into `out`, as readRows gives
  // them there: (y1 - y0) * (x1 - x0) * channels() samples, row after row. This default copies
  // the window from heldRow where the stack holds its rows, else reads the whole rows and keeps
  // the window; a stack that computes its samples as they are read computes only the window's
  // (the highlight search reads a sphere's square, a seventh of the width at 3000x2000).
  virtual void readWindow(int index, int x0, int y0, int x1, int y1, std::uint16_t* out) const;
  // Row y of image `index` where the stack holds it in memory, for readers that need no copy:
  // width() * channels() samples as readRows gives them (heldRow), or as bytes b that stand for
  // the 16-bit values 257 b readRows gives (heldByteRow: stacks of 8-bit sources). nullptr where
  // the stack holds no such row (the default: rows computed as they are read, or kept in a
  // file); a stack holds all its rows or none. Valid as long as the stack.
  virtual const std::uint16_t* heldRow(int /*index*/, int /*y*/) const { return nullptr; }
  virtual const std::uint8_t* heldByteRow(int /*index*/, int /*y*/) const { return nullptr; }
};

// An ImageStack over images held in memory. All images must have the same size and channels.
class MemoryImageStack : public ImageStack {
 public:
  explicit MemoryImageStack(std::vector<Image> images);
  int size() const override { return static_cast<int>(images_.size()); }
  int width() const override { return images_.empty() ? 0 : images_[0].width; }
  int height() const override { return images_.empty() ? 0 : images_[0].height; }
  int channels() const override { return images_.empty() ? 0 : images_[0].channels; }
  Transfer transfer() const override {
    return images_.empty() ? Transfer::Srgb : images_[0].transfer;
  }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;
  const std::uint16_t* heldRow(int index, int y) const override;
  const Image& image(int index) const { return images_[index]; }

 private:
  std::vector<Image> images_;
};

// Images index[0], index[1], ... of another stack, which must outlive it: a fit on some of a
// capture's photographs (the audit's refit without one, the quality at photographs left out,
// stages/held_out_quality.h) reads them where they are, rows held in memory included.
class SubsetStack : public ImageStack {
 public:
  SubsetStack(const ImageStack& inner, std::vector<int> index) : inner_(inner), index_(std::move(index)) {}
  int size() const override { return static_cast<int>(index_.size()); }
  int width() const override { return inner_.width(); }
  int height() const override { return inner_.height(); }
  int channels() const override { return inner_.channels(); }
  Transfer transfer() const override { return inner_.transfer(); }
  void readRows(int i, int y0, int y1, std::uint16_t* out) const override { inner_.readRows(index_[i], y0, y1, out); }
  const std::uint16_t* heldRow(int i, int y) const override { return inner_.heldRow(index_[i], y); }
  const std::uint8_t* heldByteRow(int i, int y) const override { return inner_.heldByteRow(index_[i], y); }

 private:
  const ImageStack& inner_;
  std::vector<int> index_;
};

// Image `index` of a stack, whole, with the stack's transfer.
Image readImage(const ImageStack& stack, int index);

}  // namespace surrogate
