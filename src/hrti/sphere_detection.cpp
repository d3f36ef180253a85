#include "hrti/sphere_detection.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "hrti/accumulator_peaks.h"
#include "hrti/circle_fit.h"
#include "hrti/highlight_detection.h"
#include "hrti/hough_votes.h"
#include "hrti/rim_fit.h"
#include "hrti/stack_median.h"

namespace surrogate::hrti {

namespace {

constexpr const char* kStep = "sphere detection";
// A light in front of the object puts its highlight within sin 45 deg = 0.71 of the radius;
// a little more allows for the highlight's own size and the rim's fit.
constexpr double kFrontRadius = 0.75;
// Highlights that all lie within this share of the radius of each other do not move.
constexpr double kMinMotion = 0.05;
// A sphere shows a usable highlight in front in at least this share of the images.
constexpr double kMinEvidence = 0.5;
// Circles larger than this (pixels) are checked for highlights on reduced images.
constexpr double kEvidenceRadius = 100;
// Distinct Hough candidates refined when searching the whole frame (plus four per octave).
constexpr std::size_t kCandidates = 40;

struct Candidate {
  double x = 0, y = 0, r = 0, score = -1;
  int level = 1;  // the reduction of the Hough level that found it (its uncertainty, in coarse pixels)
};

struct Gradients {
  cv::Mat gx, gy, mag;
};

Gradients gradients(const cv::Mat& coarse8) {
  cv::Mat smooth;
  cv::medianBlur(coarse8, smooth, 7);
  Gradients g;
  cv::Sobel(smooth, g.gx, CV_32F, 1, 0, 3);
  cv::Sobel(smooth, g.gy, CV_32F, 0, 1, 3);
  cv::magnitude(g.gx, g.gy, g.mag);
  return g;
}

// The accumulator value a perfect circle of radius r (unit edge strength) reaches at its
// centre: each edge pixel's central vote lands there, the arc votes land 2 r sin(|phi|/2)
// away and reach it only through the blur below (sigma 1). Dividing by this, not by the
// circumference alone, keeps scores comparable across radii: otherwise the five votes of a
// small circle pile up in one cell and a few pixels of any dark edge (a sphere's rim near
// the frame) outscore the whole sphere (seen at 6000 px wide, radius 308 px).
double perfectCircle(int r) {
  double sum = 0;
  for (int k = 0; k < kArcVotes; ++k) {
    const double d = 2 * r * std::sin(std::abs(kArc[k]) / 2);
    sum += std::exp(-d * d / 2);
  }
  return 2 * M_PI * r * sum;
}

// The edges of one Hough level that vote, and the area they vote in.
struct Votes {
  cv::Rect area;
  HoughEdges edges;
};

// The edges that vote: those above the 80th percentile of the area's gradients or a tenth of
// the strongest, whichever is lower (and at least 2 % of the strongest), each vote growing
// with the gradient up to its 97th percentile: a circle's score is then how much of its
// outline is a clear edge. The few very strong edges of the scene reflected in a sphere (a
// lamp) can neither outvote its fainter rim nor, through a floor set by them, silence it
// (a light probe); dense strong texture cannot either (stripes, where the 80th percentile
// alone silenced half a sphere's rim).
Votes houghVotes(const Gradients& g, cv::Rect area) {
  Votes v;
  v.area = area;
  std::vector<float> strengths;
  strengths.reserve(std::size_t(area.width) * area.height);
  for (int y = area.y; y < area.y + area.height; ++y)
    for (int x = area.x; x < area.x + area.width; ++x) strengths.push_back(g.mag.at<float>(y, x));
  if (strengths.empty()) return v;
  auto percentile = [&](double p) {
    const auto q = strengths.begin() + static_cast<std::ptrdiff_t>((strengths.size() - 1) * p);
    std::nth_element(strengths.begin(), q, strengths.end());
    return *q;
  };
  const float strongest = *std::max_element(strengths.begin(), strengths.end());
  const float cap = percentile(0.97);
  const float floor = std::max(std::min(percentile(0.80), 0.1f * strongest), 0.02f * strongest);
  for (int y = area.y; y < area.y + area.height; ++y) {
    for (int x = area.x; x < area.x + area.width; ++x) {
      const float m = g.mag.at<float>(y, x);
      if (m < floor || !(m > 0)) continue;
      v.edges.push_back(float(x), float(y), g.gx.at<float>(y, x) / m, g.gy.at<float>(y, x) / m,
                        cap > 0 ? std::min(1.0f, m / cap) : 1.0f);
    }
  }
  return v;
}

// The circle Hough transform of `votes` for radius r (coarse pixels of its level), in `acc`
// (scratch of the area's size): the accumulator's `perRadius` strongest local maxima (each
// found maximum's neighbourhood of r/2 cleared before the next), scored by what a perfect
// circle of that radius reaches.
std::vector<Candidate> houghRadius(const Votes& votes, int r, int perRadius, cv::Mat& acc) {
  const cv::Rect& area = votes.area;
  acc.create(area.height, area.width, CV_32F);
  acc.setTo(0);
  houghVote(votes.edges, r, {acc.ptr<float>(), area.x, area.y, area.width, area.height});
  cv::GaussianBlur(acc, acc, cv::Size(5, 5), 1.0);
  AccumulatorPeaks peaks(acc);
  std::vector<Candidate> out;
  for (int m = 0; m < perRadius; ++m) {
    cv::Point at;
    const double value = peaks.strongest(&at);
    if (value <= 0) break;
    out.push_back({double(at.x + area.x), double(at.y + area.y), double(r), value / perfectCircle(r)});
    peaks.clearDisc(at, std::max(2, r / 2));
  }
  return out;
}

// The Hough transform at several scales: level l searches the radii of 24 to 48 of its own
// pixels on the median reduced 2^l times (level 0 from r0), so that every radius is searched
// on a few dozen accumulators of a size that suits it. Candidates in coarse pixels, sorted by
// score (ties in level, then radius order), so the result is identical at any thread count.
// The levels' edges are found side by side, then every (level, radius) is one task of a
// single parallel loop: level by level, the other core waited for each level's edges and for
// its last radius.
std::vector<Candidate> houghPyramid(const cv::Mat& coarse8, cv::Rect area, int r0, int r1, int perRadius,
                                    int threads) {
  struct Level {
    cv::Mat image;
    cv::Rect area;
    int scale = 1;
    std::vector<int> radii;
    Votes votes;
  };
  std::vector<Level> levels;
  cv::Mat level = coarse8;
  for (int l = 0, scale = 1; r0 <= r1; ++l, scale *= 2) {
    const int top = r1 / scale < 48 || level.cols < 96 || level.rows < 96 ? r1 / scale : 47;
    const int lo = std::max(l == 0 ? r0 : 24, 6);
    if (top >= lo) {
      const cv::Rect a(area.x / scale, area.y / scale, std::max(1, area.width / scale), std::max(1, area.height / scale));
      const cv::Rect inLevel = a & cv::Rect(0, 0, level.cols, level.rows);
      if (inLevel.width >= 8 && inLevel.height >= 8) {
        Level one{level, inLevel, scale, {}, {}};
        for (int r = lo; r <= top; ++r) one.radii.push_back(r);
        levels.push_back(std::move(one));
      }
    }
    if (top >= r1 / scale) break;
    r0 = 48 * scale;
    cv::Mat smaller;
    cv::resize(level, smaller, cv::Size((level.cols + 1) / 2, (level.rows + 1) / 2), 0, 0, cv::INTER_AREA);
    level = smaller;
  }
  const int workers = std::max(1, effectiveThreads(threads));
  parallelFor(levels.size(), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t l = b; l < e; ++l) levels[l].votes = houghVotes(gradients(levels[l].image), levels[l].area);
  });
  struct Task {
    std::size_t level;
    int r;
  };
  std::vector<Task> tasks;
  for (std::size_t l = 0; l < levels.size(); ++l)
    if (!levels[l].votes.edges.empty())
      for (int r : levels[l].radii) tasks.push_back({l, r});
  std::vector<std::vector<Candidate>> found(tasks.size());
  std::vector<std::vector<cv::Mat>> scratch(workers, std::vector<cv::Mat>(levels.size()));
  parallelForWorkers(tasks.size(), 1, workers, [&](int worker, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      found[i] = houghRadius(levels[tasks[i].level].votes, tasks[i].r, perRadius, scratch[worker][tasks[i].level]);
  });
  std::vector<Candidate> all;
  for (std::size_t l = 0, i = 0; l < levels.size(); ++l) {
    std::vector<Candidate> inLevel;
    for (; i < tasks.size() && tasks[i].level == l; ++i) inLevel.insert(inLevel.end(), found[i].begin(), found[i].end());
    std::stable_sort(inLevel.begin(), inLevel.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    const int scale = levels[l].scale;
    for (Candidate c : inLevel) {
      c.x = (c.x + 0.5) * scale - 0.5;
      c.y = (c.y + 0.5) * scale - 0.5;
      c.r *= scale;
      c.level = scale;
      all.push_back(c);
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  return all;
}

// Two candidates describe the same circle when their centres are within a quarter of the
// larger radius and their radii within a third of each other.
bool sameCircle(const Candidate& a, const Candidate& b) {
  const double r = std::max(a.r, b.r);
  return std::hypot(a.x - b.x, a.y - b.y) < 0.25 * r && std::min(a.r, b.r) > 0.75 * r;
}

// The candidates worth refining: the strongest distinct circles overall, and the strongest four
// of each octave of radius, so that a large sphere whose rim is partly faint (its stand, its own
// shadow) is tried even when the texture reflected in it gives many small strong circles.
std::vector<Candidate> distinctCandidates(const std::vector<Candidate>& sorted, std::size_t overall) {
  std::vector<Candidate> out;
  std::map<int, int> perOctave;
  for (const Candidate& c : sorted) {
    bool seen = false;
    for (const Candidate& d : out) seen = seen || sameCircle(c, d);
    if (seen) continue;
    const int octave = static_cast<int>(std::floor(std::log2(std::max(1.0, c.r))));
    if (out.size() < overall || perOctave[octave] < 4) {
      out.push_back(c);
      ++perOctave[octave];
    }
  }
  return out;
}

// `window` reduced `factor` times by area averaging (the last block row and column partial).
Image reduced(const Image& window, int factor) {
  if (factor <= 1) return window;
  cv::Mat from(window.height, window.width, CV_16U, const_cast<std::uint16_t*>(window.pixels.data()));
  Image out((window.width + factor - 1) / factor, (window.height + factor - 1) / factor, 1);
  cv::Mat to(out.height, out.width, CV_16U, out.pixels.data());
  cv::resize(from, to, to.size(), 0, 0, cv::INTER_AREA);
  return out;
}

// Whether the stack shows a sphere's highlights in a circle: in each image, the highlight
// (detectHighlight against the median) must be confident and lie within 0.75 of the radius (a
// light in front of the object); the positions must move from image to image (a spot that
// stays put is a reflection or a speck, not the light). evidence = the share of images with
// such a highlight; 0 when the positions all lie within 5 % of the radius of each other.
// A circle larger than kEvidenceRadius is judged on its window reduced to about that radius:
// the question is whether there is a highlight, not where to the pixel, and the images of a
// circle the size of the frame would otherwise cost as much as the rest of the search. The
// images are judged a few at a time, stopping once the answer cannot change.
double highlightEvidence(const StackMedian& median, const DetectedSphere& s, int threads) {
  const ImageStack& stack = median.stack();
  const std::size_t n = stack.size();
  if (n < 3) return 1;  // no median to compare with: the rim alone decides
  const Rect r = highlightWindow(s, stack.width(), stack.height());
  if (r.w <= 0) return 0;
  const int factor = std::max(1, static_cast<int>(std::ceil(s.r / kEvidenceRadius)));
  const Image around = reduced(median.window(r), factor);
  const DetectedSphere inWindow{(s.cx - r.x + 0.5) / factor - 0.5, (s.cy - r.y + 0.5) / factor - 0.5, s.r / factor,
                                s.confidence, 0};
  const std::size_t needed = static_cast<std::size_t>(std::ceil(kMinEvidence * n));
  const std::size_t chunk = std::max<std::size_t>(2, 2 * static_cast<std::size_t>(effectiveThreads(threads)));
  std::vector<std::optional<Point2>> at(n);
  std::size_t found = 0;
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t last = std::min(n, first + chunk);
    parallelFor(last - first, 1, effectiveThreads(threads), [&](std::size_t b, std::size_t e) {
      Image window(r.w, r.h, 1);
      for (std::size_t i = first + b; i < first + e; ++i) {
        stack.readWindow(static_cast<int>(i), r.x, r.y, r.x + r.w, r.y + r.h, window.pixels.data());
        const Highlight h = detectHighlight(reduced(window, factor), &around, 0, 0, inWindow, HighlightOptions());
        // Only a confident highlight counts (above the cap of a doubtful one, kMultipleCap).
        if (isUsable(h.flag) && h.confidence > HighlightLimits::kMultipleCap &&
            std::hypot(h.x - inWindow.cx, h.y - inWindow.cy) <= kFrontRadius * inWindow.r)
          at[i] = Point2{h.x, h.y};
      }
    });
    for (std::size_t i = first; i < last; ++i) found += at[i].has_value();
    if (found + (n - last) < needed) return double(found) / n;  // it cannot reach the minimum
  }
  std::vector<Point2> positions;
  for (const auto& p : at)
    if (p) positions.push_back(*p);
  double spread = 0;
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (std::size_t j = i + 1; j < positions.size(); ++j)
      spread = std::max(spread, std::hypot(positions[i].x - positions[j].x, positions[i].y - positions[j].y));
  if (spread < kMinMotion * inWindow.r) return 0;
  return double(found) / n;
}

// A glossy black sphere is much darker than its surroundings: the mean inside 0.8 r against the
// mean of the ring between 1.15 r and 1.4 r.
bool isDarkDisc(const StackMedian& median, const DetectedSphere& s) {
  double inside = 0, outside = 0;
  int nIn = 0, nOut = 0;
  const int x0 = std::max(0, static_cast<int>(s.cx - 1.4 * s.r)), x1 = std::min(median.width() - 1, static_cast<int>(s.cx + 1.4 * s.r));
  const int y0 = std::max(0, static_cast<int>(s.cy - 1.4 * s.r)), y1 = std::min(median.height() - 1, static_cast<int>(s.cy + 1.4 * s.r));
  const MedianWindow full = medianWindow(median, x0, y0, x1 + 1, y1 + 1);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double d = std::hypot(x - s.cx, y - s.cy) / s.r;
      if (d < 0.8) {
        inside += full.values.at<float>(y - full.y0, x - full.x0);
        ++nIn;
      } else if (d > 1.15 && d < 1.4) {
        outside += full.values.at<float>(y - full.y0, x - full.x0);
        ++nOut;
      }
    }
  }
  if (nIn == 0 || nOut == 0) return false;
  return inside / nIn < 0.6 * (outside / nOut);
}

}  // namespace

DetectedSphere fitVisibleRim(const StackMedian& rim, const DetectedSphere& given) {
  const double margin = std::max(kGivenRimMargin, kGivenRimMarginShare * given.r);
  DetectedSphere fitted = refineRim(rim, given.cx, given.cy, given.r, margin, true);
  fitted.byHand = true;
  fitted.evidence = 1;
  return fitted;
}

namespace {

std::string circleText(const DetectedSphere& s) {
  return fixedDecimals(s.cx, 0) + "," + fixedDecimals(s.cy, 0) + "," + fixedDecimals(s.r, 0);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> SphereDetectionOptions::toParameters() const {
  std::string r;
  for (const Rect& q : regions)
    r += (r.empty() ? "" : ";") + std::to_string(q.x) + "," + std::to_string(q.y) + "," +
         std::to_string(q.w) + "," + std::to_string(q.h);
  return {{"minRadius", formatNumber(minRadius)},       {"maxRadius", formatNumber(maxRadius)},
          {"regions", r},                               {"maxSpheres", std::to_string(maxSpheres)},
          {"minConfidence", formatNumber(minConfidence)}, {"coarseWidth", std::to_string(coarseWidth)}};
}

SphereDetectionOptions SphereDetectionOptions::fromParameters(
    const std::vector<std::pair<std::string, std::string>>& params) {
  SphereDetectionOptions o;
  for (const auto& [name, value] : params) {
    try {
      if (name == "minRadius") o.minRadius = std::stod(value);
      else if (name == "maxRadius") o.maxRadius = std::stod(value);
      else if (name == "maxSpheres") o.maxSpheres = std::stoi(value);
      else if (name == "minConfidence") o.minConfidence = std::stod(value);
      else if (name == "coarseWidth") o.coarseWidth = std::stoi(value);
      else if (name == "regions") {
        for (const std::string& region : split(value, ';')) {
          const auto v = split(region, ',');
          if (v.size() != 4) throw std::invalid_argument(region);
          o.regions.push_back({std::stoi(v[0]), std::stoi(v[1]), std::stoi(v[2]), std::stoi(v[3])});
        }
      } else {
        throw Error(ErrorKind::Input, name, kStep, "is not a parameter of sphere detection");
      }
    } catch (const std::logic_error&) {
      throw Error(ErrorKind::Input, name + "=" + value, kStep, "is not a valid value");
    }
  }
  if (o.minRadius < 3 || o.coarseWidth < 100 || o.maxSpheres < 1)
    throw Error(ErrorKind::Input, "", kStep, "sphere detection parameters out of range");
  return o;
}

std::vector<DetectedSphere> detectSpheres(const Image& median, const SphereDetectionOptions& o) {
  if (median.channels != 1 || median.empty())
    throw Error(ErrorKind::Internal, "", kStep, "needs a one-channel median image");
  // The median of a one-image stack is that image; with no other image to compare it with,
  // the rim alone decides (highlightEvidence).
  return detectSpheres(StackMedian(MemoryImageStack({median}), o.coarseWidth, o.threads), o);
}

std::vector<DetectedSphere> detectSpheres(const StackMedian& median, const SphereDetectionOptions& o) {
  return detectSpheres(median, median, o);
}

std::vector<DetectedSphere> detectSpheres(const StackMedian& median, const StackMedian& rim,
                                          const SphereDetectionOptions& o) {
  if (rim.factor() != median.factor() || rim.width() != median.width() || rim.height() != median.height())
    throw Error(ErrorKind::Internal, "", kStep, "the rim's stack quantile and the median differ in size");
  if (median.factor() != StackMedian::factorFor(median.width(), o.coarseWidth))
    throw Error(ErrorKind::Internal, "", kStep, "the median was reduced for another coarse width");
  const cv::Mat coarse = medianToFloat(rim.coarse());
  double maxValue = 0;
  cv::minMaxLoc(coarse, nullptr, &maxValue);
  const double scale = median.factor();
  cv::Mat coarse8;
  coarse.convertTo(coarse8, CV_8U, maxValue > 0 ? 255.0 / maxValue : 1.0);
  // A sphere may fill nine tenths of the frame's height (and be cut by its edge).
  const double maxRadius = o.maxRadius > 0 ? o.maxRadius : std::min(median.width(), median.height()) / 2.0;
  // Below 6 coarse pixels a circle is a handful of accumulator cells: noise, not a sphere.
  const int r0 = std::max(6, static_cast<int>(std::floor(o.minRadius / scale)));
  auto toFull = [&](Candidate c) {
    return Candidate{(c.x + 0.5) * scale - 0.5, (c.y + 0.5) * scale - 0.5, c.r * scale, c.score, c.level};
  };

  // Each distinct candidate is refined (its rim fitted at full resolution: confidence, the
  // share of the rim that is a clean edge) and, when the rim holds, checked for highlights that
  // move with the light (evidence). The best (confidence x evidence) are taken first, skipping
  // any that overlaps one taken: a reflection in a sphere shows the moving highlight in few
  // images, a circle around a sphere has a weaker rim than the sphere. `tried` collects, for
  // the message, the first few that did not pass and why.
  //
  // The evidence costs most (every image read around the circle), and most candidates never
  // need it: they are taken in the order of their scores, a candidate's confidence bounding
  // its score from above (evidence <= 1), so a candidate's evidence is measured only when its
  // bound puts it next; one that overlaps a sphere already taken is skipped unmeasured, as it
  // would have been skipped measured. The spheres taken are those of measuring every
  // candidate and sorting by score (ties in candidate order). On a generated 36 x 1200x800
  // capture, 2 of the 7 candidates with a clean rim were measured.
  //
  // The refusal names at most three circles, each once (candidates that refine to the same
  // circle, within a pixel, are one), and only circles whose centre is in the frame: those the
  // user could give back with --sphere.
  std::vector<DetectedSphere> named;
  auto noteTried = [&](std::vector<std::string>& tried, const DetectedSphere& s, const std::string& why) {
    if (tried.size() >= 3 || !(s.cx >= 0 && s.cy >= 0 && s.cx <= median.width() - 1 && s.cy <= median.height() - 1))
      return;
    for (const DetectedSphere& n : named)
      if (std::abs(n.cx - s.cx) <= 1 && std::abs(n.cy - s.cy) <= 1 && std::abs(n.r - s.r) <= 1) return;
    named.push_back(s);
    tried.push_back(circleText(s) + " (" + why + ")");
  };
  // What became of a candidate: not a circle (dropped unnamed), a rim too weak, waiting for its
  // evidence (its score bounded by its confidence), too little evidence, no dark disc (dropped
  // unnamed), scored, or done with (taken or skipped).
  enum class Standing { NotCircle, WeakRim, Waiting, LittleEvidence, NotDark, Scored, Done };
  struct Checked {
    DetectedSphere s;
    Standing standing = Standing::Waiting;
    double key = 0;  // the score when scored, its bound (the confidence) while waiting
  };
  auto overlapsAny = [](const DetectedSphere& c, const std::vector<DetectedSphere>& taken) {
    for (const DetectedSphere& s : taken)
      if (std::hypot(s.cx - c.cx, s.cy - c.cy) < s.r + c.r) return true;
    return false;
  };
  // The margin a candidate's rim is searched within: its Hough level's uncertainty, at full resolution.
  auto rimMargin = [&](const Candidate& c) { return 3 * scale * c.level + 4; };
  auto select = [&](const std::vector<Candidate>& candidates, std::size_t wanted, std::vector<DetectedSphere>& into,
                    std::vector<std::string>& tried) {
    // The rims, each on a thread of its own: the refinements are independent and give the same
    // circles in any order.
    std::vector<Checked> checked(candidates.size());
    // The full-resolution rim every candidate's first pass reads made first, all tiles at once:
    // made by each refinement in turn, under the median's lock, the other core mostly waited.
    // Only the tiles near each circle (rimReads): no value inside a large circle enters its
    // refinement (on the 36 x 1200x800 generated capture, 133 of the frame's 247 tiles instead of
    // 156). Whatever else reads a window of it (the median's, when it is the rim's too) computes
    // the tiles it lacks when it asks.
    std::vector<Rect> reads;
    for (const Candidate& c : candidates) {
      const Candidate f = toFull(c);
      const std::vector<Rect> near = rimReads(rim, f.x, f.y, f.r, rimMargin(c));
      reads.insert(reads.end(), near.begin(), near.end());
    }
    rim.prepare(reads);
    // The largest circles first (their windows cost most): the search's candidates end with the
    // per-octave ones, the largest last, which one core refined alone while the other waited.
    std::vector<std::size_t> order(candidates.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return candidates[a].r > candidates[b].r; });
    parallelFor(candidates.size(), 1, effectiveThreads(o.threads), [&](std::size_t b, std::size_t e) {
      for (std::size_t k = b; k < e; ++k) {
        const std::size_t i = order[k];
        const Candidate f = toFull(candidates[i]);
        Checked& c = checked[i];
        c.s = refineRim(rim, f.x, f.y, f.r, rimMargin(candidates[i]));
        if (!(c.s.r >= 3)) c.standing = Standing::NotCircle;
        else if (c.s.confidence < o.minConfidence) c.standing = Standing::WeakRim;
        else c.key = c.s.confidence;
      }
    });
    for (;;) {
      // The next candidate in score order: the highest key, ties to the earlier candidate.
      Checked* next = nullptr;
      for (Checked& c : checked)
        if ((c.standing == Standing::Waiting || c.standing == Standing::Scored) && (!next || c.key > next->key))
          next = &c;
      if (!next || into.size() >= wanted) break;
      if (next->standing == Standing::Scored) {
        next->standing = Standing::Done;
        if (!overlapsAny(next->s, into)) into.push_back(next->s);
        continue;
      }
      if (overlapsAny(next->s, into)) {  // skipped when its turn came, whatever its score
        next->standing = Standing::Done;
        continue;
      }
      DetectedSphere& s = next->s;
      s.evidence = highlightEvidence(median, s, o.threads);
      // Without images to compare (a single image as the median), a black sphere is told from
      // round texture by its darkness alone.
      if (median.stack().size() < 3 && !isDarkDisc(median, s)) {
        next->standing = Standing::NotDark;
      } else if (s.evidence < kMinEvidence) {
        next->standing = Standing::LittleEvidence;
      } else {
        next->standing = Standing::Scored;
        next->key = s.confidence * s.evidence;
      }
    }
    // The refusals in candidate order. Only a search that took nothing names them, and then every
    // candidate was measured.
    for (const Checked& c : checked) {
      if (c.standing == Standing::WeakRim) noteTried(tried, c.s, "rim " + fixedDecimals(c.s.confidence, 2));
      else if (c.standing == Standing::LittleEvidence)
        noteTried(tried, c.s, "a moving highlight in " + std::to_string(std::lround(c.s.evidence * 100)) + " % of the images");
    }
  };

  std::vector<DetectedSphere> found;
  std::vector<std::string> tried;
  if (!o.regions.empty()) {
    for (const Rect& region : o.regions) {
      cv::Rect area(static_cast<int>(region.x / scale), static_cast<int>(region.y / scale),
                    static_cast<int>(std::ceil(region.w / scale)), static_cast<int>(std::ceil(region.h / scale)));
      area &= cv::Rect(0, 0, coarse.cols, coarse.rows);
      if (area.width < 8 || area.height < 8)
        throw Error(ErrorKind::Usage, "--sphere-roi", kStep, "the region is outside the image or too small");
      const int r1 = std::min(static_cast<int>(maxRadius / scale), std::max(area.width, area.height) / 2 + 2);
      std::vector<DetectedSphere> one;
      select(distinctCandidates(houghPyramid(coarse8, area, r0, r1, 3, o.threads), 6), 1, one, tried);
      found.insert(found.end(), one.begin(), one.end());
    }
  } else {
    const int r1 = static_cast<int>(maxRadius / scale);
    select(distinctCandidates(houghPyramid(coarse8, cv::Rect(0, 0, coarse.cols, coarse.rows), r0, r1, 4, o.threads),
                              kCandidates),
           static_cast<std::size_t>(o.maxSpheres), found, tried);
  }
  if (found.empty()) {
    std::string seen;
    for (const std::string& t : tried) seen += (seen.empty() ? "" : "; ") + t;
    throw Error(ErrorKind::Input, "", kStep,
                std::string("no sphere was found: no circle in the photographs has both a clean rim and a "
                            "highlight that moves from image to image") +
                    (seen.empty() ? "" : " (the strongest circles, as CX,CY,R: " + seen + ")") +
                    ". If the capture has a sphere, restrict the search to it with --sphere-roi X,Y,W,H (repeat for "
                    "each sphere); if that fails, give its circle with --sphere CX,CY,R --reason \"...\"");
  }
  // Spheres from left to right, so their indices do not depend on detection order.
  std::sort(found.begin(), found.end(), [](const DetectedSphere& a, const DetectedSphere& b) {
    return a.cx != b.cx ? a.cx < b.cx : a.cy < b.cy;
  });
  return found;
}

}  // namespace surrogate::hrti
