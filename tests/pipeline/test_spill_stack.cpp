#include <catch2/catch.hpp>

#include <thread>

#include "core/parallel.h"
#include "pipeline/spill_stack.h"

using namespace surrogate;

TEST_CASE("a SpillStack returns exactly the rows written, from several threads") {
  const int n = 5, w = 37, h = 23;
  pipeline::SpillStack stack(n, w, h, 3, Transfer::Srgb);
  std::vector<Image> images;
  for (int i = 0; i < n; ++i) {
    Image im(w, h, 3);
    for (std::size_t k = 0; k < im.pixels.size(); ++k) im.pixels[k] = static_cast<std::uint16_t>(k * 31 + i * 7);
    images.push_back(im);
  }
  parallelFor(n, 1, 2, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) stack.write(static_cast<int>(i), images[i]);
  });
  for (int i = 0; i < n; ++i) CHECK(stack.read(i).pixels == images[i].pixels);
  std::vector<std::uint16_t> band(std::size_t(w) * 3 * 4);
  stack.readRows(2, 10, 14, band.data());
  CHECK(std::equal(band.begin(), band.end(), images[2].pixels.begin() + std::size_t(10) * w * 3));
  CHECK_THROWS(stack.readRows(0, 20, 24, band.data()));
  Image wrong(w + 1, h, 3);
  CHECK_THROWS(stack.write(0, wrong));
}
