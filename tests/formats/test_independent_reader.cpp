// Golden files from an independent implementation.
//
// These tests hold their own small reader and writer of .ptm (PTM_1.2, PTM_FORMAT_LRGB and
// PTM_FORMAT_RGB) and .rti (HSH, RTI type 3), written from the published layouts that
// docs/formats.md restates (HP's "PTM File Format" 1.2; CHI's RTIViewer loaders and relight's
// writers for .rti), and their own renderer from the closed-form bases of
// tests/fit/reference_basis.h (independent_format.h). None of it calls src/formats, and the
// renderer does not call src/fit. It is used both ways:
//   (a) files written HERE are read by Surrogate (formats::readPtm / readRti,
//       fit::openRelightable) and rendered by Surrogate (fit::render) at several lights; every
//       output pixel must be the nearest 8-bit value to what the closed form gives;
//   (b) files written by Surrogate (formats::writePtm / writeRti, from known coefficients and
//       from fit::fitPtm / fitHsh of synthetic photographs) are read HERE; header fields must be
//       exactly as the format prescribes, decoded coefficients must equal the known ones within
//       the format's quantisation, and an independent re-rendering at every captured light must
//       be within a fraction of a dB of an unquantised least-squares fit made here.
// A flipped row order, a swapped channel or term, or a wrong scale/bias convention on either
// side fails (a) or (b). This file holds (a); test_independent_known.cpp and
// test_independent_fitted.cpp hold (b), with known coefficients and fitted ones.
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

namespace fs = std::filesystem;
using namespace surrogate;
using namespace golden;

// ===================================================================== (a) ours -> Surrogate

TEST_CASE("independent .ptm LRGB and RGB files read and render in Surrogate as the closed form says") {
  surrogate::TempDir temp("independent-ptm");
  for (bool lrgb : {true, false}) {
    const indep::Ptm p = knownPtm(lrgb, 5, 4);
    const fs::path file = temp.path() / (lrgb ? "lrgb.ptm" : "rgb.ptm");
    spit(file, indep::writePtm(p));

    const formats::PtmFile s = formats::readPtm(file);
    REQUIRE(s.format == (lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb));
    REQUIRE(s.width == 5);
    REQUIRE(s.height == 4);
    for (int k = 0; k < 6; ++k) {
      CHECK(s.scale[k] == p.scale[k]);
      CHECK(s.bias[k] == p.bias[k]);
    }
    for (int c = 0; c < (lrgb ? 1 : 3); ++c)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int k = 0; k < 6; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " a" << k);
            CHECK(s.coefficient(x, y, k, c) == p.a(c, x, y, k));
          }

    const auto model = fit::openRelightable(file);
    CHECK(model->basis() == (lrgb ? "ptm-lrgb" : "ptm-rgb"));
    for (const Light& l : kRenderLights) {
      const Image a = fit::render(s, l);
      const Image b = model->render(l, {});
      REQUIRE(a.width == 5);
      REQUIRE(a.height == 4);
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int c = 0; c < 3; ++c) {
            const double want = indep::ptmValue(p, x, y, c, l[0], l[1], l[2]);
            const std::string where = std::string(lrgb ? "LRGB" : "RGB") + " light (" +
                                      std::to_string(l[0]) + ", " + std::to_string(l[1]) + ", " +
                                      std::to_string(l[2]) + ") pixel (" + std::to_string(x) +
                                      ", " + std::to_string(y) + ") channel " + std::to_string(c);
            checkNearest(rendered(a, x, y, c), want, where);
            checkNearest(rendered(b, x, y, c), want, where + " (openRelightable)");
          }
    }
  }
}

TEST_CASE("independent .rti HSH files of 4, 9 and 16 terms read and render in Surrogate as the closed form says") {
  surrogate::TempDir temp("independent-rti");
  for (int terms : {4, 9, 16}) {
    const indep::Rti r = knownRti(terms, 5, 4);
    const fs::path file = temp.path() / ("hsh" + std::to_string(terms) + ".rti");
    spit(file, indep::writeRti(r));

    const formats::HshFile s = formats::readRti(file);
    REQUIRE(s.terms == terms);
    REQUIRE(s.width == 5);
    REQUIRE(s.height == 4);
    for (int k = 0; k < terms; ++k) {
      CHECK(s.scale[k] == r.scale[k]);
      CHECK(s.bias[k] == r.bias[k]);
    }
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " H" << k);
            CHECK(s.coefficient(x, y, c, k) == r.a(x, y, c, k));
          }

    const auto model = fit::openRelightable(file);
    CHECK(model->basis() == (terms == 4 ? "hsh2" : terms == 9 ? "hsh3" : "hsh4"));
    int unclamped = 0;
    for (const Light& l : kRenderLights) {
      const Image a = fit::render(s, l);
      const Image b = model->render(l, {});
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
          for (int c = 0; c < 3; ++c) {
            const double want = indep::rtiValue(r, x, y, c, l[0], l[1], l[2]);
            if (want > 0.5 && want < 254.5) ++unclamped;
            const std::string where = std::to_string(terms) + " terms, light (" +
                                      std::to_string(l[0]) + ", " + std::to_string(l[1]) + ", " +
                                      std::to_string(l[2]) + ") pixel (" + std::to_string(x) +
                                      ", " + std::to_string(y) + ") channel " + std::to_string(c);
            checkNearest(rendered(a, x, y, c), want, where);
            checkNearest(rendered(b, x, y, c), want, where + " (openRelightable)");
          }
    }
    // The comparison means something only where the output is not clipped.
    CHECK(unclamped > static_cast<int>(kRenderLights.size()) * 5 * 4 * 3 * 3 / 4);
  }
}
