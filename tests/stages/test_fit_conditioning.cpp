// RtiFit records the conditioning of a fit on its light set (src/fit/conditioning.h) in its
// results and log only when it changed the fit, so that a carrier made before conditioning
// existed re-executes to the same result items.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "carrier/carrier.h"
#include "core/stack.h"
#include "pipeline/context.h"
#include "pipeline/runner.h"
#include "pipeline/stage.h"
#include "stages/inputs.h"
#include "stages/registry.h"
#include "../light_spiral.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

using Lights = std::vector<std::array<double, 3>>;

// One RtiFit step of `basis` over a grey Lambertian relief under `lights`, recorded as the
// stage's version or as `version`.
carrier::Carrier fitOnce(const std::string& basis, const Lights& lights, const fs::path& root,
                         const std::string& version = "") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const int w = 24, h = 16;
  std::vector<std::array<double, 4>> surface;
  for (int p = 0; p < w * h; ++p) {
    const double tilt = 0.6 * u(rng), dir = 2 * M_PI * u(rng);
    surface.push_back({std::sin(tilt) * std::cos(dir), std::sin(tilt) * std::sin(dir), std::cos(tilt), 0.3 + 0.6 * u(rng)});
  }
  std::vector<Image> images;
  auto inputs = std::make_shared<stages::InputImages>();
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Image im(w, h, 3);
    for (int p = 0; p < w * h; ++p) {
      const auto& s = surface[p];
      const double v = 255 * s[3] * std::max(0.0, s[0] * lights[i][0] + s[1] * lights[i][1] + s[2] * lights[i][2]);
      const double noisy = std::round(std::clamp(v + 4 * u(rng) - 2, 0.0, 255.0));
      for (int c = 0; c < 3; ++c) im.pixels[p * 3 + c] = static_cast<std::uint16_t>(noisy * 257);
    }
    images.push_back(std::move(im));
    inputs->push_back({"f" + std::to_string(i + 1), "jpeg-exports/" + std::to_string(i) + ".jpg", std::to_string(i)});
  }
  stages::registerBuiltinStages();
  carrier::Carrier c = carrier::newCarrier("one fit", {});
  carrier::Step& s =
      c.addStep("RtiFit", version.empty() ? pipeline::StageRegistry::instance().create("RtiFit")->version() : version);
  s.setParam("basis", basis);
  fs::create_directories(root / "finished-files");
  pipeline::Context ctx(root, c, pipeline::RunSettings{});
  ctx.put(stages::kRgbStack, std::shared_ptr<ImageStack>(std::make_shared<MemoryImageStack>(std::move(images))));
  ctx.put(stages::kLights, std::make_shared<Lights>(lights));
  ctx.put(stages::kInputImages, inputs);
  pipeline::runProcess(ctx, {});
  return c;
}

std::optional<std::string> valueOf(const carrier::Carrier& c, const std::string& name) {
  for (const carrier::DataItem* v : c.data.at(0).itemsOf("value"))
    if (v->get("name") == name) return v->get("value");
  return std::nullopt;
}

int warnings(const carrier::Carrier& c) {
  int n = 0;
  for (const carrier::LogEntry& e : c.log) n += e.level == "warning";
  return n;
}

}  // namespace

TEST_CASE("RtiFit records the weight, condition and damped terms of a fit its narrow lights conditioned") {
  const fs::path root = fs::temp_directory_path() / "fit-conditioning-narrow";
  // 12 lights within 21 degrees of the view axis.
  const carrier::Carrier c = fitOnce("hsh3", test::spiralLights(12, 68.0, 85.0), root);
  REQUIRE(c.data.size() == 1);
  CHECK(c.data[0].status == "completed");
  REQUIRE(valueOf(c, "regularisation"));
  CHECK(std::stod(*valueOf(c, "regularisation")) > 0);
  CHECK(valueOf(c, "dampedTerms") == std::string("4 5 6 7 8"));
  CHECK(std::stod(*valueOf(c, "lightMatrixCondition")) > 100);
  CHECK(std::stod(*valueOf(c, "plainQuantisationNoiseGain")) > std::stod(*valueOf(c, "quantisationNoiseGain")));
  bool said = false;
  for (const carrier::LogEntry& e : c.log)
    said = said || (e.level == "warning" && e.text.find("the 12 lights lie within 21 degrees of the view axis") == 0 &&
                    e.text.find("HSH order 3's five highest terms were damped") != std::string::npos);
  CHECK(said);
}

TEST_CASE("RtiFit records no damping for lights spread over the hemisphere, only how well they support it") {
  const fs::path root = fs::temp_directory_path() / "fit-conditioning-wide";
  for (const char* basis : {"hsh3", "ptm-lrgb"}) {
    const carrier::Carrier c = fitOnce(basis, test::spiralLights(12, 20.0, 80.0), root);
    REQUIRE(c.data.size() == 1);
    CHECK(c.data[0].status == "completed");
    CHECK_FALSE(valueOf(c, "regularisation"));
    CHECK_FALSE(valueOf(c, "dampedTerms"));
    CHECK_FALSE(valueOf(c, "plainQuantisationNoiseGain"));
    // Recorded for every fit since RtiFit 4: spread lights support either basis (gain under
    // the damping's limit of 16, docs/hrti-math.md).
    REQUIRE(valueOf(c, "quantisationNoiseGain"));
    CHECK(std::stod(*valueOf(c, "quantisationNoiseGain")) < 16);
    CHECK(valueOf(c, "lightMatrixCondition"));
    CHECK(valueOf(c, "psnr"));
    CHECK(warnings(c) == 0);
  }
}

TEST_CASE("RtiFit steps of version 7 still measure the fit error in double precision, version 8 in single") {
  // The same photographs fitted as each version: the same model file, errors apart by float's
  // spacing (fit/error_kernels.h), and not the same bits: each version runs its own arithmetic.
  const fs::path root = fs::temp_directory_path() / "fit-error-versions";
  for (const std::string basis : {"ptm-lrgb", "hsh2"}) {
    INFO(basis);
    const fs::path model = root / "finished-files" / (basis + (basis == "hsh2" ? ".rti" : ".ptm"));
    std::vector<std::string> files, rmse;
    for (const char* version : {"7", "8"}) {
      const carrier::Carrier c = fitOnce(basis, test::spiralLights(12, 20.0, 80.0), root, version);
      REQUIRE(c.data.size() == 1);
      CHECK(c.data[0].status == "completed");
      std::ifstream in(model, std::ios::binary);
      files.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      REQUIRE(valueOf(c, "rmse"));
      rmse.push_back(*valueOf(c, "rmse"));
    }
    CHECK_FALSE(files[0].empty());
    CHECK(files[0] == files[1]);
    CHECK(rmse[0] != rmse[1]);
    CHECK(std::abs(std::stod(rmse[0]) - std::stod(rmse[1])) < 5e-5);
  }
}
