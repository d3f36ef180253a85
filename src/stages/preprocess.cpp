#include "stages/preprocess.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/text.h"

namespace surrogate::stages {

namespace {

[[noreturn]] void refuse(const std::string& origin, const std::string& what, const std::string& why) {
  throw Error(ErrorKind::Usage, origin + (what.empty() ? "" : " " + what), "pre-processing", why);
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(sep, start);
    out.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  return out;
}

bool parseDouble(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return *end == '\0' && std::isfinite(v);
}

bool parseInt(const std::string& s, int& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  const long l = std::strtol(s.c_str(), &end, 10);
  if (*end != '\0' || l < -1000000000L || l > 1000000000L) return false;
  v = static_cast<int>(l);
  return true;
}

PixelRect parseRect(const std::string& text, const std::string& origin, const std::string& what) {
  const auto parts = split(text, ',');
  int v[4];
  bool ok = parts.size() == 4;
  for (std::size_t i = 0; ok && i < 4; ++i) ok = parseInt(parts[i], v[i]);
  if (!ok) refuse(origin, what + text, "needs four whole numbers X,Y,W,H (pixels: left, top, width, height)");
  PixelRect r{v[0], v[1], v[2], v[3]};
  if (r.x < 0 || r.y < 0) refuse(origin, what + text, "the rectangle's left and top must be 0 or more");
  if (r.width <= 0 || r.height <= 0)
    refuse(origin, what + text, "the rectangle needs a width and height of at least one pixel");
  return r;
}

std::array<double, 3> parseGains(const std::string& text, const std::string& origin, const std::string& what) {
  const auto parts = split(text, ',');
  std::array<double, 3> g{};
  bool ok = parts.size() == 3;
  for (std::size_t i = 0; ok && i < 3; ++i) ok = parseDouble(parts[i], g[i]);
  if (!ok) refuse(origin, what + text, "needs three numbers R,G,B (the gain of each channel)");
  for (double v : g)
    if (!(v > 0) || v > 1000)
      refuse(origin, what + text, "each gain must be a positive number (above 0, at most 1000)");
  return g;
}

void requireOneOf(const std::string& origin, const std::string& name, const std::string& value,
                  std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* a : allowed) {
    if (value == a) return;
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  refuse(origin, name + "=" + value, "unknown value; use one of: " + list);
}

}  // namespace

std::string PixelRect::text() const {
  return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(width) + "," +
         std::to_string(height);
}

// ---- Crop -----------------------------------------------------------------------------------

Parameters CropOptions::toParameters() const {
  Parameters p = {{"method", method}};
  if (method == "user") p.push_back({"rectangle", rect.text()});
  else p.push_back({"margin", formatNumber(margin)});
  return p;
}

CropOptions CropOptions::fromParameters(const Parameters& params, const std::string& origin) {
  CropOptions o;
  bool hasRect = false;
  for (const auto& [name, value] : params) {
    if (name == "method") {
      requireOneOf(origin, name, value, {"user", "auto"});
      o.method = value;
    } else if (name == "rectangle") {
      o.rect = parseRect(value, origin, "rectangle=");
      hasRect = true;
    } else if (name == "margin") {
      if (!parseDouble(value, o.margin) || o.margin < 0 || o.margin > 10)
        refuse(origin, "margin=" + value, "needs a fraction of the sphere radius from 0 to 10");
    } else {
      refuse(origin, name + "=" + value, "is not a parameter of Crop (method, rectangle, margin)");
    }
  }
  if (o.method == "user" && !hasRect)
    refuse(origin, "", "a crop needs its rectangle X,Y,W,H, or \"auto\"");
  return o;
}

CropOptions CropOptions::fromText(const std::string& text, const std::string& origin) {
  CropOptions o;
  if (text == "auto") {
    o.method = "auto";
  } else {
    o.method = "user";
    o.rect = parseRect(text, origin, "");
  }
  return o;
}

// ---- Resize ---------------------------------------------------------------------------------

std::pair<int, int> ResizeOptions::outputSize(int w, int h, const std::string& origin) const {
  int ow = width, oh = height;
  if (factor > 0) {
    ow = std::max(1, static_cast<int>(std::lround(w * factor)));
    oh = std::max(1, static_cast<int>(std::lround(h * factor)));
  }
  if (ow > w || oh > h)
    refuse(origin, std::to_string(ow) + "x" + std::to_string(oh),
           "is larger than the " + std::to_string(w) + "x" + std::to_string(h) +
               " images it resizes; resizing only reduces (enlarging adds no information)");
  if (ow < kMinResizeSide || oh < kMinResizeSide) {
    const std::string given = factor > 0 ? formatNumber(factor) : std::to_string(width) + "x" + std::to_string(height);
    char least[32];
    std::snprintf(least, sizeof least, "%.3g", std::ceil(1000.0 * kMinResizeSide / std::min(w, h)) / 1000);
    refuse(origin, given,
           "would reduce the " + std::to_string(w) + "x" + std::to_string(h) + " images to " + std::to_string(ow) +
               "x" + std::to_string(oh) + " pixels; the result needs at least " + std::to_string(kMinResizeSide) +
               " pixels per side: give a factor of at least " + least + " or a size WxH");
  }
  return {ow, oh};
}

Parameters ResizeOptions::toParameters() const {
  Parameters p;
  if (factor > 0) p.push_back({"factor", formatNumber(factor)});
  else p.push_back({"size", std::to_string(width) + "x" + std::to_string(height)});
  p.push_back({"filter", filter});
  return p;
}

namespace {
void parseResizeValue(ResizeOptions& o, const std::string& text, const std::string& origin,
                      const std::string& what) {
  const auto x = text.find('x');
  if (x != std::string::npos) {
    if (!parseInt(text.substr(0, x), o.width) || !parseInt(text.substr(x + 1), o.height) ||
        o.width <= 0 || o.height <= 0)
      refuse(origin, what + text, "needs a target size WxH in whole pixels, e.g. 640x480");
    if (o.width < kMinResizeSide || o.height < kMinResizeSide)
      refuse(origin, what + text, "needs a target size of at least " + std::to_string(kMinResizeSide) + "x" +
                                      std::to_string(kMinResizeSide) + " pixels, e.g. 640x480");
    o.factor = 0;
    return;
  }
  if (!parseDouble(text, o.factor) || !(o.factor > 0) || o.factor > 1)
    refuse(origin, what + text,
           "needs a scale factor above 0 and at most 1 (e.g. 0.5), or a target size WxH");
}
}  // namespace

ResizeOptions ResizeOptions::fromParameters(const Parameters& params, const std::string& origin) {
  ResizeOptions o;
  bool given = false;
  for (const auto& [name, value] : params) {
    if (name == "factor") {
      if (value.find('x') != std::string::npos) refuse(origin, "factor=" + value, "needs a number");
      parseResizeValue(o, value, origin, "factor=");
      given = true;
    } else if (name == "size") {
      if (value.find('x') == std::string::npos) refuse(origin, "size=" + value, "needs WxH");
      parseResizeValue(o, value, origin, "size=");
      given = true;
    } else if (name == "filter") {
      requireOneOf(origin, name, value, {"area"});
    } else {
      refuse(origin, name + "=" + value, "is not a parameter of Resize (factor, size, filter)");
    }
  }
  if (!given) refuse(origin, "", "a resize needs a scale factor or a target size WxH");
  return o;
}

ResizeOptions ResizeOptions::fromText(const std::string& text, const std::string& origin) {
  ResizeOptions o;
  parseResizeValue(o, text, origin, "");
  return o;
}

// ---- WhiteBalance ---------------------------------------------------------------------------

Parameters WhiteBalanceOptions::toParameters() const {
  Parameters p = {{"mode", mode}};
  if (mode == "region") p.push_back({"region", region.text()});
  if (mode == "multipliers")
    p.push_back({"multipliers", formatNumber(multipliers[0]) + "," + formatNumber(multipliers[1]) +
                                    "," + formatNumber(multipliers[2])});
  p.push_back({"outputSpace", outputSpace});
  return p;
}

WhiteBalanceOptions WhiteBalanceOptions::fromParameters(const Parameters& params,
                                                        const std::string& origin) {
  WhiteBalanceOptions o;
  bool hasRegion = false, hasMultipliers = false;
  for (const auto& [name, value] : params) {
    if (name == "mode") {
      requireOneOf(origin, name, value, {"as-shot", "region", "multipliers"});
      o.mode = value;
    } else if (name == "region") {
      o.region = parseRect(value, origin, "region=");
      hasRegion = true;
    } else if (name == "multipliers") {
      o.multipliers = parseGains(value, origin, "multipliers=");
      hasMultipliers = true;
    } else if (name == "outputSpace") {
      requireOneOf(origin, name, value, {"srgb", "linear"});
      o.outputSpace = value;
    } else {
      refuse(origin, name + "=" + value,
             "is not a parameter of WhiteBalance (mode, region, multipliers, outputSpace)");
    }
  }
  if (o.mode == "region" && !hasRegion) refuse(origin, "", "white balance from a region needs region=X,Y,W,H");
  if (o.mode == "multipliers" && !hasMultipliers)
    refuse(origin, "", "white balance by multipliers needs multipliers=R,G,B");
  return o;
}

WhiteBalanceOptions WhiteBalanceOptions::fromText(const std::string& text, const std::string& origin) {
  WhiteBalanceOptions o;
  if (text == "as-shot") {
    o.mode = "as-shot";
  } else if (text.rfind("region:", 0) == 0) {
    o.mode = "region";
    o.region = parseRect(text.substr(7), origin, "");
  } else if (text.rfind("multipliers:", 0) == 0) {
    o.mode = "multipliers";
    o.multipliers = parseGains(text.substr(12), origin, "");
  } else {
    refuse(origin, text, "use as-shot, region:X,Y,W,H (a grey area) or multipliers:R,G,B");
  }
  return o;
}

// ---- Computations ---------------------------------------------------------------------------

PixelRect largestClearRectangle(int width, int height, const std::vector<Circle>& circles,
                                double margin) {
  struct Box {
    int x0, y0, x1, y1;  // excluded pixels [x0, x1) x [y0, y1)
  };
  std::vector<Box> boxes;
  std::vector<int> lefts = {0}, rights = {width}, tops = {0}, bottoms = {height};
  for (const Circle& c : circles) {
    const double r = c.r * (1 + margin);
    const Box b{std::clamp(static_cast<int>(std::floor(c.cx - r)), 0, width),
                std::clamp(static_cast<int>(std::floor(c.cy - r)), 0, height),
                std::clamp(static_cast<int>(std::ceil(c.cx + r)) + 1, 0, width),
                std::clamp(static_cast<int>(std::ceil(c.cy + r)) + 1, 0, height)};
    if (b.x0 >= b.x1 || b.y0 >= b.y1) continue;  // entirely outside the frame
    boxes.push_back(b);
    lefts.push_back(b.x1);
    rights.push_back(b.x0);
    tops.push_back(b.y1);
    bottoms.push_back(b.y0);
  }
  // The largest empty rectangle touches the frame or an obstacle on each side, so the
  // candidates' edges are the frame's and the obstacles' edges.
  for (auto* v : {&lefts, &rights, &tops, &bottoms}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  PixelRect best;
  for (int y0 : tops)
    for (int x0 : lefts)
      for (int y1 : bottoms)
        for (int x1 : rights) {
          if (x1 <= x0 || y1 <= y0) continue;
          const PixelRect r{x0, y0, x1 - x0, y1 - y0};
          if (r.area() <= best.area()) continue;
          bool clear = true;
          for (const Box& b : boxes)
            clear = clear && !(x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1);
          if (clear) best = r;
        }
  return best;
}

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::array<double, 3> greyRegionGains(const std::vector<std::array<double, 3>>& means,
                                      const std::string& origin) {
  std::array<double, 3> m{};
  for (int c = 0; c < 3; ++c) {
    std::vector<double> v;
    for (const auto& im : means) v.push_back(im[c]);
    m[c] = medianOf(v);
  }
  if (!(m[0] > 0 && m[1] > 0 && m[2] > 0))
    throw Error(ErrorKind::Input, origin, "white balance",
                "the grey region is black in at least one colour channel in most images; give a "
                "region on a lit, neutral grey or white surface");
  return {m[1] / m[0], 1.0, m[1] / m[2]};
}

}  // namespace surrogate::stages
