// A generated capture laid out as RTIBuilder leaves it, with prior work written here without
// Surrogate's code (tests/audit/prior_rti.h): an .lp (Windows paths, CRLF, a blank line) of the
// generator's true lights with three of them tilted by exactly 6 degrees, a PTM fitted with those
// lights (with a clamped bias, or without), and a log XML. Shared by the audit's end-to-end tests
// (test_audit_e2e.cpp, test_audit_prior_e2e.cpp).
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "../audit/prior_rti.h"

namespace audit_e2e {

constexpr int kImages = 12;
constexpr double kTiltDegrees = 6;
// Surrogate's lights from the generated sphere agree with the generator's truth to about half a
// degree (measured: median 0.4, max 0.9 on this capture); the tilted images are 6 degrees off.
constexpr double kAngleTolerance = 1.5;
const std::set<int> kTilted = {2, 5, 8};  // IMG_0003, IMG_0006, IMG_0009

struct TrueLight {
  std::string image;  // jpeg-exports/IMG_0001.jpg
  surrogate::test::Light light;
};

// truth/lights.lp as the generator writes it: a count, then "path x y z" per image.
std::vector<TrueLight> trueLights(const std::filesystem::path& capture);

// The photographs as 16-bit RGB (8-bit values widened *257), decoded with OpenCV.
std::vector<surrogate::Image> photographs(const std::filesystem::path& capture, const std::vector<TrueLight>& lights);

// The capture with RTIBuilder's prior work: stela.lp, stela.ptm, stela_log.xml, in a fresh
// folder named after `name`. The PTM's constant term is clamped unless `clampBias` is false.
std::filesystem::path rtibuilderCapture(const std::string& name, bool clampBias = true);

}  // namespace audit_e2e
