// Learned bases (fit/learned.h) in the web layout: written by publish/learned_layout.h, read
// back by readWebLayout, drawn by the independent decoder of learned_decoder.h (written from
// docs/formats.md, no code shared with src/) and compared with fit::renderLearned; a layout as
// relight-cli writes it; closed forms (a light on a node, a Lambertian basis); bad layouts.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "fit/learned_relightable.h"
#include "publish/learned_layout.h"
#include "publish/web_reader.h"
#include "learned_decoder.h"
#include "learned_samples.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path d = fs::temp_directory_path() / ("learned-layout-" + name + "-" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d.parent_path());
  return d;
}

fit::LearnedModel handMade(fit::LearnedKind kind) { return learnedsample::handMade(kind, 16, 12); }

fs::path written(const fit::LearnedModel& m, const std::string& name, int quality = 100) {
  publish::PublishOptions o;
  o.quality = quality;
  o.tiles = publish::TileLayout::None;
  const fs::path dir = freshDir(name);
  publish::writeWebLayoutFolder(publish::webLayoutOf(m, o), dir);
  return dir;
}

std::vector<int> bytesOf(const Image& image) {
  std::vector<int> v;
  for (std::uint16_t s : image.pixels) v.push_back(s / 257);
  return v;
}

int maxDifference(const std::vector<int>& a, const std::vector<int>& b) {
  REQUIRE(a.size() == b.size());
  int worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

const std::vector<std::array<double, 3>> kLights = {{0, 0, 1}, {0.6, 0.3, 0.74}, {-0.5, -0.6, 0.62}, {0.9, -0.1, 0.42}, {-0.2, 0.8, 0.57}};


}  // namespace

TEST_CASE("a learned layout reads back with its basis materials and lights exact and its planes within the JPEG error") {
  for (fit::LearnedKind kind : {fit::LearnedKind::Rbf, fit::LearnedKind::Bilinear}) {
    const fit::LearnedModel m = handMade(kind);
    const fs::path dir = written(m, "trip");
    const publish::WebLayoutModel web = publish::readWebLayout(dir);
    REQUIRE(web.isLearned);
    const fit::LearnedModel& r = web.learned;
    CHECK(r.kind == kind);
    CHECK(r.width == 16);
    CHECK(r.height == 12);
    CHECK(r.planes == 9);
    CHECK(r.resolution == m.resolution);
    CHECK(r.lights == m.lights);
    CHECK(r.basis == m.basis);
    CHECK(r.range == m.range);  // 9 significant digits read back as the same floats
    CHECK(r.scale == m.scale);
    CHECK(r.bias == m.bias);
    REQUIRE(r.coefficients.size() == m.coefficients.size());
    int worst = 0;
    for (std::size_t i = 0; i < m.coefficients.size(); ++i) worst = std::max(worst, std::abs(r.coefficients[i] - m.coefficients[i]));
    CHECK(worst <= 2);
    const publish::WebLayoutSummary s = publish::describeWebLayout(dir / "info.json");
    CHECK(s.basis == (kind == fit::LearnedKind::Rbf ? "rbf" : "bln"));
    CHECK(s.nodes == (kind == fit::LearnedKind::Rbf ? 12 : 36));
    CHECK(s.resolution == m.resolution);
    CHECK(s.missingPlanes.empty());
    CHECK(s.quality == 100);
  }
}

TEST_CASE("the independent decoder draws a written learned layout as renderLearned draws the model") {
  for (fit::LearnedKind kind : {fit::LearnedKind::Rbf, fit::LearnedKind::Bilinear}) {
    const fit::LearnedModel m = handMade(kind);
    const fs::path dir = written(m, "decoder");
    const learnedtest::Layout layout = learnedtest::readLayout(dir);
    const auto readBack = fit::makeRelightable(publish::readWebLayout(dir).learned);
    for (const auto& light : kLights) {
      const std::vector<int> decoded = learnedtest::renderAt(layout, light);
      INFO("kind " << fit::learnedKindName(kind) << ", light " << light[0] << "," << light[1] << "," << light[2]);
      CHECK(maxDifference(decoded, bytesOf(fit::renderLearned(m, light))) <= 2);
      CHECK(maxDifference(decoded, bytesOf(readBack->render(light, {}))) <= 1);
      int spread = 0;  // the test means something only if the picture is not flat or clipped
      for (int v : decoded) spread = std::max(spread, std::abs(v - decoded[0]));
      CHECK(spread > 8);
    }
  }
}

TEST_CASE("per-plane JPEG qualities are used and info.json gives the highest") {
  const fit::LearnedModel m = handMade(fit::LearnedKind::Bilinear);
  publish::PublishOptions o;
  o.planeQualities = {100, 60, 30};
  const publish::WebLayoutFiles files = publish::webLayoutOf(m, o);
  REQUIRE(files.files.size() == 4);
  CHECK(files.files[0].second.find("\"quality\": 100,") != std::string::npos);
  CHECK(files.files[1].second.size() > files.files[2].second.size());
  CHECK(files.files[2].second.size() > files.files[3].second.size());
  o.planeQualities = {90, 90};
  CHECK_THROWS_AS(publish::webLayoutOf(m, o), Error);
}

TEST_CASE("a quality ramp goes from the first plane to the last in equal rounded steps") {
  publish::PublishOptions o;
  o.quality = 90;
  o.lastQuality = 40;
  // 90 + (40 - 90) j / 14, rounded: 90, 86.4, 82.9, 79.3, ... 43.6, 40.
  const std::vector<int> expected = {90, 86, 83, 79, 76, 72, 69, 65, 61, 58, 54, 51, 47, 44, 40};
  CHECK(publish::planeQualitiesOf(o, 15) == expected);
  CHECK(publish::planeQualitiesOf(o, 1) == std::vector<int>{90});
  o.lastQuality = 0;  // no ramp: one quality for all
  CHECK(publish::planeQualitiesOf(o, 3) == std::vector<int>{90, 90, 90});
}

TEST_CASE("closed forms: a light on a bilinear node and a light halfway between two rbf nodes") {
  // Bilinear R = 5: the light (0, 0, 1) falls on node (2, 2) = 12 with weight 1. Plane 0 byte
  // 200, plane 1 byte 177 with range 250 (+0.2), coefficient (255 / 255 - 0) * 1 = 1, the
  // others 0: 200 / 255 + 0.2 = 0.98431 -> 251.
  fit::LearnedModel m;
  m.kind = fit::LearnedKind::Bilinear;
  m.width = 8;
  m.height = 8;
  m.planes = 3;
  m.resolution = 5;
  m.basis.assign(4 * 25 * 3, 127);
  for (int n = 0; n < 25; ++n)
    for (int k = 0; k < 3; ++k) m.basis[static_cast<std::size_t>(n) * 3 + k] = 60;
  for (int k = 0; k < 3; ++k) m.basis[12 * 3 + k] = 200, m.basis[(25 + 12) * 3 + k] = 177;
  m.range = {250, 250, 250};
  m.scale = {1, 1, 1};
  m.bias = {0, 0, 0};
  for (int t = 0; t < 64; ++t) m.coefficients.insert(m.coefficients.end(), {255, 0, 0});
  const auto bln = fit::makeRelightable(publish::readWebLayout(written(m, "node")).learned);
  CHECK(bytesOf(bln->render({0, 0, 1}, {})) == std::vector<int>(64 * 3, 251));
  CHECK(learnedtest::renderAt(learnedtest::readLayout(written(m, "node")), {0, 0, 1}) == std::vector<int>(64 * 3, 251));
  // RBF, lights (+-0.6, 0, 0.8): at (0, 0, 1) both are at the same distance, weights 1/2 each
  // whatever the kernel's width: plane 0 bytes 100 and 200 give 150 / 255 -> 150.
  m.kind = fit::LearnedKind::Rbf;
  m.resolution = 0;
  m.lights = {{0.6, 0, 0.8}, {-0.6, 0, 0.8}};
  m.basis.assign(4 * 2 * 3, 127);
  for (int k = 0; k < 3; ++k) m.basis[static_cast<std::size_t>(k)] = 100, m.basis[3 + static_cast<std::size_t>(k)] = 200;
  const auto rbf = fit::makeRelightable(publish::readWebLayout(written(m, "midway")).learned);
  CHECK(bytesOf(rbf->render({0, 0, 1}, {})) == std::vector<int>(64 * 3, 150));
}

TEST_CASE("the normals of a learned model whose mean is Lambertian are its normal") {
  // Bilinear R = 16, every node of plane 0 is 0.8 max(0, n . d) at the node's direction d, the
  // other planes 0: the viewer's interpolation of a Lambertian surface of albedo 0.8 (in the
  // stored units) and normal n.
  const std::array<double, 3> n = {0.3 / 0.9881, -0.2 / 0.9881, 0.93 / 0.9881};
  fit::LearnedModel m;
  m.kind = fit::LearnedKind::Bilinear;
  m.width = m.height = 4;
  m.planes = 3;
  m.resolution = 16;
  m.basis.assign(4 * 256 * 3, 127);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double u = 2.0 * x / 15 - 1, v = 2.0 * y / 15 - 1;  // the square, turned back by 45 degrees
      const double dx = (u - v) / 2, dy = (u + v) / 2, dz = std::max(0.0, 1 - std::fabs(dx) - std::fabs(dy));
      const double len = std::hypot(dx, dy, dz);
      const double value = 0.8 * std::max(0.0, (n[0] * dx + n[1] * dy + n[2] * dz) / len);
      for (int k = 0; k < 3; ++k) m.basis[static_cast<std::size_t>(x + y * 16) * 3 + k] = static_cast<std::uint8_t>(std::lround(255 * value));
    }
  m.range = {100, 100, 100};
  m.scale = {1, 1, 1};
  m.bias = {0, 0, 0};
  m.coefficients.assign(16 * 3, 0);
  const auto model = fit::makeRelightable(m);
  int fallbacks = -1;
  const Image normals = model->normalMap(&fallbacks);
  CHECK(fallbacks == 0);
  double dot = 0;
  for (int c = 0; c < 3; ++c) dot += (normals.at(1, 2, c) / 65535.0 * 2 - 1) * n[static_cast<std::size_t>(c)];
  CHECK(std::acos(std::min(1.0, dot)) * 180 / M_PI < 3.0);
  const Image albedo = model->albedoMap();
  CHECK(std::abs(albedo.at(2, 1, 0) / 257 - 204) <= 3);  // 0.8 * 255
  CHECK(model->basis() == "bln");
  fit::RenderOptions gain;
  gain.diffuseGain = 2;
  fit::RenderOptions specular;
  specular.specular = true;
  for (const auto& [options, name] : {std::make_pair(gain, "--gain"), std::make_pair(specular, "--specular")}) {
    try {
      model->render({0, 0, 1}, options);
      FAIL("not refused");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Usage);
      CHECK(e.file() == name);
      CHECK_THAT(e.message(), Catch::Contains("closed-form normal"));
    }
  }
}
