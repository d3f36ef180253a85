#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "fit/fit.h"
#include "fit/normals.h"
#include "fit/ptm_math.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "synthetic.h"

using namespace surrogate;
using namespace surrogate::fit;
using test::Light;
namespace fs = std::filesystem;

namespace {
double maxDiff(const Image& rendered, const Image& captured) {
  double worst = 0;
  for (std::size_t i = 0; i < rendered.pixels.size(); ++i)
    worst = std::max(worst, std::fabs(rendered.pixels[i] / 257.0 - captured.pixels[i] / 257.0));
  return worst;
}

std::array<double, 3> decodeNormal(const Image& im, int x, int y) {
  return {im.at(x, y, 0) / 65535.0 * 2 - 1, im.at(x, y, 1) / 65535.0 * 2 - 1,
          im.at(x, y, 2) / 65535.0 * 2 - 1};
}

// A bump of luminance whose maximum is at the normal's (nx, ny):
// L = c - k ((lu - nx)^2 + (lv - ny)^2).
std::array<double, 6> bump(double nx, double ny, double c = 200, double k = 40) {
  return {-k, -k, 0, 2 * k * nx, 2 * k * ny, c - k * (nx * nx + ny * ny)};
}
}  // namespace

TEST_CASE("render: a PTM and an HSH re-rendered at a captured light reproduce the photograph") {
  const auto lights = test::spreadLights(30);
  const auto truth = test::randomPtm(20, 12, 4);
  const auto stack = test::ptmImages(truth, lights);
  FitOptions o;
  o.basis = Basis::PtmRgb;
  const auto ptm = fitPtm(stack, lights, o);
  const auto htruth = test::randomHsh(20, 12, 9, 8);
  const auto hstack = test::hshImages(htruth, lights);
  o.basis = Basis::Hsh3;
  const auto hsh = fitHsh(hstack, lights, o);
  for (int i : {0, 7, 29}) {
    CHECK(maxDiff(render(ptm, lights[i]), stack.image(i)) <= 1.5);
    CHECK(maxDiff(render(hsh, lights[i]), hstack.image(i)) <= 1.5);
  }
  const Image r = render(ptm, lights[0]);
  CHECK(r.bitsPerSample == 8);
  CHECK(r.channels == 3);
  CHECK(r.pixels[5] % 257 == 0);
}

TEST_CASE("render: gain 1 equals no gain, the gain keeps the maximum's position and value") {
  const auto a = bump(0.3, -0.2);
  double lu0, lv0;
  REQUIRE(ptmMaximum(a, &lu0, &lv0));
  CHECK(lu0 == Approx(0.3));
  CHECK(lv0 == Approx(-0.2));
  CHECK(applyDiffuseGain(a, 1.0, lu0, lv0) == a);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 200; ++t) {
    const PtmCoefficients p = {-20 + 15 * u(rng), -20 + 15 * u(rng), 4 * u(rng), 30 * u(rng),
                               30 * u(rng), 150 + 50 * u(rng)};
    double x0, y0;
    if (!ptmMaximum(p, &x0, &y0)) continue;
    for (double g : {0.5, 2.0, 4.0}) {
      const auto q = applyDiffuseGain(p, g, x0, y0);
      double x1, y1;
      CHECK(ptmMaximum(q, &x1, &y1) == (g > 0));
      CHECK(x1 == Approx(x0).margin(1e-9));
      CHECK(y1 == Approx(y0).margin(1e-9));
      CHECK(evaluatePtm(q, x0, y0) == Approx(evaluatePtm(p, x0, y0)));
      CHECK(q[0] == Approx(g * p[0]));
    }
  }
  const auto lights = test::spreadLights(20);
  const auto stack = test::ptmImages(test::randomPtm(8, 6, 5), lights);
  const auto ptm = fitPtm(stack, lights, FitOptions{});
  RenderOptions one;
  one.diffuseGain = 1.0;
  CHECK(render(ptm, {0.3, 0.2, 0.9}, one).pixels == render(ptm, {0.3, 0.2, 0.9}).pixels);
  RenderOptions two;
  two.diffuseGain = 2.0;
  CHECK(render(ptm, {0.3, 0.2, 0.9}, two).pixels != render(ptm, {0.3, 0.2, 0.9}).pixels);
  two.threads = 1;
  RenderOptions twoThreads = two;
  twoThreads.threads = 2;
  CHECK(render(ptm, {0.9, 0, 0.4}, two).pixels == render(ptm, {0.9, 0, 0.4}, twoThreads).pixels);
}

TEST_CASE("render: options are validated, HSH has no diffuse gain, extrapolation moves the light") {
  const auto lights = test::spreadLights(20);
  const auto stack = test::ptmImages(test::randomPtm(4, 3, 6), lights);
  const auto ptm = fitPtm(stack, lights, FitOptions{});
  CHECK_THROWS_AS(render(ptm, {0, 0, 0}), Error);
  RenderOptions bad;
  bad.diffuseGain = -1;
  CHECK_THROWS_AS(render(ptm, {0, 0, 1}, bad), Error);
  FitOptions h;
  h.basis = Basis::Hsh2;
  const auto hsh = fitHsh(stack, lights, h);
  RenderOptions gain;
  gain.diffuseGain = 2;
  CHECK_THROWS_AS(render(hsh, {0, 0, 1}, gain), Error);
  RenderOptions far;
  far.extrapolation = 1.8;
  CHECK(render(ptm, {1, 0, 0.2}, far).pixels != render(ptm, {1, 0, 0.2}).pixels);
  RenderOptions spec;
  spec.specular = true;
  CHECK(render(ptm, {0, 0, 1}, spec).pixels != render(ptm, {0, 0, 1}).pixels);
  CHECK(render(hsh, {0, 0, 1}, spec).pixels.size() == 4 * 3 * 3);
}

TEST_CASE("normals: a PTM's maximum gives the normal, no maximum falls back and is counted") {
  const auto lights = test::spreadLights(30);
  const int w = 6, h = 5;
  std::vector<std::array<double, 2>> tilt;
  std::vector<Image> images;
  for (int p = 0; p < w * h; ++p) tilt.push_back({-0.4 + 0.8 * (p % w) / (w - 1), 0.5 - 0.2 * (p / w)});
  for (const Light& l : lights) {
    Image im(w, h, 3);
    for (int p = 0; p < w * h; ++p) {
      const double v = test::evalPtm(bump(tilt[p][0], tilt[p][1]), l);
      for (int c = 0; c < 3; ++c) im.pixels[p * 3 + c] = test::sample255(v);
    }
    images.push_back(std::move(im));
  }
  const MemoryImageStack stack(std::move(images));
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb}) {
    FitOptions o;
    o.basis = b;
    const auto ptm = fitPtm(stack, lights, o);
    int fallback = -1;
    const Image n = normalMap(ptm, &fallback);
    CHECK(fallback == 0);
    CHECK(n.bitsPerSample == 16);
    for (int p = 0; p < w * h; ++p) {
      const auto v = decodeNormal(n, p % w, p / w);
      CHECK(v[0] == Approx(tilt[p][0]).margin(0.02));
      CHECK(v[1] == Approx(tilt[p][1]).margin(0.02));
      CHECK(v[2] == Approx(std::sqrt(1 - tilt[p][0] * tilt[p][0] - tilt[p][1] * tilt[p][1])).margin(0.02));
    }
    const Image albedo = albedoMap(ptm);
    CHECK(albedo.bitsPerSample == 8);
    CHECK(albedo.at(0, 0, 0) > 0);
  }
  // A polynomial without a maximum (a0 > 0) uses the Lambertian fallback.
  bool fallback = false;
  const auto nf = ptmNormal({10, -20, 0, 30, 0, 100}, &fallback);
  CHECK(fallback);
  CHECK(nf[0] > 0.15);  // brighter towards +x
  CHECK(nf[2] > 0);
}

TEST_CASE("normals: HSH of a Lambertian surface gives its normal") {
  const auto lights = test::spreadLights(40);
  const std::array<double, 3> n0 = {0.25, -0.15, std::sqrt(1 - 0.25 * 0.25 - 0.15 * 0.15)};
  std::vector<Image> images;
  for (const Light& l : lights) {
    Image im(3, 2, 3);
    const double v = 200 * std::max(0.0, n0[0] * l[0] + n0[1] * l[1] + n0[2] * l[2]);
    for (auto& s : im.pixels) s = test::sample255(v);
    images.push_back(std::move(im));
  }
  const MemoryImageStack stack(std::move(images));
  FitOptions o;
  o.basis = Basis::Hsh3;
  const auto hsh = fitHsh(stack, lights, o);
  int fallback = -1;
  const Image n = normalMap(hsh, &fallback);
  CHECK(fallback == 0);
  const auto v = decodeNormal(n, 1, 1);
  CHECK(v[0] == Approx(n0[0]).margin(0.08));
  CHECK(v[1] == Approx(n0[1]).margin(0.08));
  const Image albedo = albedoMap(hsh);
  CHECK(albedo.at(1, 1, 0) / 257 == Approx(200).margin(25));
}

TEST_CASE("relightable: files written and reopened render like the objects") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-relight";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto lights = test::spreadLights(20);
  const auto stack = test::ptmImages(test::randomPtm(7, 5, 7), lights);
  const auto ptm = fitPtm(stack, lights, FitOptions{});
  FitOptions h;
  h.basis = Basis::Hsh3;
  const auto hsh = fitHsh(stack, lights, h);
  formats::writePtm(dir / "a.ptm", ptm);
  formats::writeRti(dir / "a.rti", hsh);
  const auto p = openRelightable(dir / "a.ptm");
  const auto r = openRelightable(dir / "a.rti");
  CHECK(p->basis() == "ptm-lrgb");
  CHECK(r->basis() == "hsh3");
  CHECK(p->width() == 7);
  CHECK(p->render({0.2, 0.3, 0.9}, {}).pixels == render(ptm, {0.2, 0.3, 0.9}).pixels);
  CHECK(r->render({0.2, 0.3, 0.9}, {}).pixels == render(hsh, {0.2, 0.3, 0.9}).pixels);
  CHECK(r->normalMap().pixels == normalMap(hsh).pixels);
  CHECK_THROWS_AS(openRelightable(dir / "missing.ptm"), Error);
  fs::remove_all(dir);
}

TEST_CASE("fit throughput (prints Mpixel-images/s)", "[.][bench]") {
  const int w = 1000, h = 1000, n = 60;
  const auto lights = test::spreadLights(n);
  std::vector<Image> images;
  for (int i = 0; i < n; ++i) {
    Image im(w, h, 3);
    for (std::size_t p = 0; p < im.pixels.size(); ++p)
      im.pixels[p] = static_cast<std::uint16_t>((p * 2654435761u + i * 40503u) & 0xFFFF);
    images.push_back(std::move(im));
  }
  const MemoryImageStack stack(std::move(images));
  for (Basis b : {Basis::PtmLrgb, Basis::PtmRgb, Basis::Hsh3}) {
    for (int threads : {1, 2}) {
      FitOptions o;
      o.basis = b;
      o.threads = threads;
      o.memoryBudgetBytes = 64ull << 20;  // forces two passes (the stack is 360 MB)
      FitStatistics s;
      const auto t0 = std::chrono::steady_clock::now();
      if (isPtm(b)) fitPtm(stack, lights, o, &s); else fitHsh(stack, lights, o, &s);
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cout << basisName(b) << " threads=" << threads << " passes=" << s.passes << ": "
                << sec << " s, " << (double(w) * h * n / 1e6) / sec << " Mpixel-images/s\n";
    }
  }
}

namespace {

// A PTM of the given size, scales and biases whose coefficient bytes (and, for LRGB, colour
// bytes) come from a linear congruential sequence started at `seed`.
formats::PtmFile randomPtm(formats::PtmFile::Format format, int width, int height, const std::array<double, 6>& scale,
                           const std::array<int, 6>& bias, std::uint32_t seed) {
  formats::PtmFile ptm;
  ptm.format = format;
  ptm.width = width;
  ptm.height = height;
  ptm.scale = scale;
  ptm.bias = bias;
  const int channels = format == formats::PtmFile::Format::Lrgb ? 1 : 3;
  const auto next = [&seed] { return static_cast<std::uint8_t>((seed = seed * 1664525u + 1013904223u) >> 24); };
  ptm.coefficients.resize(ptm.texels() * 6 * channels);
  for (auto& b : ptm.coefficients) b = next();
  if (channels == 1) {
    ptm.rgb.resize(ptm.texels() * 3);
    for (auto& b : ptm.rgb) b = next();
  }
  return ptm;
}

// The luminance polynomial of texel (x, y), written out: an LRGB PTM's own, an RGB PTM's the
// mean of its three channels' coefficients.
PtmCoefficients luminanceOf(const formats::PtmFile& ptm, int x, int y) {
  const int channels = ptm.format == formats::PtmFile::Format::Lrgb ? 1 : 3;
  PtmCoefficients lum{};
  for (int c = 0; c < channels; ++c)
    for (int t = 0; t < 6; ++t)
      lum[t] += channels == 1 ? ptm.coefficient(x, y, t, 0) : ptm.coefficient(x, y, t, c) / 3.0;
  return lum;
}

}  // namespace

TEST_CASE("render: the specular preview is the one std::pow gives, for any weights and exponent") {
  // src/fit/render.cpp takes nh^e by repeated squaring and calls pow only where a sample is
  // within a hair of a rounding step: every sample must be the one of the formula with pow.
  for (const auto format : {formats::PtmFile::Format::Lrgb, formats::PtmFile::Format::Rgb}) {
    const formats::PtmFile ptm = randomPtm(format, 97, 61, {0.9, 0.8, 0.7, 1.1, 1.2, 1.3},
                                           {200, 190, 128, 120, 130, 20}, 12345);
    const int channels = format == formats::PtmFile::Format::Lrgb ? 1 : 3;
    struct Case {
      std::array<double, 3> light;
      double kd, ks, exponent;
    };
    for (const Case& k : {Case{{0.6, 0.6, 0.3}, 0.7, 0.3, 40}, Case{{-0.2, 0.1, 1}, 0.5, 1.7, 1},
                          Case{{0.9, -0.3, 0.1}, 0.7, 0.3, 64}, Case{{0.1, 0.4, 0.8}, 0.7, 0.3, 7},
                          Case{{0.1, 0.4, 0.8}, 0.7, 0.3, 2.5}, Case{{0.3, 0.2, 0.9}, 0.7, 0.3, 65},
                          Case{{0, 0, 1}, 1, 0, 40}, Case{{0, 0, -1}, 0.7, 0.3, 40}}) {
      RenderOptions o;
      o.specular = true;
      o.kd = k.kd;
      o.ks = k.ks;
      o.specularExponent = k.exponent;
      const Image r = render(ptm, k.light, o);
      const double norm = std::sqrt(k.light[0] * k.light[0] + k.light[1] * k.light[1] + k.light[2] * k.light[2]);
      const double lx = k.light[0] / norm, ly = k.light[1] / norm, lz = k.light[2] / norm;
      const double h[3] = {lx, ly, lz + 1.0};
      const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
      int differing = 0;
      for (int y = 0; y < ptm.height; ++y)
        for (int x = 0; x < ptm.width; ++x) {
          const auto n = ptmNormal(luminanceOf(ptm, x, y));
          const double nh = std::max(0.0, (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / len);
          const double spec = len == 0 ? 0 : o.ks * 255.0 * std::pow(nh, o.specularExponent);
          for (int c = 0; c < 3; ++c) {
            PtmCoefficients a;
            for (int t = 0; t < 6; ++t) a[t] = ptm.coefficient(x, y, t, channels == 1 ? 0 : c);
            const double diffuse = evaluatePtm(a, lx, ly);
            const std::size_t texel = static_cast<std::size_t>(y) * ptm.width + x;
            const double d = channels == 1 ? ptm.rgb[texel * 3 + c] * diffuse / 255.0 : diffuse;
            const double v = o.kd * d + spec;
            const double clamped = v > 0 ? std::min(v, 255.0) : 0.0;  // detail::toByte
            const int rounded = static_cast<int>(clamped) + (clamped - static_cast<int>(clamped) >= 0.5 ? 1 : 0);
            if (r.at(x, y, c) != rounded * 257) ++differing;
          }
        }
      INFO("exponent " << k.exponent << ", ks " << k.ks);
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("normals: a PTM's normal and albedo maps, together or apart, are those of each texel's polynomial") {
  // src/fit/normals.cpp makes both maps in one pass with its coefficients decoded by table.
  for (const auto format : {formats::PtmFile::Format::Lrgb, formats::PtmFile::Format::Rgb}) {
    const formats::PtmFile ptm = randomPtm(format, 53, 37, {0.5, 0.6, 0.7, 1.1, 1.2, 1.3},
                                           {180, 170, 128, 120, 130, 20}, 777);
    const int channels = format == formats::PtmFile::Format::Lrgb ? 1 : 3;
    int fallback = -1, fallbackTogether = -1;
    const Image normals = normalMap(ptm, &fallback, 2), albedo = albedoMap(ptm, 2);
    Image normalsTogether, albedoTogether;
    normalAndAlbedoMaps(ptm, &normalsTogether, &albedoTogether, &fallbackTogether, 2);
    CHECK(normalsTogether.pixels == normals.pixels);
    CHECK(albedoTogether.pixels == albedo.pixels);
    CHECK(fallbackTogether == fallback);
    int expectedFallback = 0, differing = 0;
    const auto encode = [](double v, double top) {  // detail::roundClamped
      const double c = v > 0 ? std::min(v, top) : 0.0;
      return static_cast<int>(c) + (c - static_cast<int>(c) >= 0.5 ? 1 : 0);
    };
    for (int y = 0; y < ptm.height; ++y)
      for (int x = 0; x < ptm.width; ++x) {
        const PtmCoefficients lum = luminanceOf(ptm, x, y);
        bool usedFallback = false;
        const auto n = ptmNormal(lum, &usedFallback);
        expectedFallback += usedFallback ? 1 : 0;
        for (int c = 0; c < 3; ++c) {
          PtmCoefficients a;
          for (int t = 0; t < 6; ++t) a[t] = ptm.coefficient(x, y, t, channels == 1 ? 0 : c);
          const std::size_t texel = static_cast<std::size_t>(y) * ptm.width + x;
          const double v = channels == 1 ? ptm.rgb[texel * 3 + c] * evaluatePtm(lum, n[0], n[1]) / 255.0
                                         : evaluatePtm(a, n[0], n[1]);
          if (normals.at(x, y, c) != encode((n[c] + 1.0) / 2.0 * 65535.0, 65535.0)) ++differing;
          if (albedo.at(x, y, c) != encode(v, 255.0) * 257) ++differing;
        }
      }
    CHECK(fallback == expectedFallback);
    CHECK(fallback > 0);
    CHECK(differing == 0);
  }
}

TEST_CASE("render: the plain LRGB picture is each texel's colour times its luminance, at any width") {
  // src/fit/render.cpp writes it four samples at a time (AVX2) and the rest one by one.
  for (const int width : {1, 5, 97}) {
    const formats::PtmFile ptm = randomPtm(formats::PtmFile::Format::Lrgb, width, 23, {0.9, 0.8, 0.7, 1.1, 1.2, 1.3},
                                           {200, 190, 128, 120, 130, 20}, 4242);
    const std::array<double, 3> light{0.6, -0.4, 0.5};
    const double norm = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    const Image r = render(ptm, light, {});
    int differing = 0;
    for (int y = 0; y < ptm.height; ++y)
      for (int x = 0; x < ptm.width; ++x) {
        const double l = evaluatePtm(luminanceOf(ptm, x, y), light[0] / norm, light[1] / norm);
        for (int c = 0; c < 3; ++c) {
          const double v = ptm.rgb[(static_cast<std::size_t>(y) * ptm.width + x) * 3 + c] * l / 255.0;
          const double clamped = v > 0 ? std::min(v, 255.0) : 0.0;  // detail::toByte
          const int rounded = static_cast<int>(clamped) + (clamped - static_cast<int>(clamped) >= 0.5 ? 1 : 0);
          if (r.at(x, y, c) != rounded * 257) ++differing;
        }
      }
    INFO("width " << width);
    CHECK(differing == 0);
  }
}
