// What the tests of buildReport on carriers made in memory share (test_report_build.cpp,
// test_report_pictures_models.cpp): a report source in memory, a carrier like a run's with
// hostile text, small models and pictures as their files, and a picture as a step holds it.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "carrier/carrier.h"
#include "core/image.h"
#include "report/report.h"

namespace report_build {

inline constexpr const char* kHostile = "\"><img src=x onerror=alert(1)></script><script>alert(2)</script>";

class MemorySource : public surrogate::report::ReportSource {
 public:
  explicit MemorySource(surrogate::carrier::Carrier c) : carrier_(std::move(c)) {}
  const surrogate::carrier::Carrier& carrier() const override { return carrier_; }
  std::optional<std::string> read(const std::string& path) const override {
    const auto it = files.find(path);
    if (it == files.end()) return std::nullopt;
    return it->second;
  }
  std::string describe() const override { return "test source"; }
  bool isPackage() const override { return false; }
  std::map<std::string, std::string> files;

 private:
  surrogate::carrier::Carrier carrier_;
};

// A PNG file of width x height in one colour.
std::string png(int width, int height);

// An 8x6 PTM (LRGB), the same bytes in every texel, as a .ptm file.
std::string smallPtm();

// An HSH of order 2 whose bytes differ from texel to texel, as an .rti file.
std::string smallHsh(int width, int height);

// A carrier's record of an output file (size 1) of `role` and `format`.
surrogate::carrier::FileRecord output(const std::string& path, const std::string& role, const std::string& format);

// How many times `what` occurs in `text`.
int count(const std::string& text, const std::string& what);

// A carrier like a run's: 5 images, spheres, lights, a PTM fit with residuals, derived maps,
// an intervention and a warning; every free text field hostile.
surrogate::carrier::Carrier sampleCarrier();

// A picture as a pipeline step holds it (Image: 16-bit values, or 8-bit values * 257), and the
// same pixels as a PNG file written by OpenCV, a writer independent of Surrogate's.
struct HeldPicture {
  surrogate::Image pixels;
  std::string png;
};

HeldPicture heldPicture(int width, int height, int channels, bool sixteenBit, int seed);

}  // namespace report_build
