// The voting of the circle Hough transform of the sphere search (hrti/sphere_detection.cpp):
// every edge votes for the centres one radius away against its gradient, on a short arc of
// directions around it. Compiled for AVX2 as well, giving the same accumulator bits: the
// centres are computed four edges at a time with the same double operations and rounding, and
// the votes are added one by one in the plain order (edge by edge, arc by arc), since float
// sums in another order differ in their last bits.
#pragma once

#include <cmath>
#include <vector>

namespace surrogate::hrti {

// The arc of votes around the gradient direction (radians).
constexpr double kArc[] = {-M_PI / 12, -M_PI / 24, 0, M_PI / 24, M_PI / 12};
constexpr int kArcVotes = 5;

// The edges of one Hough level that vote, one array per quantity: position (pixels of the
// level), unit gradient direction, weight.
struct HoughEdges {
  std::vector<float> x, y, cosg, sing, weight;
  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  void push_back(float ex, float ey, float c, float s, float w) {
    x.push_back(ex);
    y.push_back(ey);
    cosg.push_back(c);
    sing.push_back(s);
    weight.push_back(w);
  }
};

// The accumulator the votes go into: `width` x `height` floats in rows, cell (0, 0) at the
// level's pixel (x0, y0). Votes outside it are dropped.
struct HoughGrid {
  float* cells;
  int x0, y0, width, height;
};

// Adds the votes of `edges` for radius r (pixels of the level) into `grid`: for each edge and
// arc angle, the edge's weight at the centre r away against the rotated gradient, rounded half
// away from zero. AVX2 when the processor has it (the same bits).
void houghVote(const HoughEdges& edges, int r, const HoughGrid& grid);

namespace detail {
// The two variants, for the test that compares them; houghVoteAvx2 returns false (and does
// nothing) where it is not compiled.
void houghVotePlain(const HoughEdges& edges, int r, const HoughGrid& grid);
bool houghVoteAvx2(const HoughEdges& edges, int r, const HoughGrid& grid);
}  // namespace detail

}  // namespace surrogate::hrti
