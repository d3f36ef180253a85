// Held-out quality (fit/held_out.h) against closed forms: PSNR of a uniform offset, SSIM of
// identical and of constant images (Wang et al. 2004, eq. 13 with the structure terms at their
// limit), the spread of the lights left out, and the nearest-photograph baseline.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/error.h"
#include "fit/held_out.h"

using namespace surrogate;
using namespace surrogate::fit;

namespace {

Image constant(int w, int h, int channels, double value255) {
  Image im(w, h, channels);
  for (auto& v : im.pixels) v = static_cast<std::uint16_t>(std::lround(value255 * 257));
  return im;
}

Image noise(int w, int h, unsigned seed) {
  Image im(w, h, 3);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(20, 230);
  for (auto& v : im.pixels) v = static_cast<std::uint16_t>(257 * u(rng));
  return im;
}

std::vector<std::array<double, 3>> ring(int n, double elevationDegrees) {
  const double pi = std::acos(-1.0), e = elevationDegrees * pi / 180;
  std::vector<std::array<double, 3>> out;
  for (int i = 0; i < n; ++i) {
    double a = 2 * pi * i / n;
    out.push_back({std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)});
  }
  return out;
}

}  // namespace

TEST_CASE("PSNR of a uniform offset d is 20 log10(255 / d)", "[held_out]") {
  Image photo = noise(40, 30, 1);
  for (int d : {1, 5, 20}) {
    Image relit = photo;
    for (auto& v : relit.pixels) v = static_cast<std::uint16_t>(v + 257 * d);
    HeldOutScore s = compareImages(relit, photo);
    CHECK(s.mse == Approx(d * d).epsilon(1e-12));
    CHECK(s.psnr == Approx(20 * std::log10(255.0 / d)).epsilon(1e-12));
  }
  // 16-bit samples are read as value / 257: an offset of 514 is 2 levels.
  Image relit = photo;
  for (auto& v : relit.pixels) v = static_cast<std::uint16_t>(v + 514);
  CHECK(compareImages(relit, photo).psnr == Approx(20 * std::log10(255.0 / 2)).epsilon(1e-12));
}

TEST_CASE("identical images score 100 dB and SSIM 1", "[held_out]") {
  Image photo = noise(64, 48, 2);
  HeldOutScore s = compareImages(photo, photo);
  CHECK(s.psnr == 100);
  CHECK(s.mse == 0);
  CHECK(s.ssim == Approx(1).margin(1e-6));
}

TEST_CASE("SSIM of two constant images is the luminance term of Wang et al.", "[held_out]") {
  // sigma_x = sigma_y = sigma_xy = 0: SSIM = (2 m1 m2 + C1) / (m1^2 + m2^2 + C1), C1 = (0.01 * 255)^2.
  const double c1 = (0.01 * 255) * (0.01 * 255);
  for (auto [m1, m2] : {std::pair{100.0, 120.0}, std::pair{30.0, 200.0}, std::pair{3.0, 0.0}}) {
    HeldOutScore s = compareImages(constant(32, 32, 3, m1), constant(32, 32, 3, m2));
    CHECK(s.ssim == Approx((2 * m1 * m2 + c1) / (m1 * m1 + m2 * m2 + c1)).margin(1e-5));
    CHECK(s.psnr == Approx(20 * std::log10(255.0 / std::fabs(m1 - m2))).epsilon(1e-12));
  }
  // Grey images too.
  CHECK(compareImages(constant(16, 16, 1, 50), constant(16, 16, 1, 60)).ssim ==
        Approx((2 * 50.0 * 60 + c1) / (2500.0 + 3600 + c1)).margin(1e-5));
}

TEST_CASE("images of different sizes are refused", "[held_out]") {
  CHECK_THROWS_AS(compareImages(constant(8, 8, 3, 1), constant(8, 9, 3, 1)), Error);
  CHECK_THROWS_AS(compareImages(constant(8, 8, 3, 1), constant(8, 8, 1, 1)), Error);
}

TEST_CASE("a set pools the mean squared errors, not the decibels", "[held_out]") {
  HeldOutScore a, b;
  a.mse = 1, a.ssim = 0.9;
  b.mse = 4, b.ssim = 0.7;
  HeldOutScore m = meanScore({a, b});
  CHECK(m.mse == Approx(2.5));
  CHECK(m.psnr == Approx(10 * std::log10(255.0 * 255.0 / 2.5)));
  CHECK(m.ssim == Approx(0.8));
  CHECK_THROWS_AS(meanScore({}), Error);
}

TEST_CASE("the held-out lights are spread: every other light of a ring", "[held_out]") {
  auto lights = ring(8, 30);
  CHECK(chooseHeldOut(lights, 4) == std::vector<int>{0, 2, 4, 6});
  CHECK(chooseHeldOut(lights, 2) == std::vector<int>{0, 4});
  CHECK(chooseHeldOut(lights, 4) == chooseHeldOut(lights, 4));
  auto twelve = ring(12, 45);
  // Farthest points: 0, its opposite 6, then 3 and 9 at 90 degrees from both.
  CHECK(chooseHeldOut(twelve, 4) == std::vector<int>{0, 3, 6, 9});
}

TEST_CASE("the first light left out is the one nearest the lights mean direction", "[held_out]") {
  auto lights = ring(6, 20);
  lights.push_back({0, 0, 1});  // index 6, the zenith, is nearest the mean
  CHECK(chooseHeldOut(lights, 1) == std::vector<int>{6});
  // Then the ring's lights, all 70 degrees from the zenith, tie: the lowest index, 0. Then 2, 3
  // and 4 are all 70 degrees from the nearest chosen light (the zenith) and 1 and 5 only 56
  // from light 0: the lowest of the ties, 2.
  CHECK(chooseHeldOut(lights, 3) == std::vector<int>{0, 2, 6});
}

TEST_CASE("chooseHeldOut refuses counts outside 1 to lights - 1", "[held_out]") {
  auto lights = ring(8, 30);
  for (int bad : {0, -1, 8, 9}) {
    try {
      chooseHeldOut(lights, bad);
      FAIL("accepted " << bad);
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.file() == "--holdout");
    }
  }
}

TEST_CASE("the nearest-photograph blend at a captured light is that photograph", "[held_out]") {
  auto lights = ring(8, 40);
  std::vector<Image> photos;
  for (int i = 0; i < 8; ++i) photos.push_back(noise(24, 20, 10 + i));
  MemoryImageStack stack(photos);
  for (int i : {0, 3, 7}) {
    Image out = nearestPhotographBlend(stack, lights, lights[i], 3);
    CHECK(out.pixels == photos[i].pixels);
    CHECK(out.channels == 3);
  }
}

TEST_CASE("midway between two lights the blend of two is their mean", "[held_out]") {
  // Two lights at equal angles get equal weights 1 / (angle + 1e-6): the rounded mean.
  auto lights = ring(4, 30);
  std::vector<Image> photos{constant(8, 8, 3, 100), constant(8, 8, 3, 140), constant(8, 8, 3, 0),
                            constant(8, 8, 3, 0)};
  MemoryImageStack stack(photos);
  auto mid = ring(8, 30)[1];  // between lights 0 and 1
  Image out = nearestPhotographBlend(stack, lights, mid, 2);
  for (auto v : out.pixels) CHECK(v == 257 * 120);
}

TEST_CASE("nearestPhotographBlend refuses mismatched lights and a zero light", "[held_out]") {
  auto lights = ring(4, 30);
  MemoryImageStack stack({constant(4, 4, 3, 1), constant(4, 4, 3, 2), constant(4, 4, 3, 3)});
  CHECK_THROWS_AS(nearestPhotographBlend(stack, lights, {0, 0, 1}), Error);
  lights.pop_back();
  CHECK_THROWS_AS(nearestPhotographBlend(stack, lights, {0, 0, 0}), Error);
}
