// Golden files, (b) fitted: Surrogate's fitPtm / fitHsh of photographs of a scene no model
// reproduces exactly, written to .ptm and .rti, read and re-rendered by the independent code
// (independent_format.h) and compared with an unquantised least-squares fit made here.
// test_independent_reader.cpp says more.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "core/temp_dir.h"
#include "fit/fit.h"
#include "fit/quantise.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "independent_support.h"
#include "../fit/reference_basis.h"

namespace fs = std::filesystem;
namespace ref = surrogate::reference;
using namespace surrogate;
using namespace golden;

TEST_CASE("Surrogate's fitted .ptm and .rti, read and re-rendered here, match an unquantised least-squares fit") {
  // The proof of docs/formats.md ("Testing a writer"): photographs of a scene no model
  // reproduces exactly, fitted by Surrogate and written to a file; that file read by the
  // independent reader and rendered from the closed form at every captured light is within a
  // fraction of a dB (PSNR against the photographs) of the same model fitted here, in double,
  // without quantisation.
  surrogate::TempDir temp("independent-fit");
  const Scene scene;
  const auto lights = captureLights(36);
  std::vector<std::vector<double>> photo;  // [light][(y*w + x)*3 + c], 0..255 units
  const MemoryImageStack stack = scene.photographs(lights, &photo);
  const std::size_t samples = lights.size() * scene.w * scene.h * 3;

  SECTION("RGB PTM") {
    fit::FitOptions o;
    o.basis = fit::Basis::PtmRgb;
    const fs::path file = temp.path() / "fit.ptm";
    formats::writePtm(file, fit::fitPtm(stack, lights, o));
    const indep::Ptm p = indep::readPtm(slurp(file));
    REQUIRE(!p.lrgb);
    std::vector<std::vector<double>> rows;
    for (const Light& l : lights) {
      const auto uv = ref::ptmArguments(l[0], l[1], l[2]);
      rows.push_back({});
      for (int k = 0; k < 6; ++k) rows.back().push_back(ref::ptmTerm(k, uv[0], uv[1]));
    }
    double errFile = 0, errLs = 0, worst = 0;
    for (int y = 0; y < scene.h; ++y)
      for (int x = 0; x < scene.w; ++x)
        for (int c = 0; c < 3; ++c) {
          std::vector<double> s;
          for (const auto& im : photo) s.push_back(im[(y * scene.w + x) * 3 + c]);
          const auto a = leastSquares(rows, s);
          for (std::size_t i = 0; i < lights.size(); ++i) {
            const Light& l = lights[i];
            const double file = std::clamp(indep::ptmValue(p, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
            double ls = 0;
            for (int k = 0; k < 6; ++k) ls += a[k] * rows[i][k];
            ls = std::clamp(ls, 0.0, 255.0);
            errFile += (file - s[i]) * (file - s[i]);
            errLs += (ls - s[i]) * (ls - s[i]);
            worst = std::max(worst, std::fabs(file - ls));
          }
        }
    const double bound = quantisationBound(rows, {p.scale.begin(), p.scale.end()});
    INFO("PSNR of the file " << psnr(errFile, samples) << " dB, unquantised fit "
                             << psnr(errLs, samples) << " dB, largest difference " << worst
                             << " (quantisation bound " << bound << ")");
    CHECK(psnr(errLs, samples) < 60);  // the scene is not a PTM: quantisation is not all
    CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
    CHECK(worst <= bound);
  }

  SECTION("LRGB PTM") {
    const fs::path file = temp.path() / "fit-lrgb.ptm";
    formats::writePtm(file, fit::fitPtm(stack, lights, fit::FitOptions{}));
    const indep::Ptm p = indep::readPtm(slurp(file));
    REQUIRE(p.lrgb);
    // relight's LRGB definition: colour = the mean colour weighted by
    // w_i = max(0, 0.25 - (asin(lz)/(pi/2) - 0.5)^2), stored as bytes (checked against the
    // file's to within 1, then the file's bytes are used); luminance
    // L_i = 255 (R_i + G_i + B_i) / (sum of the colour bytes), fitted by least squares.
    std::vector<std::vector<double>> rows;
    std::vector<double> weight;
    double total = 0;
    for (const Light& l : lights) {
      const auto uv = ref::ptmArguments(l[0], l[1], l[2]);
      rows.push_back({});
      for (int k = 0; k < 6; ++k) rows.back().push_back(ref::ptmTerm(k, uv[0], uv[1]));
      const double e = std::asin(l[2]) / (ref::kPi / 2) - 0.5;
      weight.push_back(std::max(0.0, 0.25 - e * e));
      total += weight.back();
    }
    double errFile = 0, errLs = 0, worst = 0;
    int colourOff = 0;
    for (int y = 0; y < scene.h; ++y)
      for (int x = 0; x < scene.w; ++x) {
        std::array<double, 3> colour{};
        double colourSum = 0;
        for (int c = 0; c < 3; ++c) {
          for (std::size_t i = 0; i < lights.size(); ++i)
            colour[c] += weight[i] * photo[i][(y * scene.w + x) * 3 + c] / total;
          if (std::fabs(colour[c] - p.colour[y][x][c]) > 1) ++colourOff;
          colour[c] = p.colour[y][x][c];
          colourSum += colour[c];
        }
        std::vector<double> lum;
        for (const auto& im : photo)
          lum.push_back(255.0 * (im[(y * scene.w + x) * 3] + im[(y * scene.w + x) * 3 + 1] +
                                 im[(y * scene.w + x) * 3 + 2]) / colourSum);
        const auto a = leastSquares(rows, lum);
        for (std::size_t i = 0; i < lights.size(); ++i) {
          const Light& l = lights[i];
          double lsL = 0;
          for (int k = 0; k < 6; ++k) lsL += a[k] * rows[i][k];
          for (int c = 0; c < 3; ++c) {
            const double s = photo[i][(y * scene.w + x) * 3 + c];
            const double file = std::clamp(indep::ptmValue(p, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
            const double ls = std::clamp(colour[c] * lsL / 255.0, 0.0, 255.0);
            errFile += (file - s) * (file - s);
            errLs += (ls - s) * (ls - s);
            worst = std::max(worst, std::fabs(file - ls));
          }
        }
      }
    // colour_c / 255 <= 1 multiplies the luminance's quantisation error.
    const double bound = quantisationBound(rows, {p.scale.begin(), p.scale.end()});
    INFO("PSNR of the file " << psnr(errFile, samples) << " dB, unquantised fit "
                             << psnr(errLs, samples) << " dB, largest difference " << worst
                             << " (quantisation bound " << bound << ")");
    CHECK(colourOff == 0);
    CHECK(psnr(errLs, samples) < 60);
    CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
    CHECK(worst <= bound);
  }

  SECTION("HSH orders 2 and 3") {
    for (fit::Basis b : {fit::Basis::Hsh2, fit::Basis::Hsh3}) {
      fit::FitOptions o;
      o.basis = b;
      const fs::path file = temp.path() / (std::string(fit::basisName(b)) + ".rti");
      formats::writeRti(file, fit::fitHsh(stack, lights, o));
      const indep::Rti r = indep::readRti(slurp(file));
      const int terms = b == fit::Basis::Hsh2 ? 4 : 9;
      REQUIRE(r.terms == terms);
      std::vector<std::vector<double>> rows;
      for (const Light& l : lights) {
        rows.push_back({});
        for (int k = 0; k < terms; ++k) rows.back().push_back(ref::hshTerm(k, l[0], l[1], l[2]));
      }
      double errFile = 0, errLs = 0, worst = 0;
      for (int y = 0; y < scene.h; ++y)
        for (int x = 0; x < scene.w; ++x)
          for (int c = 0; c < 3; ++c) {
            std::vector<double> s;
            for (const auto& im : photo) s.push_back(im[(y * scene.w + x) * 3 + c]);
            const auto a = leastSquares(rows, s);
            for (std::size_t i = 0; i < lights.size(); ++i) {
              const Light& l = lights[i];
              const double file = std::clamp(indep::rtiValue(r, x, y, c, l[0], l[1], l[2]), 0.0, 255.0);
              double ls = 0;
              for (int k = 0; k < terms; ++k) ls += a[k] * rows[i][k];
              ls = std::clamp(ls, 0.0, 255.0);
              errFile += (file - s[i]) * (file - s[i]);
              errLs += (ls - s[i]) * (ls - s[i]);
              worst = std::max(worst, std::fabs(file - ls));
            }
          }
      // A step of coefficient k is SCALE_k / 255 in 0..1 units, 255 times that rendered.
      std::vector<double> step;
      for (float sc : r.scale) step.push_back(static_cast<double>(sc));
      const double bound = quantisationBound(rows, step);
      INFO(terms << " terms: PSNR of the file " << psnr(errFile, samples)
                 << " dB, unquantised fit " << psnr(errLs, samples) << " dB, largest difference "
                 << worst << " (quantisation bound " << bound << ")");
      CHECK(psnr(errLs, samples) < 60);
      CHECK(psnr(errFile, samples) > psnr(errLs, samples) - 0.3);
      CHECK(worst <= bound);
    }
  }
}
