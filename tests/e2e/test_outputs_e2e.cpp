// What a run produces for the light estimation and fitting stages, checked as a user would.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"
#include "formats/lp.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {
// Results of every step, without times (which differ between runs).
std::string resultsOf(const carrier::Carrier& c) {
  std::string out;
  for (const carrier::Result& r : c.data) {
    out += r.step + " " + r.status + "\n";
    for (const carrier::DataItem& i : r.items) {
      out += i.element;
      for (const auto& [k, v] : i.attributes) out += " " + k + "=" + v;
      out += "\n";
    }
  }
  return out;
}
}  // namespace

TEST_CASE("a run writes the .lp, overlays, .ptm, .rti, normals and previews, all hashed in the carrier") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("outputs"), 12);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  for (const char* path : {"assembly-files/lights.lp", "assembly-files/spheres.png", "assembly-files/highlights-sphere1.png",
                           "finished-files/ptm-lrgb.ptm", "finished-files/hsh2.rti", "finished-files/normals.png",
                           "finished-files/albedo.png", "finished-files/preview-raking.png"}) {
    INFO(path);
    const carrier::FileRecord* f = c.findFileByPath(path);
    REQUIRE(f != nullptr);
    CHECK(f->sha256 == digestFile(capture / path).sha256);
    CHECK_FALSE(f->createdBy.empty());
  }
  // The files re-read bit-exactly: reading and writing again gives the same bytes.
  CHECK(formats::serializePtm(formats::readPtm(capture / "finished-files/ptm-lrgb.ptm")) ==
        e2e::bytesOf(capture / "finished-files/ptm-lrgb.ptm"));
  CHECK(formats::serializeRti(formats::readRti(capture / "finished-files/hsh2.rti")) ==
        e2e::bytesOf(capture / "finished-files/hsh2.rti"));
  // One light per image, unit vectors, in the standard .lp layout.
  const auto lights = formats::readLp(capture / "assembly-files/lights.lp");
  CHECK(lights.size() == 12);
  CHECK(std::string(e2e::bytesOf(capture / "assembly-files/lights.lp")).rfind("12\n", 0) == 0);
  // Fit quality recorded for each model.
  int fits = 0;
  for (const carrier::Result& res : c.data)
    for (const carrier::DataItem* v : res.itemsOf("value"))
      if (v->get("name") == "psnr") {
        ++fits;
        CHECK(v->number("value") > 20);
      }
  CHECK(fits == 2);
}

TEST_CASE("results are bit-identical with 1 and 2 threads") {
  const fs::path a = e2e::smallCapture(e2e::freshDir("threads-1"), 10);
  const fs::path b = e2e::smallCapture(e2e::freshDir("threads-2"), 10);
  REQUIRE(e2e::surrogate("run " + e2e::quote(a) + " --quiet --threads 1").exitCode == 0);
  REQUIRE(e2e::surrogate("run " + e2e::quote(b) + " --quiet --threads 2 --memory 64M").exitCode == 0);
  CHECK(resultsOf(carrier::loadCarrier(a / "assembly-files/carrier.xml")) ==
        resultsOf(carrier::loadCarrier(b / "assembly-files/carrier.xml")));
  // Every file DerivedMaps writes (written while the next map is computed at 2 threads).
  for (const char* path : {"assembly-files/lights.lp", "assembly-files/spheres.png", "finished-files/ptm-lrgb.ptm",
                           "finished-files/hsh2.rti", "finished-files/normals.png", "finished-files/albedo.png",
                           "finished-files/preview-raking.png", "finished-files/preview-top.png",
                           "finished-files/preview-specular.png"}) {
    INFO(path);
    CHECK(digestFile(a / path).sha256 == digestFile(b / path).sha256);
  }
}

TEST_CASE("a memory budget too small to hold the decoded images gives bit-identical results") {
  // 16 x 800x600 JPEGs: 23 MB of 8-bit samples, held in memory under the default 2G; under 64M
  // (the least --memory takes), beside decoding one image and the two models kept, they go to
  // a temporary file.
  const fs::path dir = e2e::freshDir("memory");
  const fs::path a = dir / "held", b = dir / "spilled";
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(a) +
                        " --images 16 --width 800 --height 600 --sphere-radius 60 --seed 5 --formats jpeg").exitCode == 0);
  fs::remove_all(a / "truth");
  fs::copy(a, b, fs::copy_options::recursive);
  REQUIRE(e2e::surrogate("run " + e2e::quote(a) + " --quiet --threads 2").exitCode == 0);
  const e2e::CommandResult spilled = e2e::surrogate("run " + e2e::quote(b) + " --quiet --threads 2 --memory 64M");
  INFO(spilled.output);
  REQUIRE(spilled.exitCode == 0);
  const carrier::Carrier ca = carrier::loadCarrier(a / "assembly-files/carrier.xml");
  const carrier::Carrier cb = carrier::loadCarrier(b / "assembly-files/carrier.xml");
  CHECK(resultsOf(ca) == resultsOf(cb));
  for (const char* path : {"assembly-files/lights.lp", "assembly-files/spheres.png", "finished-files/ptm-lrgb.ptm",
                           "finished-files/hsh2.rti", "finished-files/normals.png", "finished-files/preview-specular.png"}) {
    INFO(path);
    CHECK(digestFile(a / path).sha256 == digestFile(b / path).sha256);
  }
  // The log says where the decoded images were, so that a slow run can be told apart.
  auto logged = [](const carrier::Carrier& c, const std::string& words) {
    for (const carrier::LogEntry& e : c.log)
      if (e.text.find(words) != std::string::npos) return true;
    return false;
  };
  CHECK(logged(ca, "decoded images are held in memory"));
  CHECK(logged(cb, ") are in a temporary file"));
}

TEST_CASE("surrogate lights writes the .lp and light directions close to the truth") {
  const fs::path dir = e2e::freshDir("lights");
  const fs::path generated = dir / "generated";
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(generated) +
                        " --images 16 --width 600 --height 400 --sphere-radius 70 --seed 9").exitCode == 0);
  const e2e::CommandResult r = e2e::surrogate("lights " + e2e::quote(generated) + " -o " + e2e::quote(dir / "out.lp") + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const auto estimated = formats::readLp(dir / "out.lp");
  const auto truth = formats::readLp(generated / "truth/lights.lp");
  REQUIRE(estimated.size() == truth.size());
  double worst = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double dot = estimated[i].x * truth[i].x + estimated[i].y * truth[i].y + estimated[i].z * truth[i].z;
    worst = std::max(worst, std::acos(std::min(1.0, dot)) * 180 / M_PI);
  }
  CHECK(worst < 1.5);
  CHECK_FALSE(fs::exists(generated / "finished-files/ptm-lrgb.ptm"));  // light estimation only
}

TEST_CASE("a dome capture's .lp skips detection, and the carrier says so") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("dome"), 8);
  const fs::path truth = capture.parent_path() / "truth.lp";
  // The generator's truth, as a dome would give it, placed in the capture folder.
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture.parent_path() / "t") +
                        " --images 8 --width 400 --height 300 --sphere-radius 45 --seed 7 --formats jpeg").exitCode == 0);
  fs::copy_file(capture.parent_path() / "t/truth/lights.lp", capture / "dome.lp");
  // Dome mode is explicit: an .lp in the folder is not used until --lp names it, and sphere
  // options with it are refused, naming the conflict.
  const e2e::CommandResult sphere = e2e::surrogate("run " + e2e::quote(capture) + " --lp dome.lp --sphere 339,57,45 --reason x --quiet");
  CHECK(sphere.exitCode == 2);
  CHECK_THAT(sphere.output, Catch::Contains("dome"));
  CHECK_FALSE(fs::exists(capture / "assembly-files/carrier.xml"));
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --lp dome.lp");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("lights: from dome.lp (dome capture"));
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  bool fromFile = false, detection = false;
  for (const carrier::Step& s : c.process) {
    fromFile = fromFile || s.component == "LightsFromFile";
    detection = detection || s.component == "SphereDetection";
  }
  CHECK(fromFile);
  CHECK_FALSE(detection);
  bool logged = false;
  for (const carrier::LogEntry& e : c.log) logged = logged || e.text.find("dome capture") != std::string::npos;
  CHECK(logged);
  // The choice stands: a plain run keeps the dome's lights.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 0);
  const carrier::Carrier again = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  bool stillFromFile = false;
  for (const carrier::Step& s : again.process) stillFromFile = stillFromFile || s.component == "LightsFromFile";
  CHECK(stillFromFile);
}

TEST_CASE("a sphere given by hand is used and recorded as an intervention") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("manual"), 8);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) +
                                              " --quiet --operator Tester --sphere 340,60,45 --reason 'checked on screen'");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  const carrier::Step* step = nullptr;
  for (const carrier::Step& s : c.process)
    if (s.component == "SphereDetection") step = &s;
  REQUIRE(step != nullptr);
  REQUIRE(step->interventions.size() == 1);
  CHECK(step->interventions[0].value == "340,60,45");
  CHECK(step->interventions[0].reason == "checked on screen");
  const auto spheres = c.findResult(step->id)->itemsOf("sphere");
  REQUIRE(spheres.size() == 1);
  CHECK(*spheres[0]->get("source") == "manual");
  CHECK(spheres[0]->number("cx") == 340);
}

TEST_CASE("fit, render and info work on the files a run wrote") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("tools"), 10);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --basis ptm-rgb --basis hsh3").exitCode == 0);
  CHECK(fs::exists(capture / "finished-files/ptm-rgb.ptm"));
  CHECK(fs::exists(capture / "finished-files/hsh3.rti"));

  const fs::path out = capture.parent_path();
  e2e::CommandResult r = e2e::surrogate("fit --lp " + e2e::quote(capture / "assembly-files/lights.lp") + " -o " +
                                        e2e::quote(out / "refit.ptm") + " --quiet");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(formats::readPtm(out / "refit.ptm").width == 400);

  r = e2e::surrogate("render " + e2e::quote(out / "refit.ptm") + " --light 0.5,0.5,0.707 -o " + e2e::quote(out / "r.png"));
  CHECK(r.exitCode == 0);
  CHECK(fs::file_size(out / "r.png") > 1000);
  r = e2e::surrogate("render " + e2e::quote(capture / "finished-files/hsh3.rti") + " --light 1.5,0,0.2 --specular -o " +
                     e2e::quote(out / "r2.png"));
  CHECK(r.exitCode == 0);
  r = e2e::surrogate("render " + e2e::quote(out / "refit.ptm") + " --light 0.3,0.2,0.9 --gain 2 -o " + e2e::quote(out / "r3.png"));
  CHECK(r.exitCode == 0);

  r = e2e::surrogate("info " + e2e::quote(out / "refit.ptm"));
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("400"));
  r = e2e::surrogate("info --json " + e2e::quote(capture / "assembly-files/lights.lp"));
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("10"));

  std::ofstream(out / "bad.ptm") << "PTM_1.2\nPTM_FORMAT_LRGB\n99999999\n2\n";
  r = e2e::surrogate("render " + e2e::quote(out / "bad.ptm") + " --light 0,0,1 -o " + e2e::quote(out / "x.png"));
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.output, Catch::Contains("bad.ptm"));
  CHECK_FALSE(fs::exists(out / "x.png"));
}
