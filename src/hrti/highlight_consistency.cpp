#include "hrti/highlight_consistency.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/parallel.h"
#include "core/text.h"
#include "hrti/light_position.h"
#include "hrti/stack_median.h"

namespace surrogate::hrti {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + (v.size() - 1) / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::string percent(double fraction) { return std::to_string(static_cast<int>(std::lround(fraction * 100))) + " %"; }

// A disc of radius rho around a point, as the window read and the pixels in it.
struct Disc {
  Rect window;                 // inside the frame
  std::vector<int> offsets;    // indices into the window's pixels inside the disc
};

Disc discAround(double x, double y, double rho, int width, int height) {
  Disc d;
  const int x0 = std::clamp(static_cast<int>(std::floor(x - rho)), 0, width - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(y - rho)), 0, height - 1);
  const int x1 = std::clamp(static_cast<int>(std::ceil(x + rho)) + 1, x0 + 1, width);
  const int y1 = std::clamp(static_cast<int>(std::ceil(y + rho)) + 1, y0 + 1, height);
  d.window = {x0, y0, x1 - x0, y1 - y0};
  for (int yy = y0; yy < y1; ++yy)
    for (int xx = x0; xx < x1; ++xx)
      if ((xx - x) * (xx - x) + (yy - y) * (yy - y) <= rho * rho)
        d.offsets.push_back((yy - y0) * d.window.w + (xx - x0));
  if (d.offsets.empty()) d.offsets.push_back(0);
  return d;
}

bool detected(const Highlight& h) { return h.flag == HighlightFlag::Ok || h.flag == HighlightFlag::Multiple; }

}  // namespace

std::vector<std::vector<HighlightSupport>> judgeAcrossImages(const ImageStack& stack, const StackMedian& med,
                                                             const std::vector<DetectedSphere>& spheres,
                                                             std::vector<std::vector<Highlight>>& highlights,
                                                             const std::vector<double>& imageMeans, int threads,
                                                             double lightDistancePx) {
  using L = ConsistencyLimits;
  const std::size_t n = highlights.size();
  std::vector<std::vector<HighlightSupport>> out(n, std::vector<HighlightSupport>(spheres.size()));
  if (n < static_cast<std::size_t>(L::kMinImages) || stack.channels() != 1) return out;
  const double typicalMean = median(imageMeans);
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const DetectedSphere& s = spheres[k];
    std::vector<std::size_t> judged;
    for (std::size_t i = 0; i < n; ++i)
      if (detected(highlights[i][k])) judged.push_back(i);
    if (judged.size() < static_cast<std::size_t>(L::kMinImages)) continue;
    const double rho = std::max(3.0, 2 * std::clamp(s.r / 150.0, 0.8, 4.0));
    const double near = std::max(3 * rho, s.r / 20);
    // The discs, and the median over each (tiles of the median are computed once and kept).
    std::vector<Disc> discs;
    std::vector<double> steadyLevel;
    for (std::size_t i : judged) {
      discs.push_back(discAround(highlights[i][k].x, highlights[i][k].y, rho, stack.width(), stack.height()));
      const Image m = med.window(discs.back().window);
      double sum = 0;
      for (int o : discs.back().offsets) sum += m.pixels[static_cast<std::size_t>(o)] / 65535.0;
      steadyLevel.push_back(sum / discs.back().offsets.size());
    }
    // rise[j][c]: image j's mean rise over disc c; level[c]: image judged[c]'s mean over its disc.
    std::vector<std::vector<double>> rise(n, std::vector<double>(judged.size(), 0));
    std::vector<double> level(judged.size(), 0);
    parallelFor(n, 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      std::vector<std::uint16_t> pixels;
      for (std::size_t j = b; j < e; ++j)
        for (std::size_t c = 0; c < judged.size(); ++c) {
          const Rect& w = discs[c].window;
          pixels.resize(static_cast<std::size_t>(w.w) * w.h);
          stack.readWindow(static_cast<int>(j), w.x, w.y, w.x + w.w, w.y + w.h, pixels.data());
          const Image m = med.window(w);
          double sum = 0, value = 0;
          for (int o : discs[c].offsets) {
            const double v = pixels[static_cast<std::size_t>(o)] / 65535.0;
            sum += std::max(0.0, v - m.pixels[static_cast<std::size_t>(o)] / 65535.0);
            value += v;
          }
          rise[j][c] = sum / discs[c].offsets.size();
          if (j == judged[c]) level[c] = value / discs[c].offsets.size();
        }
    });
    // The highlight's flux: its rise summed over a disc of 4 rho, above the images' lower
    // quartile there (not the median: where the lights are close together, the highlights
    // overlap and raise the median). The same lamp mirrored in the same sphere gives about the
    // same flux in every image; a reflection of the room or a remnant of glare a fraction of it.
    std::vector<double> flux(judged.size(), 0), clippedArea(judged.size(), 0);
    const int quartile = static_cast<int>(n - 1) / 4;
    parallelFor(judged.size(), 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      for (std::size_t c = b; c < e; ++c) {
        const Highlight& h = highlights[judged[c]][k];
        const Disc big = discAround(h.x, h.y, 4 * rho, stack.width(), stack.height());
        const std::size_t area = static_cast<std::size_t>(big.window.w) * big.window.h;
        std::vector<std::uint16_t> all(area * n), values(n);
        for (std::size_t j = 0; j < n; ++j)
          stack.readWindow(static_cast<int>(j), big.window.x, big.window.y, big.window.x + big.window.w,
                           big.window.y + big.window.h, all.data() + j * area);
        const std::uint16_t* own = all.data() + judged[c] * area;
        for (int o : big.offsets) {
          for (std::size_t j = 0; j < n; ++j) values[j] = all[j * area + static_cast<std::size_t>(o)];
          std::nth_element(values.begin(), values.begin() + quartile, values.end());
          const double under = values[static_cast<std::size_t>(quartile)] / 65535.0;
          flux[c] += std::max(0.0, own[o] / 65535.0 - under) / std::max(0.05, 1 - under);
        }
        std::vector<std::uint16_t> pixels;
        // The clipped area around it, for exposure-outlier: the lamp's halo reaches full scale
        // over a wider disc in a frame exposed too long.
        const Disc wide = discAround(h.x, h.y, L::kClippedRadius * s.r, stack.width(), stack.height());
        pixels.resize(static_cast<std::size_t>(wide.window.w) * wide.window.h);
        stack.readWindow(static_cast<int>(judged[c]), wide.window.x, wide.window.y, wide.window.x + wide.window.w,
                         wide.window.y + wide.window.h, pixels.data());
        int clipped = 0;
        for (int o : wide.offsets)
          clipped += pixels[static_cast<std::size_t>(o)] >= HighlightLimits::kSaturatedLevel * 65535;
        clippedArea[c] = clipped;
      }
    });
    for (std::size_t c = 0; c < judged.size(); ++c) highlights[judged[c]][k].clippedArea = clippedArea[c];
    // A near light: a highlight whose light was farther from the sphere than the median is
    // brought to the median distance. Never lowered: a clipped highlight's flux grows far less
    // than 1/t^2 as its light comes nearer, so scaling the near ones down would make them faint.
    if (lightDistancePx > 0) {
      std::vector<double> t(judged.size(), 0), known;
      for (std::size_t c = 0; c < judged.size(); ++c) {
        const Highlight& h = highlights[judged[c]][k];
        Vec3 point, ray;
        mirrorRay(s, h.x, h.y, stack.width(), stack.height(), point, ray);
        const PositionAtDistance x = positionAtDistance(s, ray, lightDistancePx, stack.width(), stack.height());
        if (!x.ok) continue;
        t[c] = std::hypot(x.position[0] - point[0], x.position[1] - point[1], x.position[2] - point[2]);
        known.push_back(t[c]);
      }
      const double typical = median(known);
      for (std::size_t c = 0; c < judged.size() && typical > 0; ++c)
        if (t[c] > typical) flux[c] *= (t[c] / typical) * (t[c] / typical);
    }
    // fixed: shared with other images, or bright in the median.
    std::vector<bool> fixed(judged.size(), false);
    for (std::size_t c = 0; c < judged.size(); ++c) {
      const std::size_t i = judged[c];
      const Highlight& h = highlights[i][k];
      HighlightSupport& sup = out[i][k];
      sup.judged = true;
      sup.rise = rise[i][c];
      sup.steady = level[c] > 0 ? steadyLevel[c] / level[c] : 1;
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const Highlight& other = highlights[j][k];
        const bool hasOwn = isUsable(other.flag) || other.flag == HighlightFlag::Multiple;
        if (hasOwn && std::hypot(other.x - h.x, other.y - h.y) <= near) continue;
        if (rise[j][c] >= L::kSharedRise * sup.rise) ++sup.shared;
      }
      fixed[c] = 2 * sup.shared > static_cast<int>(n - 1) && sup.steady >= L::kSteadyRatio;
    }
    std::vector<double> others;
    for (std::size_t c = 0; c < judged.size(); ++c)
      if (!fixed[c]) others.push_back(flux[c]);
    const double typicalFlux = median(others);
    for (std::size_t c = 0; c < judged.size(); ++c) {
      const std::size_t i = judged[c];
      Highlight& h = highlights[i][k];
      const HighlightSupport& sup = out[i][k];
      const bool dark = imageMeans.size() == n && typicalMean > 0 && imageMeans[i] < L::kDarkImage * typicalMean;
      const double size = typicalFlux > 0 ? flux[c] / typicalFlux : 1;
      out[i][k].flux = size;
      const bool faint = !fixed[c] && !dark && imageMeans.size() == n && others.size() >= 3 && size < L::kFaintRatio;
      const std::string at =
          "the brightest new spot on the sphere, at " + fixedDecimals(h.x, 0) + "," + fixedDecimals(h.y, 0);
      if (fixed[c]) {
        h.flag = HighlightFlag::Fixed;
        h.confidence = 0;
        h.reason = at + ", brightens in " + std::to_string(sup.shared) + " of the " + std::to_string(n - 1) +
                   " other images too, whose lights are elsewhere, and is " + percent(sup.steady) +
                   " as bright in most images (the stack's median) as in this one: it is a reflection of the "
                   "room or dust fixed on the sphere, not this image's highlight. The light probably missed "
                   "the sphere or did not fire";
      } else if (faint) {
        h.flag = HighlightFlag::Faint;
        h.confidence = 0;
        h.reason = at + ", gives " + percent(size) + " of the light of the other images' highlights (the same lamp "
                   "mirrored in the sphere gives at least " + percent(L::kFaintRatio) +
                   " of it): the highlight is missing, what was found is a reflection of the room or glare. The "
                   "light probably missed the sphere or did not fire" +
                   std::string(lightDistancePx > 0 ? ""
                                                   : "; or the flash was near, and farther from this sphere than in the "
                                                     "other images: then state its distance with --light-distance D "
                                                     "(frame widths from the frame's centre)");
      }
    }
  }
  return out;
}

}  // namespace surrogate::hrti
