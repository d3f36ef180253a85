#include "verify/model_difference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "fit/render.h"
#include "image/decode.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::verify {

namespace {

struct Accumulator {
  double max = 0, sumSq = 0;
  std::size_t n = 0;
  void add(double d) {
    d = std::fabs(d);
    if (d > max) max = d;
    sumSq += d * d;
    ++n;
  }
  double rms() const { return n ? std::sqrt(sumSq / double(n)) : 0; }
};

double psnr(const Image& a, const Image& b) {
  double sumSq = 0;
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    const double d = (double(a.pixels[i]) - double(b.pixels[i])) / 257.0;  // 8-bit levels
    sumSq += d * d;
  }
  if (sumSq == 0 || a.pixels.empty()) return std::numeric_limits<double>::infinity();
  const double mse = sumSq / double(a.pixels.size());
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

const std::array<std::array<double, 3>, 5> kLights = {{
    {0, 0, 1}, {0.7071, 0, 0.7071}, {-0.7071, 0, 0.7071}, {0, 0.7071, 0.7071}, {0, -0.7071, 0.7071}}};

bool isPtm(const std::filesystem::path& p) {
  FILE* f = std::fopen(p.c_str(), "rb");
  char head[4] = {};
  const bool ok = f && std::fread(head, 1, 4, f) == 4 && std::string(head, 4) == "PTM_";
  if (f) std::fclose(f);
  return ok;
}

}  // namespace

std::string ModelDifference::describe() const {
  if (!comparable) return why;
  char text[200];
  if (std::isinf(renderPsnr))
    std::snprintf(text, sizeof text, "coefficients differ by at most %.6g (RMS %.6g); renders identical",
                  maxCoefficient, rmsCoefficient);
  else
    std::snprintf(text, sizeof text, "coefficients differ by at most %.6g (RMS %.6g); renders PSNR %.2f dB",
                  maxCoefficient, rmsCoefficient, renderPsnr);
  return text;
}

ModelDifference compareModels(const std::filesystem::path& recorded,
                              const std::filesystem::path& reproduced) {
  ModelDifference d;
  const bool ptmA = isPtm(recorded), ptmB = isPtm(reproduced);
  if (ptmA != ptmB) {
    d.why = "one file is a PTM and the other is not";
    return d;
  }
  double worst = std::numeric_limits<double>::infinity();
  Accumulator acc;
  if (ptmA) {
    const formats::PtmFile a = formats::readPtm(recorded), b = formats::readPtm(reproduced);
    if (a.format != b.format || a.width != b.width || a.height != b.height) {
      d.why = "the PTMs differ in format or size";
      return d;
    }
    const int channels = a.format == formats::PtmFile::Format::Rgb ? 3 : 1;
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
          for (int k = 0; k < 6; ++k) acc.add(a.coefficient(x, y, k, c) - b.coefficient(x, y, k, c));
    for (std::size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i)
      acc.add(double(a.rgb[i]) - double(b.rgb[i]));
    for (const auto& l : kLights) worst = std::min(worst, psnr(fit::render(a, l), fit::render(b, l)));
  } else {
    const formats::HshFile a = formats::readRti(recorded), b = formats::readRti(reproduced);
    if (a.terms != b.terms || a.width != b.width || a.height != b.height) {
      d.why = "the RTIs differ in order or size";
      return d;
    }
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < a.terms; ++k) acc.add(a.coefficient(x, y, c, k) - b.coefficient(x, y, c, k));
    for (const auto& l : kLights) worst = std::min(worst, psnr(fit::render(a, l), fit::render(b, l)));
  }
  d.comparable = true;
  d.maxCoefficient = acc.max;
  d.rmsCoefficient = acc.rms();
  d.renderPsnr = worst;
  return d;
}

std::string compareImages(const std::filesystem::path& recorded,
                          const std::filesystem::path& reproduced) {
  const Image a = image::decodeImage(recorded, {}), b = image::decodeImage(reproduced, {});
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    return "the images differ in size (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
           " recorded, " + std::to_string(b.width) + "x" + std::to_string(b.height) + " reproduced)";
  double maxDiff = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    maxDiff = std::max(maxDiff, std::fabs(double(a.pixels[i]) - double(b.pixels[i])) / 257.0);
  const double p = psnr(a, b);
  char text[160];
  if (std::isinf(p))
    std::snprintf(text, sizeof text, "pixels identical (the files differ in encoding only)");
  else
    std::snprintf(text, sizeof text, "pixels differ by at most %.3g levels; PSNR %.2f dB", maxDiff, p);
  return text;
}

}  // namespace surrogate::verify
