// `surrogate publish` on a generated capture: the web layout of every recorded model, read by
// the independent reader (web_reader.h), against `surrogate render` of the .ptm/.rti at
// several lights, per JPEG quality; deterministic; the capture left as it was.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>

#include "../e2e/e2e_support.h"
#include "fitted_capture.h"
#include "web_reader.h"

namespace fs = std::filesystem;

namespace {

using publishtest::fittedCapture;
using publishtest::kLights;
using publishtest::kModels;

using publishtest::renderedBySurrogate;

}  // namespace

// Tolerance: the worst PSNR over the four lights and the four bases, against `surrogate
// render`, per quality; the measured values (printed) are in docs/formats.md. A wrong plane
// order, bias convention or row order gives far less than 25 dB.
TEST_CASE("surrogate publish of a capture renders as surrogate render within the JPEG error at quality 75 90 100") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("publish-quality");
  std::map<std::string, std::vector<std::vector<int>>> references;
  for (const auto& [name, file] : kModels)
    for (std::size_t i = 0; i < kLights.size(); ++i)
      references[name].push_back(renderedBySurrogate(capture / "finished-files" / file, kLights[i],
                                                     work / (name + std::to_string(i) + ".png")));
  const std::map<int, double> minPsnr = {{100, 45}, {90, 37}, {75, 34}};
  for (const auto& [quality, threshold] : minPsnr) {
    const fs::path out = work / ("web-" + std::to_string(quality));
    const auto r = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(out) +
                                  " --quality " + std::to_string(quality));
    REQUIRE(r.exitCode == 0);
    for (const auto& [name, file] : kModels) {
      const webtest::WebModel web = webtest::readWebModel(out / name);
      double worst = INFINITY;
      for (std::size_t i = 0; i < kLights.size(); ++i)
        worst = std::min(worst, webtest::psnr(webtest::renderAt(web, kLights[i][0], kLights[i][1], kLights[i][2]),
                                              references[name][i]));
      std::uintmax_t bytes = 0, viewer = 0;  // the layout (info.json, planes), and the viewer beside it
      for (const auto& e : fs::directory_iterator(out / name)) {
        const bool ofViewer = e.path().extension() == ".html" || e.path().extension() == ".js";
        (ofViewer ? viewer : bytes) += fs::file_size(e.path());
      }
      WARN("quality " << quality << " " << name << ": worst PSNR " << worst << " dB, " << bytes << " bytes against "
                      << fs::file_size(capture / "finished-files" / file) << " of " << file << "; viewer " << viewer
                      << " bytes");
      CHECK(worst >= threshold);
    }
  }
  fs::remove_all(work);
}

TEST_CASE("surrogate publish of a capture is deterministic and leaves the capture unchanged and info describes it") {
  const fs::path capture = fittedCapture();
  const auto before = e2e::snapshot(capture);
  const fs::path work = e2e::freshDir("publish-twice");
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "a")).exitCode == 0);
  REQUIRE(e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "b") + " --json").exitCode == 0);
  const auto a = e2e::snapshot(work / "a"), b = e2e::snapshot(work / "b");
  // four info.json, their planes and their viewers, and the index of the four
  CHECK(a.size() == 4 + 3 + 6 + 4 + 9 + 4 * 2 + 1);
  CHECK(a.count("index.html") == 1);
  CHECK(a == b);
  CHECK(e2e::snapshot(capture) == before);
  const auto info = e2e::surrogate("info " + e2e::quote(work / "a" / "ptm-rgb" / "info.json") + " --json");
  CHECK(info.exitCode == 0);
  CHECK(info.output.find(R"("kind":"web-layout","type":"ptm","colorspace":"rgb","basis":"ptm-rgb")") !=
        std::string::npos);
  CHECK(info.output.find(R"("missingPlanes":[])") != std::string::npos);
  fs::remove_all(work);
}

TEST_CASE("surrogate publish refuses a capture with no recorded model and a non-empty output folder") {
  const fs::path work = e2e::freshDir("publish-refuse");
  const fs::path bare = e2e::smallCapture(work, 12);
  const auto none = e2e::surrogate("publish " + e2e::quote(bare) + " -o " + e2e::quote(work / "web"));
  CHECK(none.exitCode != 0);
  CHECK(!fs::exists(work / "web"));
  fs::create_directories(work / "full");
  { std::ofstream(work / "full" / "keep.txt") << "x"; }
  const auto full = e2e::surrogate("publish " + e2e::quote(fittedCapture() / "finished-files" / "hsh3.rti") +
                                   " -o " + e2e::quote(work / "full"));
  CHECK(full.exitCode == 2);
  CHECK(full.output.find("not an empty folder") != std::string::npos);
  fs::remove_all(work);
}

TEST_CASE("surrogate publish --tiles deepzoom writes tiles the independent reader assembles into the model and info reports") {
  const fs::path capture = fittedCapture();
  const fs::path work = e2e::freshDir("publish-tiles");
  const auto r = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "web") +
                                " --tiles deepzoom --tile-size 128 --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  // 400x300 in tiles of 128: 400 -> 200 -> 100, three levels (OpenLIME: ceil(log2(400/128)) + 1).
  CHECK(r.output.find(R"("tiles":"deepzoom","levels":3)") != std::string::npos);
  for (const auto& [name, file] : kModels) {
    INFO(name);
    CHECK_FALSE(fs::exists(work / "web" / name / "plane_0.jpg"));
    const webtest::WebModel web = webtest::readWebModel(work / "web" / name);
    for (std::size_t i = 0; i < kLights.size(); ++i) {
      const auto reference = renderedBySurrogate(capture / "finished-files" / file, kLights[i], work / "r.png");
      CHECK(webtest::psnr(webtest::renderAt(web, kLights[i][0], kLights[i][1], kLights[i][2]), reference) >= 37);
    }
    const auto info = e2e::surrogate("info " + e2e::quote(work / "web" / name / "info.json") + " --json");
    CHECK(info.exitCode == 0);
    CHECK(info.output.find(R"("tiles":"deepzoom")") != std::string::npos);
    CHECK(info.output.find(R"("missingPlanes":[])") != std::string::npos);
  }
  const auto badSize = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "b") + " --tile-size 8");
  CHECK(badSize.exitCode == 2);
  CHECK(badSize.output.find("--tile-size") != std::string::npos);
  const auto badLayout = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(work / "b") + " --tiles iiif");
  CHECK(badLayout.exitCode == 2);
  CHECK_FALSE(fs::exists(work / "b"));
  fs::remove_all(work);
}
