// publish::readWebLayout (src/publish/web_reader.h): a layout publish wrote gives back the
// model's scales and biases exactly and its bytes as OpenCV decodes the planes; a layout
// whose scales and biases differ per colour (as relight writes them) is re-quantised and still
// renders as the independent reader of web_reader.h renders it; removeInterruptedPublishes
// removes only a dead writer's own folders.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "fit/render.h"
#include "publish/interrupted_publish.h"
#include "publish/web_layout.h"
#include "publish/web_reader.h"
#include "dead_pid.h"
#include "synthetic_models.h"
#include "web_reader.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kW = 80, kH = 56;

// Smooth fields that differ along x and y and between terms and channels.
std::uint8_t field(int x, int y, int k, int c) { return test::smoothField(x, y, k, c, kH, 30.0); }

formats::PtmFile makePtm(formats::PtmFile::Format format) { return test::smoothPtm(format, kW, kH, 30.0); }

formats::HshFile makeHsh(int terms) { return test::smoothHsh(terms, kW, kH, 30.0); }

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path d = fs::temp_directory_path() / ("web-reader-" + name + "-" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Publishes `model` (written as `file`) into dir/web and returns that folder.
template <class Model>
fs::path published(const Model& model, const std::string& file, int quality) {
  const fs::path dir = freshDir("pub");
  if constexpr (std::is_same_v<Model, formats::PtmFile>) formats::writePtm(dir / file, model);
  else formats::writeRti(dir / file, model);
  publish::PublishOptions options;
  options.quality = quality;
  options.tiles = publish::TileLayout::None;
  publish::publish(dir / file, dir / "web", options);
  return dir / "web";
}

// Plane j of a layout as OpenCV decodes it, R, G, B per texel.
std::vector<std::uint8_t> openCvPlane(const fs::path& web, int j) {
  const cv::Mat bgr = cv::imread((web / ("plane_" + std::to_string(j) + ".jpg")).string(), cv::IMREAD_COLOR);
  std::vector<std::uint8_t> rgb;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x)
      for (int c = 0; c < 3; ++c) rgb.push_back(bgr.at<cv::Vec3b>(y, x)[2 - c]);
  return rgb;
}

const std::array<std::array<double, 3>, 4> kLights = {{{0, 0, 1}, {0.6, 0.3, 0.74}, {-0.5, -0.6, 0.62}, {0.9, -0.1, 0.42}}};

void writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

// `text` with its first `from` replaced by `to` (the test fails when there is none).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("readWebLayout gives back the scales and biases of the PTM it was published from and the planes' bytes") {
  for (const auto format : {formats::PtmFile::Format::Lrgb, formats::PtmFile::Format::Rgb}) {
    const formats::PtmFile ptm = makePtm(format);
    const fs::path web = published(ptm, "a.ptm", 90);
    const publish::WebLayoutModel read = publish::readWebLayout(web);
    REQUIRE(read.isPtm);
    CHECK_FALSE(read.requantised);
    CHECK(read.ptm.format == format);
    CHECK(read.ptm.scale == ptm.scale);
    CHECK(read.ptm.bias == ptm.bias);
    // Web term j (1, u, v, u^2, uv, v^2) is .ptm coefficient 5, 3, 4, 0, 2, 1 (docs/formats.md).
    const std::array<int, 6> ptmIndex = {5, 3, 4, 0, 2, 1};
    const bool lrgb = format == formats::PtmFile::Format::Lrgb;
    if (lrgb) CHECK(read.ptm.rgb == openCvPlane(web, 0));
    for (int j = 0; j < 6; ++j) {
      const int plane = lrgb ? 1 + j / 3 : j;
      const std::vector<std::uint8_t> cvPlane = openCvPlane(web, plane);
      std::size_t differing = 0;
      for (int c = 0; c < (lrgb ? 1 : 3); ++c)
        for (int y = 0; y < kH; ++y)
          for (int x = 0; x < kW; ++x) {
            const std::size_t at = (static_cast<std::size_t>(y) * kW + x) * 3 + static_cast<std::size_t>(lrgb ? j % 3 : c);
            differing += read.ptm.byte(x, y, ptmIndex[static_cast<std::size_t>(j)], c) != cvPlane[at];
          }
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("readWebLayout gives back the scales and biases of the HSH model it was published from") {
  const formats::HshFile hsh = makeHsh(9);
  const fs::path web = published(hsh, "a.rti", 100);
  const publish::WebLayoutModel read = publish::readWebLayout(web / "info.json");
  REQUIRE_FALSE(read.isPtm);
  CHECK_FALSE(read.requantised);
  CHECK(read.hsh.terms == 9);
  CHECK(read.hsh.scale == hsh.scale);
  CHECK(read.hsh.bias == hsh.bias);
  int largest = 0;
  for (std::size_t i = 0; i < hsh.coefficients.size(); ++i)
    largest = std::max(largest, std::abs(int(read.hsh.coefficients[i]) - int(hsh.coefficients[i])));
  WARN("HSH bytes after JPEG quality 100: largest change " << largest);
  CHECK(largest <= 3);  // smooth fields at quality 100: JPEG moves a byte by a few units at most
}

// A layout whose scales and biases differ per colour cannot keep its bytes in a .ptm or .rti
// (one scale and bias per term): each term is re-quantised over its range, an error of half
// a step, at most (range / 510) per coefficient. Against the independent reader evaluating the
// planes as they are, 40 dB is far above what a misread plane or colour gives (< 25 dB).
TEST_CASE("a layout with a scale and bias per colour is re-quantised and renders as the independent reader") {
  const fs::path hshWeb = published(makeHsh(9), "a.rti", 95);
  const fs::path ptmWeb = published(makePtm(formats::PtmFile::Format::Rgb), "b.ptm", 95);
  const fs::path lrgbWeb = published(makePtm(formats::PtmFile::Format::Lrgb), "c.ptm", 95);
  for (const fs::path& web : {hshWeb, ptmWeb, lrgbWeb}) {
    // Scale the green coefficients by 0.9 and shift the blue ones, as another writer could.
    std::string info = webtest::slurp(web / "info.json");
    const std::size_t scaleAt = info.find("\"scale\":[") + 9, scaleEnd = info.find(']', scaleAt);
    const std::size_t biasAt = info.find("\"bias\":[") + 8, biasEnd = info.find(']', biasAt);
    auto edit = [](const std::string& list, double factor, double shift, int channel) {
      std::string out;
      std::stringstream in(list);
      std::string item;
      for (int p = 0; std::getline(in, item, ','); ++p) {
        double v = std::stod(item);
        if (p % 3 == channel) v = v * factor + shift;
        out += (p ? "," : "") + std::to_string(v);
      }
      return out;
    };
    const std::string scale = edit(info.substr(scaleAt, scaleEnd - scaleAt), 0.9, 0, 1);
    const std::string bias = edit(info.substr(biasAt, biasEnd - biasAt), 1, 0.02, 2);
    info = info.substr(0, scaleAt) + scale + info.substr(scaleEnd, biasAt - scaleEnd) + bias + info.substr(biasEnd);
    writeText(web / "info.json", info);
    const publish::WebLayoutModel read = publish::readWebLayout(web);
    CHECK(read.requantised);
    const auto model = read.isPtm ? fit::makeRelightable(read.ptm) : fit::makeRelightable(read.hsh);
    const webtest::WebModel independent = webtest::readWebModel(web);
    double worst = INFINITY;
    for (const auto& l : kLights)
      worst = std::min(worst, webtest::psnr(test::renderedValues(*model, l), webtest::renderAt(independent, l[0], l[1], l[2])));
    const char* basis = !read.isPtm ? "HSH" : read.ptm.format == formats::PtmFile::Format::Lrgb ? "PTM LRGB" : "PTM RGB";
    WARN(basis << " re-quantised: worst PSNR " << worst << " dB against the independent reader");
    CHECK(worst >= 40);
  }
}

TEST_CASE("removeInterruptedPublishes removes only the folders of a writer that no longer runs") {
  const fs::path parent = freshDir("leftovers");
  const std::string dead = std::to_string(publishtest::deadPid());
  const std::string alive = std::to_string(::getppid());
  const fs::path gone = parent / (".web.partial-" + dead + "-Ab12Cd");
  const fs::path running = parent / (".web.partial-" + alive + "-Ab12Cd");
  const fs::path mine = parent / (".web.partial-" + std::to_string(::getpid()) + "-Ab12Cd");
  const fs::path link = parent / (".lnk.partial-" + dead + "-Ab12Cd");
  const fs::path file = parent / (".f.partial-" + dead + "-Ab12Cd");
  const fs::path odd = parent / (".web.partial-" + dead + "-Ab12Cd-more");
  const fs::path target = parent / "kept";
  for (const fs::path& d : {gone, running, mine, odd, target}) {
    fs::create_directories(d);
    writeText(d / "x", "x");
  }
  fs::create_directory_symlink(target, link);
  writeText(file, "x");
  const auto removed = publish::removeInterruptedPublishes(parent / "anything");
  REQUIRE(removed.size() == 1);
  CHECK(removed[0] == "removed " + gone.string() + ", the partial folder of a publish that did not finish (process " +
                          dead + " no longer runs)");
  CHECK(!fs::exists(gone));
  for (const fs::path& p : {running, mine, odd, target}) CHECK(fs::exists(p / "x"));
  CHECK(fs::is_symlink(link));
  CHECK(fs::exists(file));
  CHECK(publish::stagingPattern(parent / "web") == (parent / (".web.partial-" + std::to_string(::getpid()) + "-XXXXXX")).string());
}

TEST_CASE("readWebLayout decodes a plane coded as YCbCr as OpenCV does") {
  const fs::path web = published(makePtm(formats::PtmFile::Format::Lrgb), "a.ptm", 95);
  cv::Mat picture(kH, kW, CV_8UC3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) picture.at<cv::Vec3b>(y, x) = cv::Vec3b(field(x, y, 1, 0), field(x, y, 2, 1), field(x, y, 3, 2));
  // OpenCV writes an ordinary JFIF: YCbCr with 4:2:0 chroma, as another tool's planes may be.
  REQUIRE(cv::imwrite((web / "plane_0.jpg").string(), picture, {cv::IMWRITE_JPEG_QUALITY, 90}));
  const publish::WebLayoutModel read = publish::readWebLayout(web);
  CHECK(read.ptm.rgb == openCvPlane(web, 0));
}

TEST_CASE("readWebLayout assembles Deep Zoom tiles numbered from one tile or from one texel") {
  const formats::HshFile hsh = makeHsh(4);
  const fs::path whole = published(hsh, "a.rti", 90);
  const fs::path dir = freshDir("tiles");
  formats::writeRti(dir / "a.rti", hsh);
  publish::PublishOptions options;
  options.quality = 90;
  options.tiles = publish::TileLayout::DeepZoom;
  options.tileSize = 16;
  publish::publish(dir / "a.rti", dir / "web", options);
  // 80x56 in tiles of 16: levels 0..3 from the first that fits in one tile; 0..7 from 1x1.
  REQUIRE(fs::is_directory(dir / "web" / "plane_0_files" / "3"));
  const publish::WebLayoutModel fromTiles = publish::readWebLayout(dir / "web");
  const publish::WebLayoutModel fromPlanes = publish::readWebLayout(whole);
  int largest = 0;
  for (std::size_t i = 0; i < hsh.coefficients.size(); ++i)
    largest = std::max(largest, std::abs(int(fromTiles.hsh.coefficients[i]) - int(fromPlanes.hsh.coefficients[i])));
  WARN("tiles of 16 against whole planes at quality 90: largest byte difference " << largest);
  CHECK(largest <= 8);  // each compressed on its own: the JPEG error twice at most, on smooth fields
  for (int j = 0; j < 4; ++j)
    fs::rename(dir / "web" / ("plane_" + std::to_string(j) + "_files") / "3",
               dir / "web" / ("plane_" + std::to_string(j) + "_files") / "7");
  const publish::WebLayoutModel renumbered = publish::readWebLayout(dir / "web");
  CHECK(renumbered.hsh.coefficients == fromTiles.hsh.coefficients);
}

// Each damaged layout is refused with Error(Input) naming the file at fault, and nothing is
// read past a buffer (the AddressSanitizer build runs this too).
TEST_CASE("readWebLayout refuses damaged planes tiles and descriptors naming the file") {
  const fs::path whole = published(makeHsh(4), "a.rti", 90);
  const fs::path tiledDir = freshDir("hostile-tiles");
  formats::writeRti(tiledDir / "a.rti", makeHsh(4));
  publish::PublishOptions options;
  options.tiles = publish::TileLayout::DeepZoom;
  options.tileSize = 32;
  publish::publish(tiledDir / "a.rti", tiledDir / "web", options);
  const fs::path tiled = tiledDir / "web";
  auto refusedNaming = [](const fs::path& layout, const fs::path& file, const std::string& words) {
    try {
      publish::readWebLayout(layout);
      FAIL("accepted " << file);
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file() == file.string());
      CHECK(e.message().find(words) != std::string::npos);
    }
  };
  const std::string jpeg = webtest::slurp(whole / "plane_1.jpg");
  for (std::size_t cut : {std::size_t{2}, std::size_t{200}, jpeg.size() / 2, jpeg.size() - 2}) {
    writeText(whole / "plane_1.jpg", jpeg.substr(0, cut));
    refusedNaming(whole, whole / "plane_1.jpg", "is not a JPEG plane that decodes cleanly");
  }
  std::string flipped = jpeg;
  for (std::size_t i = jpeg.size() / 3; i < jpeg.size() - 2; i += 97) flipped[i] = static_cast<char>(flipped[i] ^ 0x5a);
  writeText(whole / "plane_1.jpg", flipped);
  refusedNaming(whole, whole / "plane_1.jpg", "is not a JPEG plane that decodes cleanly");
  writeText(whole / "plane_1.jpg", jpeg);

  const fs::path tile = tiled / "plane_2_files" / "2" / "1_1.jpg";
  const std::string tileBytes = webtest::slurp(tile);
  cv::imwrite(tile.string(), cv::Mat(10, 10, CV_8UC3, cv::Scalar(0, 0, 0)));
  refusedNaming(tiled, tile, "is 10x10 pixels");
  fs::remove(tile);
  refusedNaming(tiled, tile, "is missing");
  writeText(tile, tileBytes);
  const std::string dzi = webtest::slurp(tiled / "plane_3.dzi");
  for (const std::string& bad : {std::string("<Image"), std::string("<!DOCTYPE x [<!ENTITY a \"aaaa\">]><x>&a;</x>"),
                                 replaced(dzi, "Width=\"80\"", "Width=\"81\""),
                                 replaced(dzi, "TileSize=\"32\"", "TileSize=\"1\""),
                                 replaced(dzi, "Format=\"jpg\"", "Format=\"png\"")}) {
    writeText(tiled / "plane_3.dzi", bad);
    refusedNaming(tiled, tiled / "plane_3.dzi", "is not a Deep Zoom descriptor render reads");
  }
}
