// Pre-processing: the options as the carrier records them, the automatic crop rectangle, the
// grey-region gains, and the stack views the fit reads (crop, gain tables, area reduction).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/stack.h"
#include "pipeline/decoded_stack.h"
#include "stages/preprocess.h"
#include "stages/stack_views.h"

using namespace surrogate;
using namespace surrogate::stages;

namespace {

// Two 3-channel images whose sample (x, y, c) is a known function of position.
std::shared_ptr<MemoryImageStack> ramps(int w, int h, Transfer transfer = Transfer::Srgb) {
  std::vector<Image> images;
  for (int i = 0; i < 2; ++i) {
    Image im(w, h, 3);
    im.transfer = transfer;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) im.at(x, y, c) = static_cast<std::uint16_t>((x * 7 + y * 131 + c * 1000 + i * 3) % 65536);
    images.push_back(im);
  }
  return std::make_shared<MemoryImageStack>(images);
}

Image readAll(const ImageStack& s, int index) {
  Image im(s.width(), s.height(), s.channels());
  s.readRows(index, 0, s.height(), im.pixels.data());
  return im;
}

ErrorKind kindOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  return ErrorKind::Internal;
}

}  // namespace

TEST_CASE("crop, resize and white-balance options round-trip through their carrier parameters") {
  const CropOptions c = CropOptions::fromText("10,20,300,200");
  CHECK(CropOptions::fromParameters(c.toParameters()).rect.text() == "10,20,300,200");
  const CropOptions a = CropOptions::fromText("auto");
  CHECK(CropOptions::fromParameters(a.toParameters()).method == "auto");
  CHECK(CropOptions::fromParameters(a.toParameters()).margin == 0.25);

  const ResizeOptions f = ResizeOptions::fromText("0.5");
  CHECK(ResizeOptions::fromParameters(f.toParameters()).outputSize(400, 300) == std::make_pair(200, 150));
  const ResizeOptions s = ResizeOptions::fromText("120x90");
  CHECK(ResizeOptions::fromParameters(s.toParameters()).outputSize(400, 300) == std::make_pair(120, 90));

  const WhiteBalanceOptions r = WhiteBalanceOptions::fromText("region:5,6,7,8");
  CHECK(WhiteBalanceOptions::fromParameters(r.toParameters()).region.text() == "5,6,7,8");
  const WhiteBalanceOptions m = WhiteBalanceOptions::fromText("multipliers:1.5,1,0.75");
  CHECK(WhiteBalanceOptions::fromParameters(m.toParameters()).multipliers == std::array<double, 3>{1.5, 1, 0.75});
}

TEST_CASE("bad pre-processing options are usage errors naming the option") {
  for (const char* bad : {"0,0,0,10", "0,0,10,0", "-1,0,10,10", "1,2,3", "a,b,c,d"}) {
    INFO(bad);
    try {
      CropOptions::fromText(bad, "--crop");
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.file().rfind("--crop", 0) == 0);
    }
  }
  for (const char* bad : {"0", "-0.5", "1.5", "0x10", "abc"})
    CHECK(kindOf([&] { ResizeOptions::fromText(bad); }) == ErrorKind::Usage);
  CHECK(kindOf([] { ResizeOptions::fromText("500x10").outputSize(400, 300); }) == ErrorKind::Usage);
  for (const char* bad : {"multipliers:1,-1,1", "multipliers:0,1,1", "multipliers:1,1", "region:0,0,0,0", "grey"}) {
    INFO(bad);
    try {
      WhiteBalanceOptions::fromText(bad, "--wb");
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.file().rfind("--wb", 0) == 0);
    }
  }
  CHECK(kindOf([] { CropOptions::fromParameters({{"method", "user"}}); }) == ErrorKind::Usage);
  CHECK(kindOf([] { WhiteBalanceOptions::fromParameters({{"mode", "grey"}}); }) == ErrorKind::Usage);
}

TEST_CASE("the automatic crop is the largest rectangle clear of every sphere and its margin") {
  // No spheres: the whole frame.
  CHECK(largestClearRectangle(400, 300, {}, 0.25).text() == "0,0,400,300");
  // One sphere at the right: everything left of it.
  const PixelRect r = largestClearRectangle(400, 300, {{350, 150, 40}}, 0.25);
  CHECK(r.text() == "0,0,300,300");  // 350 - 50 = 300: the margin is a quarter of the radius
  // A sphere at the top-left corner: the larger of the strip below and the strip to the right.
  const PixelRect c = largestClearRectangle(400, 300, {{30, 30, 20}}, 0);
  CHECK(c.area() == std::max(400LL * (300 - 51), (400LL - 51) * 300));
  // Whatever the layout, no pixel of the result is within the enlarged radius of a sphere.
  const std::vector<Circle> two = {{100, 80, 30}, {320, 220, 25}};
  const PixelRect t = largestClearRectangle(400, 300, two, 0.5);
  REQUIRE(t.area() > 0);
  for (const Circle& s : two) {
    const double nx = std::clamp(s.cx, double(t.x), double(t.x + t.width - 1));
    const double ny = std::clamp(s.cy, double(t.y), double(t.y + t.height - 1));
    CHECK(std::hypot(nx - s.cx, ny - s.cy) > s.r * 1.5);
  }
  // A sphere filling the frame leaves nothing.
  CHECK(largestClearRectangle(100, 100, {{50, 50, 100}}, 0).area() == 0);
}

TEST_CASE("grey-region gains make the median region neutral with green fixed at one") {
  const std::vector<std::array<double, 3>> means = {
      {0.2, 0.4, 0.1}, {0.25, 0.5, 0.2}, {0.9, 0.1, 0.9}};  // the last is an outlier
  const auto g = greyRegionGains(means, "--wb-region");
  CHECK(g[0] == 0.4 / 0.25);
  CHECK(g[1] == 1.0);
  CHECK(g[2] == 0.4 / 0.2);
  CHECK(medianOf({4, 1, 3, 2}) == 2.5);
  CHECK(kindOf([] { greyRegionGains({{0, 0.5, 0.5}}, "--wb-region"); }) == ErrorKind::Input);
}

TEST_CASE("a crop view reads exactly the rectangle's samples") {
  const auto stack = ramps(50, 40);
  const CropStack crop(stack, {5, 7, 20, 10});
  CHECK(crop.width() == 20);
  CHECK(crop.height() == 10);
  const Image im = readAll(crop, 1);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) REQUIRE(im.at(x, y, c) == stack->image(1).at(x + 5, y + 7, c));
  // Reading a sub-band gives the same rows as reading everything.
  std::vector<std::uint16_t> band(3 * 20 * 3);
  crop.readRows(1, 4, 7, band.data());
  CHECK(std::equal(band.begin(), band.end(), im.pixels.begin() + 4 * 20 * 3));
}

TEST_CASE("unit gains with the same encoding leave every sample unchanged, and linear output decodes sRGB") {
  const auto stack = ramps(30, 20);
  const TableStack same(stack, gainTables({1, 1, 1}, Transfer::Srgb, Transfer::Srgb), Transfer::Srgb);
  CHECK(readAll(same, 0).pixels == stack->image(0).pixels);
  const TableStack lin(stack, gainTables({1, 1, 1}, Transfer::Srgb, Transfer::Linear), Transfer::Linear);
  CHECK(lin.transfer() == Transfer::Linear);
  const Image l = readAll(lin, 0);
  for (std::size_t i = 0; i < l.pixels.size(); i += 97)
    CHECK(l.pixels[i] == std::lround(toLinear(stack->image(0).pixels[i], Transfer::Srgb) * 65535));
  // Gains multiply linear light and clip at full scale.
  const TableStack g(stack, gainTables({2, 1, 0.5}, Transfer::Linear, Transfer::Linear), Transfer::Linear);
  const Image gi = readAll(g, 0);
  CHECK(gi.at(1, 0, 0) == std::min(65535, 2 * stack->image(0).at(1, 0, 0)));
  CHECK(gi.at(1, 0, 2) == std::lround(stack->image(0).at(1, 0, 2) * 0.5));
}

TEST_CASE("area reduction averages whole pixels exactly and keeps a uniform image uniform") {
  // A uniform sRGB image stays the same value at any factor (no drift from the encoding).
  std::vector<Image> flat;
  for (std::uint16_t v : {std::uint16_t(0), std::uint16_t(1234), std::uint16_t(40000), std::uint16_t(65535)}) {
    Image im(37, 23, 3);
    std::fill(im.pixels.begin(), im.pixels.end(), v);
    flat.push_back(im);
  }
  const auto flatStack = std::make_shared<MemoryImageStack>(flat);
  const AreaResizeStack reduced(flatStack, 11, 7);
  for (int i = 0; i < 4; ++i) {
    const Image im = readAll(reduced, i);
    CHECK(std::all_of(im.pixels.begin(), im.pixels.end(), [&](std::uint16_t v) { return v == flat[i].pixels[0]; }));
  }
  // Halving a linear image: each output sample is the rounded mean of a 2x2 block.
  const auto lin = ramps(40, 30, Transfer::Linear);
  const AreaResizeStack half(lin, 20, 15);
  const Image h = readAll(half, 0);
  const Image& src = lin->image(0);
  for (int y = 0; y < 15; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) {
        const long sum = long(src.at(2 * x, 2 * y, c)) + src.at(2 * x + 1, 2 * y, c) +
                         src.at(2 * x, 2 * y + 1, c) + src.at(2 * x + 1, 2 * y + 1, c);
        REQUIRE(std::abs(long(h.at(x, y, c)) - sum / 4.0) <= 0.5);
      }
  // Bands read separately give the same rows.
  std::vector<std::uint16_t> band(2 * 20 * 3);
  half.readRows(0, 6, 8, band.data());
  CHECK(std::equal(band.begin(), band.end(), h.pixels.begin() + 6 * 20 * 3));
}

TEST_CASE("area reduction by a non-integer factor matches a floating-point reference in linear light") {
  const auto srgb = ramps(40, 30);
  const AreaResizeStack reduced(srgb, 13, 11);
  const Image out = readAll(reduced, 1);
  const Image& in = srgb->image(1);
  const double sx = 40.0 / 13, sy = 30.0 / 11;
  for (int Y = 0; Y < 11; ++Y)
    for (int X = 0; X < 13; ++X)
      for (int c = 0; c < 3; ++c) {
        double sum = 0, area = 0;
        for (int y = 0; y < 30; ++y) {
          const double wy = std::max(0.0, std::min(y + 1.0, (Y + 1) * sy) - std::max(double(y), Y * sy));
          if (wy <= 0) continue;
          for (int x = 0; x < 40; ++x) {
            const double wx = std::max(0.0, std::min(x + 1.0, (X + 1) * sx) - std::max(double(x), X * sx));
            if (wx <= 0) continue;
            sum += toLinear(in.at(x, y, c), Transfer::Srgb) * wx * wy;
            area += wx * wy;
          }
        }
        const double mean = sum / area;
        // The sample whose linear value is nearest the reference mean, give or take one code.
        int best = 0;
        for (int v = 1; v < 65536; ++v)
          if (std::abs(toLinear(std::uint16_t(v), Transfer::Srgb) - mean) <
              std::abs(toLinear(std::uint16_t(best), Transfer::Srgb) - mean))
            best = v;
        REQUIRE(std::abs(int(out.at(X, Y, c)) - best) <= 1);
      }
}

TEST_CASE("the luminance view gives Rec. 709 luminance of 8- and 16-bit stacks, in memory or in a file") {
  using pipeline::DecodedStack;
  constexpr int kCount = 3, kW = 29, kH = 11;
  // Reference: the Rec. 709 weights in 1/65536 units (13933, 46871, 4732; docs/hrti-math.md),
  // applied to 16-bit samples (8-bit ones times 257) with the sum rounded half up.
  const auto reference = [](std::uint32_t r, std::uint32_t g, std::uint32_t b) {
    return static_cast<std::uint16_t>((13933 * r + 46871 * g + 4732 * b + 32768) / 65536);
  };
  for (const auto placement : {DecodedStack::Placement::Memory, DecodedStack::Placement::TemporaryFile}) {
    INFO("placement " << (placement == DecodedStack::Placement::Memory ? "memory" : "file"));
    auto narrow = std::make_shared<DecodedStack>(kCount, DecodedStack::Format{kW, kH, 3, 1, Transfer::Srgb}, placement);
    auto wide = std::make_shared<DecodedStack>(kCount, DecodedStack::Format{kW, kH, 3, 2, Transfer::Linear}, placement);
    std::vector<std::vector<std::uint8_t>> bytes(kCount);
    std::vector<std::vector<std::uint16_t>> words(kCount);
    for (int i = 0; i < kCount; ++i) {
      bytes[i].resize(std::size_t(kW) * kH * 3);
      words[i].resize(bytes[i].size());
      for (std::size_t k = 0; k < bytes[i].size(); ++k) {
        bytes[i][k] = static_cast<std::uint8_t>(k * 37 + i * 101);
        words[i][k] = static_cast<std::uint16_t>(k * 7919 + i * 4001);
      }
      narrow->store(i, bytes[i]);
      wide->store(i, words[i]);
    }
    const LuminanceStack narrowLum(narrow), wideLum(wide);
    REQUIRE(narrowLum.channels() == 1);
    const int y0 = 3, y1 = 9;
    for (int i = 0; i < kCount; ++i) {
      std::vector<std::uint16_t> a(std::size_t(kW) * (y1 - y0)), b(a.size());
      narrowLum.readRows(i, y0, y1, a.data());
      wideLum.readRows(i, y0, y1, b.data());
      for (std::size_t p = 0; p < a.size(); ++p) {
        const std::size_t k = (std::size_t(y0) * kW + p) * 3;
        CHECK(a[p] == reference(bytes[i][k] * 257u, bytes[i][k + 1] * 257u, bytes[i][k + 2] * 257u));
        CHECK(b[p] == reference(words[i][k], words[i][k + 1], words[i][k + 2]));
      }
      // A window (the highlight search's read): the same luminance at each of its pixels, with
      // windows at both edges, one column wide, and empty.
      for (const auto& [x0, x1] : std::vector<std::pair<int, int>>{{0, 7}, {5, 22}, {20, kW}, {13, 14}, {9, 9}}) {
        INFO("columns " << x0 << " to " << x1);
        const std::size_t span = std::size_t(x1 - x0);
        std::vector<std::uint16_t> wa(span * (y1 - y0) + 1, 7), wb(wa.size(), 7);
        narrowLum.readWindow(i, x0, y0, x1, y1, wa.data());
        wideLum.readWindow(i, x0, y0, x1, y1, wb.data());
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) {
            const std::size_t k = (std::size_t(y) * kW + x) * 3, at = std::size_t(y - y0) * span + (x - x0);
            CHECK(wa[at] == reference(bytes[i][k] * 257u, bytes[i][k + 1] * 257u, bytes[i][k + 2] * 257u));
            CHECK(wb[at] == reference(words[i][k], words[i][k + 1], words[i][k + 2]));
          }
        CHECK(wa.back() == 7);  // nothing written past the window
        CHECK(wb.back() == 7);
      }
    }
    std::vector<std::uint16_t> out(64);
    CHECK_THROWS(narrowLum.readWindow(0, 5, 0, kW + 1, 1, out.data()));
    CHECK_THROWS(narrowLum.readWindow(0, -1, 0, 3, 1, out.data()));
  }
}

TEST_CASE("an image stack's default window is the columns of its rows") {
  const auto stack = ramps(13, 6);
  const Image all = readAll(*stack, 1);
  std::vector<std::uint16_t> window(std::size_t(4) * 3 * 3);
  stack->readWindow(1, 2, 1, 6, 4, window.data());
  for (int y = 1; y < 4; ++y)
    for (int x = 2; x < 6; ++x)
      for (int c = 0; c < 3; ++c) CHECK(window[((std::size_t(y - 1) * 4) + (x - 2)) * 3 + c] == all.at(x, y, c));
}
