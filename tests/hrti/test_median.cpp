// hrti::medianImage: the per-pixel median of a stack, whether the stack is in memory (read
// where it is) or read band by band (a spilled stack), equals the middle value of each pixel's
// samples sorted in the test.
#include <algorithm>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "../rows_only_stack.h"
#include "core/stack.h"
#include "hrti/median.h"

using namespace surrogate;

TEST_CASE("the median image of a stack in memory and of one read by rows is each pixel's middle sample") {
  const int w = 37, h = 23;
  std::mt19937 rng(5);
  for (int n : {1, 2, 7, 12}) {
    std::vector<Image> images;
    for (int i = 0; i < n; ++i) {
      Image im(w, h, 1);
      for (auto& v : im.pixels) v = static_cast<std::uint16_t>(rng() % 65536);
      images.push_back(im);
    }
    Image expected(w, h, 1);
    for (std::size_t p = 0; p < expected.pixels.size(); ++p) {
      std::vector<std::uint16_t> v;
      for (const Image& im : images) v.push_back(im.pixels[p]);
      std::sort(v.begin(), v.end());
      expected.pixels[p] = v[(v.size() - 1) / 2];  // the lower middle for an even count
    }
    const MemoryImageStack held(images);
    const test::RowsOnlyStack rows(held);  // read by rows, as a spilled stack
    INFO(n << " images");
    CHECK(hrti::medianImage(held, 5, 1).pixels == expected.pixels);
    CHECK(hrti::medianImage(held, 5, 2).pixels == expected.pixels);
    CHECK(hrti::medianImage(rows, 5, 2).pixels == expected.pixels);
    CHECK(hrti::medianImage(rows, 1000, 1).pixels == expected.pixels);
  }
}
