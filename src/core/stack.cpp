#include "core/stack.h"

#include <algorithm>
#include <stdexcept>

namespace surrogate {

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

}  // namespace surrogate
