// The Hough votes (hrti/hough_votes.h): the AVX2 variant gives the plain one's accumulator bit
// for bit, and the plain one what std::lround of the centres gives, on random edges that vote
// inside and outside the grid, many into the same cells (the float sums' order shows in their
// bits), and with centres exactly half way between two cells.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/cpu_features.h"
#include "hrti/hough_votes.h"

using namespace surrogate::hrti;

namespace {

// The accumulator as the sphere search made it before the votes had a file of their own.
std::vector<float> byLround(const HoughEdges& e, int r, int x0, int y0, int width, int height) {
  std::vector<float> acc(static_cast<std::size_t>(width) * height, 0.0f);
  for (std::size_t i = 0; i < e.size(); ++i)
    for (int k = 0; k < kArcVotes; ++k) {
      const double dx = e.cosg[i] * std::cos(kArc[k]) - e.sing[i] * std::sin(kArc[k]);
      const double dy = e.sing[i] * std::cos(kArc[k]) + e.cosg[i] * std::sin(kArc[k]);
      const int cx = static_cast<int>(std::lround(e.x[i] - r * dx)) - x0;
      const int cy = static_cast<int>(std::lround(e.y[i] - r * dy)) - y0;
      if (cx >= 0 && cy >= 0 && cx < width && cy < height) acc[static_cast<std::size_t>(cy) * width + cx] += e.weight[i];
    }
  return acc;
}

HoughEdges randomEdges(std::mt19937& rng, std::size_t n, int extent) {
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f), weight(0.01f, 1.0f);
  std::uniform_int_distribution<int> at(-4, extent + 4), kind(0, 3);
  HoughEdges e;
  for (std::size_t i = 0; i < n; ++i) {
    float x = float(at(rng)), y = float(at(rng)), c, s;
    switch (kind(rng)) {
      case 0: c = 1, s = 0, x += 0.5f; break;   // the central vote exactly half way, to the right
      case 1: c = 0, s = -1, y -= 0.5f; break;  // half way, upwards (a negative half)
      default: {
        const float a = angle(rng);
        c = std::cos(a), s = std::sin(a);
      }
    }
    e.push_back(x, y, c, s, weight(rng));
  }
  return e;
}

}  // namespace

TEST_CASE("Hough votes: the AVX2 variant gives the plain one's bits, the plain one lround's") {
  std::mt19937 rng(59);
  for (const std::size_t n : {std::size_t(0), std::size_t(3), std::size_t(4), std::size_t(1001), std::size_t(20003)}) {
    for (const int r : {6, 23, 47}) {
      const int x0 = 5, y0 = -3, width = 61, height = 40;
      const HoughEdges e = randomEdges(rng, n, 64);
      const std::vector<float> expected = byLround(e, r, x0, y0, width, height);
      std::vector<float> plain(expected.size(), 0.0f), avx2(expected.size(), 0.0f);
      detail::houghVotePlain(e, r, {plain.data(), x0, y0, width, height});
      REQUIRE(std::memcmp(plain.data(), expected.data(), plain.size() * sizeof(float)) == 0);
      if (!surrogate::cpuHasAvx2() || !detail::houghVoteAvx2(e, r, {avx2.data(), x0, y0, width, height})) continue;
      REQUIRE(std::memcmp(avx2.data(), plain.data(), plain.size() * sizeof(float)) == 0);
      // The dispatching entry point adds to what the grid holds.
      houghVote(e, r, {avx2.data(), x0, y0, width, height});
      detail::houghVotePlain(e, r, {plain.data(), x0, y0, width, height});
      REQUIRE(std::memcmp(avx2.data(), plain.data(), plain.size() * sizeof(float)) == 0);
    }
  }
}
