#include "core/stack.h"

#include <algorithm>
#include <stdexcept>

namespace surrogate {

void ImageStack::readWindow(int index, int x0, int y0, int x1, int y1, std::uint16_t* out) const {
  if (x0 < 0 || x1 > width() || x0 > x1) throw std::out_of_range("readWindow: bad column range");
  const std::size_t c = static_cast<std::size_t>(channels());
  const std::size_t rowSamples = static_cast<std::size_t>(width()) * c, span = std::size_t(x1 - x0) * c;
  if (y1 > y0 && heldRow(index, y0)) {  // rows held in memory: the window straight from them
    for (int y = y0; y < y1; ++y)
      std::copy_n(heldRow(index, y) + std::size_t(x0) * c, span, out + std::size_t(y - y0) * span);
    return;
  }
  std::vector<std::uint16_t> rows(static_cast<std::size_t>(std::max(0, y1 - y0)) * rowSamples);
  readRows(index, y0, y1, rows.data());
  for (int y = y0; y < y1; ++y)
    std::copy_n(rows.data() + std::size_t(y - y0) * rowSamples + std::size_t(x0) * c, span,
                out + std::size_t(y - y0) * span);
}

MemoryImageStack::MemoryImageStack(std::vector<Image> images) : images_(std::move(images)) {
  for (const Image& im : images_) {
    if (im.width != images_[0].width || im.height != images_[0].height ||
        im.channels != images_[0].channels) {
      throw std::invalid_argument("MemoryImageStack: images differ in size or channels");
    }
  }
}

void MemoryImageStack::readRows(int index, int y0, int y1, std::uint16_t* out) const {
  const Image& im = images_.at(index);
  if (y0 < 0 || y1 > im.height || y0 > y1) throw std::out_of_range("readRows: bad row range");
  const std::size_t rowSamples = static_cast<std::size_t>(im.width) * im.channels;
  std::copy(im.pixels.begin() + y0 * rowSamples, im.pixels.begin() + y1 * rowSamples, out);
}

const std::uint16_t* MemoryImageStack::heldRow(int index, int y) const {
  const Image& im = images_.at(index);
  if (y < 0 || y >= im.height) throw std::out_of_range("heldRow: bad row");
  return im.pixels.data() + static_cast<std::size_t>(y) * im.width * im.channels;
}

Image readImage(const ImageStack& stack, int index) {
  Image im(stack.width(), stack.height(), stack.channels());
  im.transfer = stack.transfer();
  stack.readRows(index, 0, stack.height(), im.pixels.data());
  return im;
}

}  // namespace surrogate
