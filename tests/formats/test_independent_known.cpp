// Golden files, (b) with known coefficients: .ptm and .rti files Surrogate writes
// (formats::writePtm / writeRti) from coefficients chosen here, read back by the independent
// reader (independent_format.h): header fields exactly as the format prescribes, pixel order, and
// the coefficients within the format's quantisation. test_independent_reader.cpp says more.
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

// ===================================================================== (b) Surrogate -> ours

TEST_CASE("Surrogate's .ptm from known coefficients reads back here: header, pixel order, quantisation") {
  surrogate::TempDir temp("independent-ptm-back");
  const int w = 6, h = 5;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (bool lrgb : {true, false}) {
    const int channels = lrgb ? 1 : 3;
    // Known real coefficients (0..255 units), [channel][y][x][k], and colours.
    std::vector<std::array<double, 6>> truth(static_cast<std::size_t>(channels) * w * h);
    for (auto& a : truth)
      a = {-30 * u(rng), -30 * u(rng), -8 + 16 * u(rng), -25 + 50 * u(rng), -25 + 50 * u(rng),
           110 + 100 * u(rng)};
    auto at = [&](int c, int x, int y) -> const std::array<double, 6>& {
      return truth[(static_cast<std::size_t>(c) * h + y) * w + x];
    };
    // Surrogate's quantisation of them, into Surrogate's in-memory object.
    formats::PtmFile s;
    s.format = lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb;
    s.width = w;
    s.height = h;
    std::array<fit::PtmQuantisation, 6> q;
    for (int k = 0; k < 6; ++k) {
      double lo = 1e300, hi = -1e300;
      for (const auto& a : truth) {
        lo = std::min(lo, a[k]);
        hi = std::max(hi, a[k]);
      }
      q[k] = fit::choosePtmQuantisation(lo, hi);
      s.scale[k] = q[k].scale;
      s.bias[k] = q[k].bias;
    }
    s.coefficients.resize(static_cast<std::size_t>(w) * h * 6 * channels);
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int k = 0; k < 6; ++k)
            s.coefficients[((static_cast<std::size_t>(c) * h + y) * w + x) * 6 + k] =
                q[k].quantise(at(c, x, y)[k]);
    if (lrgb) {
      s.rgb.resize(static_cast<std::size_t>(w) * h * 3);
      for (std::size_t i = 0; i < s.rgb.size(); ++i) s.rgb[i] = static_cast<std::uint8_t>(30 + (i * 37) % 200);
    }
    const fs::path file = temp.path() / (lrgb ? "lrgb.ptm" : "rgb.ptm");
    formats::writePtm(file, s);

    indep::Ptm p;
    try {
      p = indep::readPtm(slurp(file));
    } catch (const indep::Failure& e) {
      FAIL("the independent reader rejects Surrogate's .ptm: " << e.what());
    }
    CHECK(p.headerLines[0] == "PTM_1.2");
    CHECK(p.headerLines[1] == (lrgb ? "PTM_FORMAT_LRGB" : "PTM_FORMAT_RGB"));
    CHECK(p.headerLines[2] == std::to_string(w));
    CHECK(p.headerLines[3] == std::to_string(h));
    for (int k = 0; k < 6; ++k) {
      CHECK(p.scale[k] == s.scale[k]);  // the text reads back to the very double
      CHECK(p.bias[k] == s.bias[k]);
    }
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int k = 0; k < 6; ++k) {
            INFO("texel (" << x << ", " << y << ") channel " << c << " a" << k);
            CHECK(p.coef[c][y][x][k] == s.byte(x, y, k, c));
            CHECK(std::fabs(p.a(c, x, y, k) - at(c, x, y)[k]) <= p.scale[k] / 2 + 1e-9);
          }
    if (lrgb)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c)
            CHECK(p.colour[y][x][c] == s.rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c]);
    // And our own writer, given the same header numbers and texels, writes the same payload.
    const std::string ours = indep::writePtm(p), theirs = slurp(file);
    const std::size_t payload = static_cast<std::size_t>(w) * h * (lrgb ? 9 : 18);
    CHECK(ours.substr(ours.size() - payload) == theirs.substr(theirs.size() - payload));
  }
}

TEST_CASE("Surrogate's .rti from known coefficients reads back here: header, pixel order, quantisation") {
  surrogate::TempDir temp("independent-rti-back");
  const int w = 6, h = 5;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int terms : {4, 9, 16}) {
    std::vector<double> truth(static_cast<std::size_t>(w) * h * 3 * terms);  // [y][x][c][k]
    for (std::size_t i = 0; i < truth.size(); ++i)
      truth[i] = (i % terms == 0) ? 1.2 + 0.3 * u(rng) : 0.05 * u(rng);
    auto at = [&](int x, int y, int c, int k) {
      return truth[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k];
    };
    formats::HshFile s;
    s.width = w;
    s.height = h;
    s.terms = terms;
    std::vector<fit::HshQuantisation> q(terms);
    for (int k = 0; k < terms; ++k) {
      double lo = 1e300, hi = -1e300;
      for (std::size_t i = k; i < truth.size(); i += terms) {
        lo = std::min(lo, truth[i]);
        hi = std::max(hi, truth[i]);
      }
      q[k] = fit::chooseHshQuantisation(lo, hi);
      s.scale.push_back(q[k].scale);
      s.bias.push_back(q[k].bias);
    }
    s.coefficients.resize(truth.size());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k)
            s.coefficients[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k] =
                q[k].quantise(at(x, y, c, k));
    const fs::path file = temp.path() / ("hsh" + std::to_string(terms) + ".rti");
    formats::writeRti(file, s);

    indep::Rti r;
    try {
      r = indep::readRti(slurp(file));
    } catch (const indep::Failure& e) {
      FAIL("the independent reader rejects Surrogate's .rti: " << e.what());
    }
    REQUIRE(r.headerLines.size() == 4);
    CHECK(r.headerLines[0] == "#HSH1.2");
    CHECK(r.headerLines[1] == "3");
    CHECK(r.headerLines[2] == std::to_string(w) + " " + std::to_string(h) + " 3");
    CHECK(r.headerLines[3] == std::to_string(terms) + " 2 1");
    for (int k = 0; k < terms; ++k) {
      CHECK(r.scale[k] == s.scale[k]);
      CHECK(r.bias[k] == s.bias[k]);
    }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < terms; ++k) {
            INFO(terms << " terms, texel (" << x << ", " << y << ") channel " << c << " H" << k);
            CHECK(r.coef[y][x][c][k] == s.byte(x, y, c, k));
            // Half a step of SCALE/255, plus the float32 rounding of SCALE and BIAS.
            CHECK(std::fabs(r.a(x, y, c, k) - at(x, y, c, k)) <=
                  static_cast<double>(r.scale[k]) / 510.0 + 1e-6);
          }
    CHECK(indep::writeRti(r) == slurp(file));  // byte for byte
  }
}
