// DerivedMaps writes its five pictures on encoder threads while the next is computed
// (src/stages/derived_maps_stage.cpp, OverlappedPngWrites): the files and the carrier must be
// those of one thread, whatever memory allows to be held, and a write that fails must stop the
// step with its error rather than leave it waiting.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>

#include "carrier/carrier.h"
#include "core/error.h"
#include "fit/render.h"
#include "pipeline/context.h"
#include "pipeline/runner.h"
#include "stages/registry.h"
#include "stages/rti_fit_stage.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

// A model whose pictures depend on the light and the texel, with noise that deflate cannot
// shrink much (as real normals): each picture distinct, each encode a few milliseconds.
class PatternModel : public fit::Relightable {
 public:
  int width() const override { return 320; }
  int height() const override { return 240; }
  std::string basis() const override { return "ptm-lrgb"; }
  Image render(const std::array<double, 3>& light, const fit::RenderOptions&) const override {
    return picture(static_cast<std::uint32_t>(1000 * (light[0] + 2 * light[1] + 3 * light[2]) + 7), 8);
  }
  Image normalMap(int* fallback, int) const override {
    if (fallback) *fallback = 3;
    return picture(1, 16);
  }
  Image albedoMap(int) const override { return picture(2, 8); }

 private:
  Image picture(std::uint32_t seed, int bits) const {
    Image im(width(), height(), 3);
    im.bitsPerSample = bits;
    std::uint32_t x = seed * 2654435761u + 1;
    for (std::size_t k = 0; k < im.pixels.size(); ++k) {
      x ^= x << 13, x ^= x >> 17, x ^= x << 5;
      const std::size_t p = k / 3;
      const double smooth = 0.5 + 0.4 * std::sin(0.05 * (p % width()) + 0.03 * (p / width()) + seed);
      im.pixels[k] = static_cast<std::uint16_t>(smooth * 60000 + (x & 1023));
    }
    return im;
  }
};

struct Outcome {
  carrier::Carrier carrier;
  std::map<std::string, std::string> files;  // name -> bytes
};

Outcome derive(const fs::path& root, int threads, std::size_t memory) {
  stages::registerBuiltinStages();
  fs::remove_all(root);
  fs::create_directories(root / "finished-files");
  Outcome o{carrier::newCarrier("derived maps", {}), {}};
  o.carrier.addStep("DerivedMaps", pipeline::StageRegistry::instance().create("DerivedMaps")->version())
      .setParam("model", "ptm-lrgb");
  pipeline::RunSettings settings;
  settings.threads = threads;
  settings.memoryBudget = memory;
  pipeline::Context ctx(root, o.carrier, settings);
  ctx.put(stages::modelKey("ptm-lrgb"), std::shared_ptr<fit::Relightable>(std::make_shared<PatternModel>()));
  pipeline::runProcess(ctx, {});
  for (const auto& e : fs::directory_iterator(root / "finished-files")) {
    std::ifstream in(e.path(), std::ios::binary);
    o.files[e.path().filename().string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  return o;
}

// The files the step recorded, in order, and its result's items (without the step's timing).
std::string itemsOf(const carrier::Carrier& c) {
  std::string out;
  for (const carrier::FileRecord& f : c.files)
    out += f.id + " " + f.path + " " + f.role + " " + std::to_string(f.size) + " " + f.sha256 + " " + f.puid + "\n";
  for (const carrier::DataItem& item : c.data.at(0).items) {
    out += item.element;
    for (const auto& [name, value] : item.attributes) out += " " + name + "=" + value;
    out += "\n";
  }
  return out;
}

}  // namespace

TEST_CASE("DerivedMaps writes the same files and records them in the same order at any thread count and memory") {
  const fs::path base = fs::temp_directory_path() / "surrogate-test-derived-maps";
  const Outcome one = derive(base / "one", 1, std::size_t(2) << 30);
  REQUIRE(one.files.size() == 5);
  const std::string items = itemsOf(one.carrier);
  // Recorded in the order given: normals, albedo, then the previews.
  const auto at = [&](const std::string& name) { return items.find("finished-files/" + name); };
  REQUIRE(at("preview-specular.png") != std::string::npos);
  CHECK(at("normals.png") < at("albedo.png"));
  CHECK(at("albedo.png") < at("preview-raking.png"));
  CHECK(at("preview-raking.png") < at("preview-top.png"));
  CHECK(at("preview-top.png") < at("preview-specular.png"));
  CHECK(items.find("normalFallbackPixels") != std::string::npos);
  // Two and four encoders, memory for every picture or (a budget whose eighth holds none of
  // them) only for as many as the encoders take at once.
  for (const int threads : {2, 4})
    for (const std::size_t memory : {std::size_t(2) << 30, std::size_t(1) << 20}) {
      CAPTURE(threads, memory);
      const Outcome other = derive(base / "other", threads, memory);
      CHECK(other.files == one.files);
      CHECK(itemsOf(other.carrier) == items);
    }
  fs::remove_all(base);
}

TEST_CASE("a picture DerivedMaps cannot write stops the step with the write's error, at any thread count") {
  const fs::path root = fs::temp_directory_path() / "surrogate-test-derived-maps-unwritable";
  for (const int threads : {1, 2}) {
    CAPTURE(threads);
    stages::registerBuiltinStages();
    fs::remove_all(root);
    fs::create_directories(root / "finished-files");
    // A folder where the preview is to be written: its atomic rename cannot replace it.
    fs::create_directories(root / "finished-files" / "preview-top.png" / "inside");
    carrier::Carrier c = carrier::newCarrier("derived maps", {});
    c.addStep("DerivedMaps", pipeline::StageRegistry::instance().create("DerivedMaps")->version())
        .setParam("model", "ptm-lrgb");
    pipeline::RunSettings settings;
    settings.threads = threads;
    pipeline::Context ctx(root, c, settings);
    ctx.put(stages::modelKey("ptm-lrgb"), std::shared_ptr<fit::Relightable>(std::make_shared<PatternModel>()));
    CHECK_THROWS_AS(pipeline::runProcess(ctx, {}), Error);
    REQUIRE(c.data.size() == 1);
    CHECK(c.data[0].status == "failed");
  }
  fs::remove_all(root);
}
