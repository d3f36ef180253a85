#include "hrti/hough_votes.h"

#include "core/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace surrogate::hrti {

namespace {

struct ArcTable {
  double cos[kArcVotes], sin[kArcVotes];
};

// The arc angles' cosines and sines, computed once.
const ArcTable& arcs() {
  static const ArcTable table = [] {
    ArcTable t{};
    for (int k = 0; k < kArcVotes; ++k) {
      t.cos[k] = std::cos(kArc[k]);
      t.sin[k] = std::sin(kArc[k]);
    }
    return t;
  }();
  return table;
}

// std::lround(v) for |v| well inside the range of long, without the call into the maths library
// (a fifth of the Hough transform's time): v - trunc(v) is exact, so the half is judged as
// std::lround judges it.
inline long roundHalfAway(double v) {
  const long t = static_cast<long>(v);  // towards zero
  const double f = v - static_cast<double>(t);
  return f >= 0.5 ? t + 1 : f <= -0.5 ? t - 1 : t;
}

// The votes of edges [begin, end), one by one.
void votePlain(const HoughEdges& edges, int r, const HoughGrid& grid, std::size_t begin, std::size_t end) {
  const ArcTable& a = arcs();
  for (std::size_t i = begin; i < end; ++i) {
    const float x = edges.x[i], y = edges.y[i], cosg = edges.cosg[i], sing = edges.sing[i];
    for (int k = 0; k < kArcVotes; ++k) {
      // Rotate the gradient direction by the arc angle; step against it (into the dark).
      const double dx = cosg * a.cos[k] - sing * a.sin[k];
      const double dy = sing * a.cos[k] + cosg * a.sin[k];
      const int cx = static_cast<int>(roundHalfAway(x - r * dx)) - grid.x0;
      const int cy = static_cast<int>(roundHalfAway(y - r * dy)) - grid.y0;
      if (cx >= 0 && cy >= 0 && cx < grid.width && cy < grid.height)
        grid.cells[static_cast<std::size_t>(cy) * grid.width + cx] += edges.weight[i];
    }
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// Edges whose centres one AVX2 pass computes.
constexpr int kLanes = 4;

// roundHalfAway of four values, as doubles: trunc(v) is what the conversion to long gives, and
// adding or subtracting one to a whole number below 2^53 is exact.
__attribute__((target("avx2"))) inline __m256d roundHalfAway4(__m256d v) {
  const __m256d t = _mm256_round_pd(v, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
  const __m256d f = _mm256_sub_pd(v, t);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d up = _mm256_and_pd(_mm256_cmp_pd(f, _mm256_set1_pd(0.5), _CMP_GE_OQ), one);
  const __m256d down = _mm256_and_pd(_mm256_cmp_pd(f, _mm256_set1_pd(-0.5), _CMP_LE_OQ), one);
  return _mm256_sub_pd(_mm256_add_pd(t, up), down);
}

// "avx2" alone: the compiler may not fuse a multiply and an add (that needs "fma"), so every
// product and sum rounds as in votePlain.
__attribute__((target("avx2"))) void voteAvx2(const HoughEdges& edges, int r, const HoughGrid& grid) {
  const ArcTable& a = arcs();
  const std::size_t n = edges.size();
  const __m256d radius = _mm256_set1_pd(static_cast<double>(r));
  const __m128i x0 = _mm_set1_epi32(grid.x0), y0 = _mm_set1_epi32(grid.y0);
  const __m128i width = _mm_set1_epi32(grid.width), height = _mm_set1_epi32(grid.height);
  const __m128i minusOne = _mm_set1_epi32(-1);
  alignas(16) int cell[kArcVotes][kLanes];  // the cell of each arc's vote of each edge, -1 outside
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const __m256d x = _mm256_cvtps_pd(_mm_loadu_ps(edges.x.data() + i));
    const __m256d y = _mm256_cvtps_pd(_mm_loadu_ps(edges.y.data() + i));
    const __m256d cosg = _mm256_cvtps_pd(_mm_loadu_ps(edges.cosg.data() + i));
    const __m256d sing = _mm256_cvtps_pd(_mm_loadu_ps(edges.sing.data() + i));
    for (int k = 0; k < kArcVotes; ++k) {
      const __m256d ca = _mm256_set1_pd(a.cos[k]), sa = _mm256_set1_pd(a.sin[k]);
      const __m256d dx = _mm256_sub_pd(_mm256_mul_pd(cosg, ca), _mm256_mul_pd(sing, sa));
      const __m256d dy = _mm256_add_pd(_mm256_mul_pd(sing, ca), _mm256_mul_pd(cosg, sa));
      const __m128i cx = _mm_sub_epi32(_mm256_cvttpd_epi32(roundHalfAway4(_mm256_sub_pd(x, _mm256_mul_pd(radius, dx)))), x0);
      const __m128i cy = _mm_sub_epi32(_mm256_cvttpd_epi32(roundHalfAway4(_mm256_sub_pd(y, _mm256_mul_pd(radius, dy)))), y0);
      const __m128i inside = _mm_and_si128(_mm_and_si128(_mm_cmpgt_epi32(cx, minusOne), _mm_cmpgt_epi32(cy, minusOne)),
                                           _mm_and_si128(_mm_cmpgt_epi32(width, cx), _mm_cmpgt_epi32(height, cy)));
      const __m128i at = _mm_add_epi32(_mm_mullo_epi32(cy, width), cx);
      _mm_store_si128(reinterpret_cast<__m128i*>(cell[k]), _mm_or_si128(_mm_and_si128(inside, at), _mm_andnot_si128(inside, minusOne)));
    }
    // The votes added in the plain order: edge by edge, arc by arc.
    for (int e = 0; e < kLanes; ++e) {
      const float w = edges.weight[i + e];
      for (int k = 0; k < kArcVotes; ++k)
        if (cell[k][e] >= 0) grid.cells[cell[k][e]] += w;
    }
  }
  votePlain(edges, r, grid, i, n);
}
#endif

}  // namespace

namespace detail {

void houghVotePlain(const HoughEdges& edges, int r, const HoughGrid& grid) {
  votePlain(edges, r, grid, 0, edges.size());
}

bool houghVoteAvx2(const HoughEdges& edges, int r, const HoughGrid& grid) {
#if defined(__x86_64__) && defined(__GNUC__)
  voteAvx2(edges, r, grid);
  return true;
#else
  (void)edges, (void)r, (void)grid;
  return false;
#endif
}

}  // namespace detail

void houghVote(const HoughEdges& edges, int r, const HoughGrid& grid) {
  if (!cpuHasAvx2() || !detail::houghVoteAvx2(edges, r, grid)) detail::houghVotePlain(edges, r, grid);
}

}  // namespace surrogate::hrti
