// Test support for the publish end-to-end tests: a generated capture fitted once per process
// with the four bases, and the lights at which published models are compared.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "../e2e/e2e_support.h"
#include "web_reader.h"

namespace publishtest {

inline const std::array<std::array<double, 3>, 4> kLights = {{
    {0, 0, 1}, {0.5, 0.5, 0.71}, {-0.7, 0.2, 0.69}, {0.1, -0.8, 0.59}}};

// The models `run` writes in finished-files/, by basis.
inline const std::map<std::string, std::string> kModels = {
    {"ptm-lrgb", "ptm-lrgb.ptm"}, {"ptm-rgb", "ptm-rgb.ptm"}, {"hsh2", "hsh2.rti"}, {"hsh3", "hsh3.rti"}};

// A 12-image generated capture run once per process with the four bases.
inline std::filesystem::path fittedCapture() {
  static std::filesystem::path capture;
  if (capture.empty()) {
    capture = e2e::smallCapture(e2e::freshDir("fitted"), 12);
    const auto r = e2e::surrogate("run " + e2e::quote(capture) +
                                  " --basis ptm-lrgb --basis ptm-rgb --basis hsh2 --basis hsh3");
    if (r.exitCode != 0) throw std::runtime_error("surrogate run failed: " + r.output);
  }
  return capture;
}

// `surrogate render MODEL --light L -o PNG` as 8-bit RGB values, rows top-first.
inline std::vector<int> renderedBySurrogate(const std::filesystem::path& model, const std::array<double, 3>& l,
                                            const std::filesystem::path& png) {
  const auto r = e2e::surrogate("render " + e2e::quote(model) + " --light " + std::to_string(l[0]) + "," +
                                std::to_string(l[1]) + "," + std::to_string(l[2]) + " -o " + e2e::quote(png));
  if (r.exitCode != 0) throw std::runtime_error("surrogate render failed: " + r.output);
  return webtest::rgbValues(cv::imread(png.string(), cv::IMREAD_COLOR));
}

}  // namespace publishtest
