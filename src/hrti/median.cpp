#include "hrti/median.h"

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace surrogate::hrti {

Image medianImage(const ImageStack& stack, int bandRows, int threads) {
  if (stack.channels() != 1 || stack.size() == 0)
    throw Error(ErrorKind::Internal, "", "median", "the median needs a non-empty one-channel stack");
  const int n = stack.size(), w = stack.width(), h = stack.height();
  Image out(w, h, 1);
  out.transfer = stack.transfer();
  // A stack already in memory (the decoded stacks when they fit --memory) is read where it is,
  // as one band: a band copy of every image would double its memory for nothing.
  const auto* held = dynamic_cast<const MemoryImageStack*>(&stack);
  bandRows = held ? h : std::clamp(bandRows, 1, h);
  std::vector<std::uint16_t> band(held ? 0 : std::size_t(n) * bandRows * w);
  std::vector<const std::uint16_t*> rows(n);  // each image's first row of the band
  for (int y0 = 0; y0 < h; y0 += bandRows) {
    const int count = std::min(bandRows, h - y0);
    const std::size_t plane = std::size_t(count) * w;
    for (int i = 0; i < n; ++i)
      rows[i] = held ? held->image(i).pixels.data() + std::size_t(y0) * w : &band[i * plane];
    if (!held)
      parallelFor(n, 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
          stack.readRows(static_cast<int>(i), y0, y0 + count, &band[i * plane]);
      });
    parallelFor(plane, 4096, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      std::vector<std::uint16_t> samples(n);
      for (std::size_t p = b; p < e; ++p) {
        for (int i = 0; i < n; ++i) samples[i] = rows[i][p];
        const auto mid = samples.begin() + (n - 1) / 2;
        std::nth_element(samples.begin(), mid, samples.end());
        out.pixels[std::size_t(y0) * w + p] = *mid;
      }
    });
  }
  return out;
}

}  // namespace surrogate::hrti
