// hrti::StackMedian: its full-resolution windows are each pixel's middle sample and its reduced
// median the middle of each reduced pixel's samples, both computed plainly here, whether the
// stack is in memory (read where it is) or read by rows (a spilled stack), at 1 and 2 threads.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "../rows_only_stack.h"
#include "core/error.h"
#include "core/stack.h"
#include "hrti/stack_median.h"

using namespace surrogate;
using hrti::StackMedian;

namespace {

std::vector<Image> noise(int n, int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Image> images;
  for (int i = 0; i < n; ++i) {
    Image im(w, h, 1);
    for (auto& v : im.pixels) v = static_cast<std::uint16_t>(rng() % 65536);
    images.push_back(im);
  }
  return images;
}

// The lower middle value of each pixel's samples (the middle one for an odd count).
Image plainMedian(const std::vector<Image>& images) {
  Image out(images[0].width, images[0].height, 1);
  for (std::size_t p = 0; p < out.pixels.size(); ++p) {
    std::vector<std::uint16_t> v;
    for (const Image& im : images) v.push_back(im.pixels[p]);
    std::nth_element(v.begin(), v.begin() + (v.size() - 1) / 2, v.end());
    out.pixels[p] = v[(v.size() - 1) / 2];
  }
  return out;
}

// Each pixel's samples sorted, the one at `rank` (0: the smallest).
Image plainRanked(const std::vector<Image>& images, std::size_t rank) {
  Image out(images[0].width, images[0].height, 1);
  for (std::size_t p = 0; p < out.pixels.size(); ++p) {
    std::vector<std::uint16_t> v;
    for (const Image& im : images) v.push_back(im.pixels[p]);
    std::sort(v.begin(), v.end());
    out.pixels[p] = v[rank];
  }
  return out;
}

// Each f x f block's mean (the blocks at the right and bottom edges cut by the frame),
// rounded to the nearest integer, halves up.
Image plainReduced(const Image& im, int f) {
  Image out((im.width + f - 1) / f, (im.height + f - 1) / f, 1);
  for (int cy = 0; cy < out.height; ++cy)
    for (int cx = 0; cx < out.width; ++cx) {
      double sum = 0;
      int count = 0;
      for (int y = cy * f; y < std::min(im.height, cy * f + f); ++y)
        for (int x = cx * f; x < std::min(im.width, cx * f + f); ++x) {
          sum += im.at(x, y);
          ++count;
        }
      out.at(cx, cy) = static_cast<std::uint16_t>(std::floor(sum / count + 0.5));
    }
  return out;
}

Image crop(const Image& im, const hrti::Rect& r) {
  Image out(r.w, r.h, 1);
  for (int y = 0; y < r.h; ++y)
    for (int x = 0; x < r.w; ++x) out.at(x, y) = im.at(r.x + x, r.y + y);
  return out;
}

}  // namespace

TEST_CASE("full-resolution windows of the median are each pixel's middle sample") {
  const int w = 150, h = 97;  // tiles cut by both edges
  for (int n : {1, 2, 3, 7, 12, 36}) {  // 36: a sorting network of many stages (AVX2)
    const std::vector<Image> images = noise(n, w, h, 5 + n);
    const Image expected = plainMedian(images);
    const MemoryImageStack held(images);
    const test::RowsOnlyStack rows(held);  // read by rows, as a spilled stack
    for (const ImageStack* stack : {static_cast<const ImageStack*>(&held), static_cast<const ImageStack*>(&rows)})
      for (int threads : {1, 2}) {
        INFO(n << " images, " << threads << " threads, " << (stack == &held ? "in memory" : "by rows"));
        const StackMedian median(*stack, 50, threads);
        // Overlapping windows: later ones partly from tiles an earlier one computed.
        for (const hrti::Rect& r : {hrti::Rect{70, 10, 20, 60}, hrti::Rect{60, 0, 90, 30}, hrti::Rect{149, 96, 1, 1},
                                    hrti::Rect{0, 0, w, h}, hrti::Rect{63, 63, 2, 2}})
          CHECK(median.window(r).pixels == crop(expected, r).pixels);
      }
  }
}

TEST_CASE("the reduced median is the middle of each reduced pixel's samples") {
  for (int n : {1, 2, 3, 7, 12, 36}) {  // 36: a sorting network of many stages (AVX2)
    for (int w : {150, 151}) {  // 151: the right blocks cut by the frame
      const int h = 97;         // the bottom blocks cut by the frame
      const std::vector<Image> images = noise(n, w, h, 11 + n);
      std::vector<Image> reduced;
      for (const Image& im : images) reduced.push_back(plainReduced(im, 3));
      const Image expected = plainMedian(reduced);
      const MemoryImageStack held(images);
      const test::RowsOnlyStack rows(held);
      for (const ImageStack* stack : {static_cast<const ImageStack*>(&held), static_cast<const ImageStack*>(&rows)})
        for (int threads : {1, 2})
          for (std::size_t budget : {std::size_t(1), StackMedian::kCoarseBudget}) {  // one coarse row a band, or all
            INFO(n << " images, " << w << " wide, " << threads << " threads, budget " << budget);
            const StackMedian median(*stack, 50, threads, budget);
            REQUIRE(median.factor() == 3);
            CHECK(median.coarse().width == expected.width);
            CHECK(median.coarse().height == expected.height);
            CHECK(median.coarse().pixels == expected.pixels);
          }
    }
  }
}

TEST_CASE("the reduction is the integer factor nearest the coarse width, at least 1 and at most kMaxFactor") {
  CHECK(StackMedian::factorFor(3000, 800) == 4);  // 3.75
  CHECK(StackMedian::factorFor(6000, 800) == 8);  // 7.5
  CHECK(StackMedian::factorFor(1200, 800) == 2);  // 1.5
  CHECK(StackMedian::factorFor(480, 800) == 1);
  CHECK(StackMedian::factorFor(1 << 30, 1) == StackMedian::kMaxFactor);  // block sums stay within 32 bits
}

TEST_CASE("a window outside the frame is an Error, not a read past the images") {
  const MemoryImageStack held(noise(3, 40, 30, 1));
  const StackMedian median(held, 800, 1);
  CHECK_THROWS_AS(median.window({30, 0, 20, 10}), Error);
  CHECK_THROWS_AS(median.window({-1, 0, 5, 5}), Error);
  CHECK_THROWS_AS(median.window({0, 0, 0, 5}), Error);
}

TEST_CASE("a quantile's windows and reduced image are each pixel's sample of rank floor(q (n - 1))") {
  const int w = 70, h = 45;
  for (int n : {4, 12, 36}) {
    const std::vector<Image> images = noise(n, w, h, 11 + n);
    for (double q : {0.0, 0.75, 1.0}) {
      const std::size_t rank = static_cast<std::size_t>(std::floor(q * (n - 1)));
      CHECK(StackMedian::rankFor(n, q) == static_cast<int>(rank));
      const MemoryImageStack held(images);
      for (int threads : {1, 2}) {
        INFO(n << " images, quantile " << q << ", " << threads << " threads");
        const StackMedian upper(held, 35, threads, StackMedian::kCoarseBudget, q);
        CHECK(upper.window({0, 0, w, h}).pixels == plainRanked(images, rank).pixels);
        std::vector<Image> reduced;
        for (const Image& im : images) reduced.push_back(plainReduced(im, upper.factor()));
        CHECK(upper.coarse().pixels == plainRanked(reduced, rank).pixels);
      }
    }
  }
  CHECK(StackMedian::rankFor(12, 0.5) == 5);  // the lower median, as StackMedian's default
  CHECK_THROWS_AS(StackMedian::rankFor(12, 1.5), Error);
}

TEST_CASE("the median and another quantile from one reading are each pixel's samples of both ranks") {
  const int w = 151, h = 97;  // blocks and tiles cut by both edges
  for (int n : {1, 4, 13, 36}) {  // 36: a sorting network of many stages (AVX2); 13: a scalar tail
    const std::vector<Image> images = noise(n, w, h, 23 + n);
    const std::size_t middle = static_cast<std::size_t>(n - 1) / 2;
    const std::size_t upper = static_cast<std::size_t>(std::floor(0.75 * (n - 1)));
    std::vector<Image> reduced;
    for (const Image& im : images) reduced.push_back(plainReduced(im, 3));
    auto held = std::make_shared<MemoryImageStack>(images);
    auto rows = std::make_shared<test::RowsOnlyStack>(*held);  // read by rows, as a spilled stack
    for (std::shared_ptr<const ImageStack> stack : {std::shared_ptr<const ImageStack>(held),
                                                   std::shared_ptr<const ImageStack>(rows)})
      for (int threads : {1, 2})
        for (std::size_t budget : {std::size_t(1), StackMedian::kCoarseBudget}) {  // one coarse row a band, or all
          INFO(n << " images, " << threads << " threads, budget " << budget << (stack == held ? ", in memory" : ", by rows"));
          const auto [median, quantile] = StackMedian::medianAnd(stack, 0.75, 50, threads, budget);
          REQUIRE(median->factor() == 3);
          REQUIRE(quantile->factor() == 3);
          CHECK(median->coarse().pixels == plainRanked(reduced, middle).pixels);
          CHECK(quantile->coarse().pixels == plainRanked(reduced, upper).pixels);
          const hrti::Rect r{60, 0, 91, 40};
          CHECK(median->window(r).pixels == crop(plainRanked(images, middle), r).pixels);
          CHECK(quantile->window(r).pixels == crop(plainRanked(images, upper), r).pixels);
          // Each image's mean of its reduced copy, as one median alone gives it.
          std::vector<double> means;
          for (const Image& im : reduced) {
            double sum = 0;
            for (std::uint16_t v : im.pixels) sum += v;
            means.push_back(sum / double(im.pixels.size()) / 65535.0);
          }
          for (const auto& m : {median, quantile}) {
            REQUIRE(m->imageMeans().size() == means.size());
            for (std::size_t i = 0; i < means.size(); ++i) CHECK(m->imageMeans()[i] == Approx(means[i]).epsilon(1e-12));
          }
        }
  }
}

TEST_CASE("the reduced image is each block's rounded mean at every factor, whole blocks and cut ones") {
  // Factors 2 to 16 divide whole blocks by a count the compiler knows; 1 and 17 take the general
  // division. Blocks of 65535 alone reach the largest sums; the frame cuts the last blocks.
  for (int f : {1, 2, 3, 4, 5, 7, 8, 11, 16, 17}) {
    const int w = 10 * f + 1, h = 5 * f + 1;  // ten whole blocks and one column a row
    for (bool bright : {false, true}) {
      std::vector<Image> images = noise(3, w, h, 300 + f);
      if (bright)
        for (Image& im : images) std::fill(im.pixels.begin(), im.pixels.end(), std::uint16_t(65535));
      std::vector<Image> reduced;
      for (const Image& im : images) reduced.push_back(plainReduced(im, f));
      const MemoryImageStack held(images);
      const test::RowsOnlyStack rows(held);
      for (const ImageStack* stack : {static_cast<const ImageStack*>(&held), static_cast<const ImageStack*>(&rows)}) {
        INFO("factor " << f << (bright ? ", all 65535" : ", noise"));
        const StackMedian median(*stack, 10, 1);
        REQUIRE(median.factor() == f);
        CHECK(median.coarse().pixels == plainMedian(reduced).pixels);
      }
    }
  }
}
