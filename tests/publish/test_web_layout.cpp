// The web layout (src/publish) read back by the independent reader of web_reader.h: each
// basis renders as fit::render (what `surrogate render` calls) renders the source, within
// the JPEG error; the planes keep the model's bytes and rows; publishing is deterministic and
// writes nothing over an existing folder.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "fit/render.h"
#include "publish/web_layout.h"
#include "synthetic_models.h"
#include "web_reader.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kW = 96, kH = 64;

// Models of smooth coefficients (synthetic_models.h): a swapped plane, channel or a flipped
// row order shows as a large error.
formats::PtmFile makePtm(formats::PtmFile::Format format, int w = kW, int h = kH) {
  return test::smoothPtm(format, w, h, 40.0);
}

formats::HshFile makeHsh(int terms) { return test::smoothHsh(terms, kW, kH, 40.0); }

const std::array<std::array<double, 3>, 5> kLights = {{
    {0, 0, 1}, {0.6, 0.3, 0.74}, {-0.5, -0.6, 0.62}, {0.9, -0.1, 0.42}, {-0.2, 0.95, 0.24}}};

fs::path freshDir(const std::string& name) {
  static int counter = 0;
  const fs::path d = fs::temp_directory_path() /
                     ("surrogate-publish-test-" + std::to_string(::getpid()) + "-" + name + "-" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void writeModel(const fs::path& file, const formats::PtmFile& ptm) { formats::writePtm(file, ptm); }
void writeModel(const fs::path& file, const formats::HshFile& hsh) { formats::writeRti(file, hsh); }

struct Worst {
  double psnr = INFINITY;
  int maxDiff = 0;
};

// Publishes `model` at `quality` and compares the reader's renders with fit::render's.
template <class Model>
Worst publishAndCompare(const Model& model, const std::string& fileName, int quality) {
  const fs::path dir = freshDir("cmp");
  writeModel(dir / fileName, model);
  publish::PublishOptions options;
  options.quality = quality;
  publish::publish(dir / fileName, dir / "web", options);
  const webtest::WebModel web = webtest::readWebModel(dir / "web");
  const auto reference = fit::openRelightable(dir / fileName);
  Worst worst;
  for (const auto& l : kLights) {
    const auto a = webtest::renderAt(web, l[0], l[1], l[2]);
    const auto b = test::renderedValues(*reference, l);
    worst.psnr = std::min(worst.psnr, webtest::psnr(a, b));
    worst.maxDiff = std::max(worst.maxDiff, webtest::maxAbsDifference(a, b));
  }
  fs::remove_all(dir);
  return worst;
}

}  // namespace

TEST_CASE("publish writes info.json and the planes the web viewers request for each basis") {
  struct Case {
    std::string file, type, colorspace;
    int nplanes;
  };
  const fs::path dir = freshDir("names");
  writeModel(dir / "lrgb.ptm", makePtm(formats::PtmFile::Format::Lrgb));
  writeModel(dir / "rgb.ptm", makePtm(formats::PtmFile::Format::Rgb));
  writeModel(dir / "hsh2.rti", makeHsh(4));
  writeModel(dir / "hsh3.rti", makeHsh(9));
  for (const Case& c : {Case{"lrgb.ptm", "ptm", "lrgb", 9}, Case{"rgb.ptm", "ptm", "rgb", 18},
                        Case{"hsh2.rti", "hsh", "rgb", 12}, Case{"hsh3.rti", "hsh", "rgb", 27}}) {
    INFO(c.file);
    const fs::path out = dir / ("web-" + c.file);
    const auto models = publish::publish(dir / c.file, out, {});
    REQUIRE(models.size() == 1);
    const webtest::Json info = webtest::JsonParser(webtest::slurp(out / "info.json")).parseDocument();
    CHECK(info["type"].text == c.type);
    CHECK(info["colorspace"].text == c.colorspace);
    CHECK(info["nplanes"].number == c.nplanes);
    CHECK(info["width"].number == kW);
    CHECK(info["height"].number == kH);
    CHECK(info["format"].text == "jpg");
    CHECK(info["quality"].number == 95);
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(out)) files += e.is_regular_file();
    CHECK(files == 1 + static_cast<std::size_t>(c.nplanes / 3) + 2);  // and index.html, viewer-data.js
    CHECK(fs::is_regular_file(out / "index.html"));
    CHECK(fs::is_regular_file(out / "viewer-data.js"));
    for (int j = 0; j < c.nplanes / 3; ++j) CHECK(fs::is_regular_file(out / ("plane_" + std::to_string(j) + ".jpg")));
  }
  fs::remove_all(dir);
}

// Tolerance at quality 100: JPEG changes a byte by at most a few units, which moves a relit
// value by a few levels; a wrong plane, channel, term order, bias convention or row order
// moves it by tens (the fields above vary by +-80 bytes).
constexpr int kMaxDifferenceAtQuality100 = 4;
constexpr double kMinPsnrAtQuality100 = 45;

TEST_CASE("the independent reader renders the published PTM LRGB as surrogate render renders the .ptm") {
  const Worst w = publishAndCompare(makePtm(formats::PtmFile::Format::Lrgb), "m.ptm", 100);
  CHECK(w.maxDiff <= kMaxDifferenceAtQuality100);
  CHECK(w.psnr >= kMinPsnrAtQuality100);
}

TEST_CASE("the independent reader renders the published PTM RGB as surrogate render renders the .ptm") {
  const Worst w = publishAndCompare(makePtm(formats::PtmFile::Format::Rgb), "m.ptm", 100);
  CHECK(w.maxDiff <= kMaxDifferenceAtQuality100);
  CHECK(w.psnr >= kMinPsnrAtQuality100);
}

TEST_CASE("the independent reader renders the published HSH order 2 and 3 as surrogate render renders the .rti") {
  for (int terms : {4, 9}) {
    INFO(terms << " terms");
    const Worst w = publishAndCompare(makeHsh(terms), "m.rti", 100);
    CHECK(w.maxDiff <= kMaxDifferenceAtQuality100);
    CHECK(w.psnr >= kMinPsnrAtQuality100);
  }
}

TEST_CASE("an HSH term with scale 0 is published as its constant") {
  formats::HshFile h = makeHsh(4);
  h.scale[2] = 0;
  h.bias[2] = 0.25f;
  const Worst w = publishAndCompare(h, "m.rti", 100);
  CHECK(w.maxDiff <= kMaxDifferenceAtQuality100);
}

// The relit error per JPEG quality on the smooth fields above (the measured values are
// printed; docs/formats.md gives those of a fitted capture).
TEST_CASE("the relit error grows as the JPEG quality falls and stays bounded at 75") {
  const auto lrgb = makePtm(formats::PtmFile::Format::Lrgb);
  const auto hsh = makeHsh(9);
  double previousPtm = INFINITY, previousHsh = INFINITY;
  for (int q : {100, 90, 75}) {
    const Worst p = publishAndCompare(lrgb, "m.ptm", q);
    const Worst h = publishAndCompare(hsh, "m.rti", q);
    WARN("quality " << q << ": PTM LRGB worst PSNR " << p.psnr << " dB (max " << p.maxDiff << "), HSH3 "
                    << h.psnr << " dB (max " << h.maxDiff << ")");
    CHECK(p.psnr <= previousPtm);
    CHECK(h.psnr <= previousHsh);
    CHECK(p.psnr >= 30);
    CHECK(h.psnr >= 30);
    previousPtm = p.psnr;
    previousHsh = h.psnr;
  }
}

TEST_CASE("the colour plane of a PTM LRGB keeps the model's bytes and rows top-first") {
  const fs::path dir = freshDir("rows");
  const auto ptm = makePtm(formats::PtmFile::Format::Lrgb);
  writeModel(dir / "m.ptm", ptm);
  publish::PublishOptions options;
  options.quality = 100;
  publish::publish(dir / "m.ptm", dir / "web", options);
  const cv::Mat bgr = cv::imread((dir / "web" / "plane_0.jpg").string(), cv::IMREAD_COLOR);
  REQUIRE(bgr.rows == kH);
  int worst = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(int(bgr.at<cv::Vec3b>(y, x)[2 - c]) -
                                         int(ptm.rgb[(static_cast<std::size_t>(y) * kW + x) * 3 + c])));
  CHECK(worst <= 2);
  fs::remove_all(dir);
}

TEST_CASE("publishing twice gives identical bytes") {
  const fs::path dir = freshDir("twice");
  writeModel(dir / "m.rti", makeHsh(9));
  publish::PublishOptions options;
  options.quality = 90;
  publish::publish(dir / "m.rti", dir / "a", options);
  publish::publish(dir / "m.rti", dir / "b", options);
  std::size_t compared = 0;
  for (const auto& e : fs::directory_iterator(dir / "a")) {
    INFO(e.path().filename().string());
    CHECK(webtest::slurp(e.path()) == webtest::slurp(dir / "b" / e.path().filename()));
    ++compared;
  }
  CHECK(compared == 12);  // info.json, nine planes, index.html, viewer-data.js
  fs::remove_all(dir);
}

TEST_CASE("publish refuses a folder that is not empty and leaves it as it was") {
  const fs::path dir = freshDir("refuse");
  writeModel(dir / "m.ptm", makePtm(formats::PtmFile::Format::Lrgb));
  fs::create_directories(dir / "web");
  { std::ofstream(dir / "web" / "mine.txt") << "not Surrogate's"; }
  CHECK_THROWS_AS(publish::publish(dir / "m.ptm", dir / "web", {}), Error);
  CHECK(webtest::slurp(dir / "web" / "mine.txt") == "not Surrogate's");
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string()[0] == '.';
  CHECK(entries == 0);  // no partial folder left beside it
  fs::remove_all(dir);
}

TEST_CASE("publish into an existing empty folder fills it") {
  const fs::path dir = freshDir("empty");
  writeModel(dir / "m.ptm", makePtm(formats::PtmFile::Format::Rgb));
  fs::create_directories(dir / "web");
  publish::publish(dir / "m.ptm", dir / "web", {});
  CHECK(fs::is_regular_file(dir / "web" / "plane_5.jpg"));
  fs::remove_all(dir);
}

TEST_CASE("publish refuses HSH order 4 and a quality outside 1 to 100") {
  CHECK_THROWS_AS(publish::webLayoutOf(makeHsh(16), {}), Error);
  publish::PublishOptions bad;
  bad.quality = 0;
  CHECK_THROWS_AS(publish::webLayoutOf(makeHsh(4), bad), Error);
  bad.quality = 101;
  CHECK_THROWS_AS(publish::webLayoutOf(makePtm(formats::PtmFile::Format::Lrgb), bad), Error);
}

TEST_CASE("describeWebLayout reads back what publish wrote and names a missing plane") {
  const fs::path dir = freshDir("describe");
  writeModel(dir / "m.rti", makeHsh(4));
  publish::PublishOptions options;
  options.quality = 80;
  publish::publish(dir / "m.rti", dir / "web", options);
  publish::WebLayoutSummary s = publish::describeWebLayout(dir / "web" / "info.json");
  CHECK(s.type == "hsh");
  CHECK(s.colorspace == "rgb");
  CHECK(s.basis == "hsh2");
  CHECK(s.width == kW);
  CHECK(s.height == kH);
  CHECK(s.nplanes == 12);
  CHECK(s.quality == 80);
  CHECK(s.planes == std::vector<std::string>{"plane_0.jpg", "plane_1.jpg", "plane_2.jpg", "plane_3.jpg"});
  CHECK(s.missingPlanes.empty());
  std::uintmax_t bytes = 0;  // the layout's own files: not the viewer beside them
  for (const auto& e : fs::directory_iterator(dir / "web"))
    if (e.path().extension() != ".html" && e.path().extension() != ".js") bytes += fs::file_size(e.path());
  CHECK(s.bytes == bytes);
  fs::remove(dir / "web" / "plane_2.jpg");
  s = publish::describeWebLayout(dir / "web" / "info.json");
  CHECK(s.missingPlanes == std::vector<std::string>{"plane_2.jpg"});
  fs::remove_all(dir);
}

TEST_CASE("describeWebLayout refuses text that is not JSON or lacks what the viewers need") {
  const fs::path dir = freshDir("describe-bad");
  const auto refused = [&](const std::string& text) {
    { std::ofstream(dir / "info.json", std::ios::binary) << text; }
    try {
      publish::describeWebLayout(dir / "info.json");
    } catch (const Error& e) {
      return e.kind() == ErrorKind::Input;
    }
    return false;
  };
  const std::string material = R"("materials":[{"scale":[1,1,1],"bias":[0,0,0]}])";
  CHECK_FALSE(refused(R"({"width":4,"height":3,"type":"ptm","colorspace":"rgb","nplanes":3,)" + material + "}"));
  CHECK(refused(R"({"width":4,"height":3,"type":"ptm","colorspace":"rgb","nplanes":3,)" + material));  // unclosed
  CHECK(refused(R"({"width":4,"height":3,"type":"ptm","nplanes":3,)" + material + "}"));  // no colorspace
  CHECK(refused(R"({"width":4.5,"height":3,"type":"ptm","colorspace":"rgb","nplanes":3,)" + material + "}"));
  CHECK(refused(R"({"width":4,"height":3,"type":"ptm","colorspace":"rgb","nplanes":6,)" + material + "}"));
  CHECK(refused(std::string(100, '[') + std::string(100, ']')));  // nested too deeply
  CHECK(refused("[1,2]"));
  fs::remove_all(dir);
}

// The reader is OpenCV's FileStorage with a check before it (src/publish/info_json.cpp): what
// FileStorage would crash on (deep nesting), stop at (a NUL byte), ignore (text after the object)
// or misread (010, 4294967300) is refused, and its own errors become an Error(Input).
TEST_CASE("describeWebLayout says what is wrong with malformed or hostile JSON, naming the file") {
  const fs::path dir = freshDir("describe-malformed");
  const fs::path file = dir / "info.json";
  const std::string material = R"("materials":[{"scale":[1,1,1],"bias":[0,0,0]}])";
  const std::string good = R"({"width":4,"height":3,"type":"ptm","colorspace":"rgb","nplanes":3,)" + material + "}";
  // The sentence of the Error(Input) describeWebLayout throws, "" when it reads the text.
  const auto refusal = [&](const std::string& text) -> std::string {
    { std::ofstream(file, std::ios::binary) << text; }
    try {
      publish::describeWebLayout(file);
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file() == file.string());
      return e.message();
    } catch (...) {
      FAIL("describeWebLayout let an exception other than surrogate::Error out");
    }
    return "";
  };
  const auto says = [](const std::string& message, const std::string& what) {
    INFO(message);
    CHECK(message.find(what) != std::string::npos);
  };
  CHECK(refusal(good).empty());
  CHECK(refusal("\xEF\xBB\xBF" + good + "\n").empty());  // a byte order mark, a final newline
  CHECK(refusal("\xEF\xBB\xBF \r\n\t" + good).empty());  // space before the object
  // FileStorage's own refusal, its line counted from the start of the file.
  says(refusal("\n\n" R"({"width":4,)" "\n" R"("height":})"), "at line 4");
  says(refusal(""), "it is empty");
  says(refusal("[1,2]"), "it is not a JSON object");
  says(refusal(good.substr(0, good.size() - 1)), "it ends before its brackets close");
  says(refusal(good + " {}"), "there is more text after the JSON object");
  says(refusal(good + std::string(1, '\0') + "x"), "NUL byte");
  says(refusal(R"({"width":4,"type":"ptm)"), "a string is not closed");
  says(refusal(R"({"width":010})"), "neither a string, a number");
  says(refusal(R"({"width":0x10})"), "neither a string, a number");
  says(refusal(R"({"width":4294967300})"), "outside -2147483648 to 2147483647");
  says(refusal(R"({"width":99999999999999999999999999999})"), "outside -2147483648 to 2147483647");
  says(refusal(R"({"width":1e999})"), "too large for a double");
  says(refusal(R"({"width":4,"width":5})"), "\"width\" is given twice");
  says(refusal(R"({"width":4,)" "\n" R"("height":})"), "at line 2");  // FileStorage's own refusal
  says(refusal("{\"type\":\"pt\x1Bm\"}"), "a string holds a control character");
  says(refusal(R"({"type":null})"), "OpenCV's FileStorage");
  // Nesting: FileStorage recurses once per level and overflows the stack at some 50 000.
  const int deep = 200000;
  says(refusal("{\"a\":" + std::string(deep, '[') + std::string(deep, ']') + "}"), "nested too deeply");
  std::string maps;
  for (int i = 0; i < deep; ++i) maps += "{\"a\":";
  says(refusal(maps + "1" + std::string(deep, '}')), "nested too deeply");
  const std::size_t deepest = 63;  // within the object: 64 levels, the most the reader takes
  CHECK(refusal("{\"a\":" + std::string(deepest, '[') + std::string(deepest, ']') + "," + good.substr(1)).empty());
  says(refusal("{\"a\":" + std::string(deepest + 1, '[') + std::string(deepest + 1, ']') + "," + good.substr(1)),
       "nested too deeply");
  // relight's PCA bases: megabytes of numbers beside the members the viewers need.
  std::string basis = R"({"basis":[)";
  for (int i = 0; i < 200000; ++i) basis += (i ? "," : "") + std::to_string(i % 997 - 498) + ".125e-3";
  CHECK(refusal(basis + "]," + good.substr(1)).empty());
  // JSON is UTF-8; FileStorage would pass Latin-1 bytes into the type that `info --json` prints.
  const std::string utf8 =
      R"({"width":4,"height":3,"type":"pt)" "\xC3\xA9" R"(","colorspace":"rgb","nplanes":3,)" + material + "}";
  CHECK(refusal(utf8).empty());
  CHECK(publish::describeWebLayout(file).type == "pt\xC3\xA9");
  CHECK(publish::describeWebLayout(file).basis.empty());
  std::string latin1 = utf8;
  latin1.replace(latin1.find("\xC3\xA9"), 2, "\xE9");
  says(refusal(latin1), "not UTF-8");
  says(refusal(R"({"type":"pt)" "\xED\xA0\x80" R"("})"), "not UTF-8");  // a UTF-16 surrogate
  says(refusal(R"({"type":"pt)" "\xC0\xAF" R"("})"), "not UTF-8");      // an overlong '/'
  says(refusal(std::string("\xFF\xFE{\0\"\0", 6)), "NUL byte");  // UTF-16
  fs::remove_all(dir);
}

// JSON's escapes, which FileStorage refuses (\u, \/) or reads only in values, are read as the
// characters they stand for (src/publish/info_json.cpp); a malformed one is refused by name.
TEST_CASE("describeWebLayout reads JSON escapes, surrogate pairs included, and refuses malformed ones") {
  const fs::path dir = freshDir("describe-escapes");
  const fs::path file = dir / "info.json";
  const std::string rest = R"("colorspace":"rgb","nplanes":3,"materials":[{"scale":[1,1,1],"bias":[0,0,0]}]})";
  const auto read = [&](const std::string& type, const std::string& key = "type") {
    { std::ofstream(file, std::ios::binary) << "{\"width\":4,\"height\":3,\"" + key + "\":\"" + type + "\"," + rest; }
    return publish::describeWebLayout(file);
  };
  const auto refusal = [&](const std::string& type) -> std::string {
    try {
      read(type);
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file() == file.string());
      return e.message();
    }
    return "";
  };
  CHECK(read(R"(\u0070tm)").type == "ptm");
  CHECK(read(R"(\u0050\u0074M)").type == "PtM");
  CHECK(read(R"(a\/b)").type == "a/b");
  CHECK(read(R"(\u00e9\u00E9)").type == "\xC3\xA9\xC3\xA9");            // é, either case of hex
  CHECK(read(R"(\u20AC)").type == "\xE2\x82\xAC");                   // three bytes of UTF-8
  CHECK(read(R"(\uD83D\uDE00)").type == "\xF0\x9F\x98\x80");            // a surrogate pair: U+1F600
  CHECK(read(R"(q\u0022\u005c\"\\)").type == "q\"\\\"\\");           // quotation marks, backslashes
  CHECK(read(R"(\u000a\n\u0009\u0001)").type == "\n\n\t\x01");           // control characters
  CHECK(read("ptm", R"(t\u0079pe)").type == "ptm");                   // an escaped key
  const auto says = [](const std::string& message, const std::string& what) {
    INFO(message);
    CHECK(message.find(what) != std::string::npos);
  };
  says(refusal(R"(\u00)"), "four hexadecimal digits");
  says(refusal(R"(\u00G0)"), "four hexadecimal digits");
  says(refusal(R"(\uD83D)"), "without its second");
  says(refusal(R"(\uD83Dx)"), "without its second");
  says(refusal(R"(\uD83D\u0041)"), "without its second");
  says(refusal(R"(\uDE00)"), "without its first");
  says(refusal(R"(\u0000)"), "NUL");
  says(refusal(R"(\x41)"), "the escape \\x");
  says(refusal(R"(\')"), "the escape \\'");
  fs::remove_all(dir);
}

namespace {
// Every file under `root`, relative path -> bytes.
std::map<std::string, std::string> filesUnder(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) out[fs::relative(e.path(), root).generic_string()] = webtest::slurp(e.path());
  return out;
}

// A number of viewer-data.js ("key": value), found by name.
int viewerNumber(const std::string& js, const std::string& key) {
  const std::size_t at = js.find("\"" + key + "\": ");
  if (at == std::string::npos) throw std::runtime_error("viewer-data.js has no " + key);
  return std::stoi(js.substr(at + key.size() + 4, 12));
}
}  // namespace

// OpenLIME's "deepzoom" layout (LayoutTiles.js) counts ceil(log2(max side / tile size)) + 1
// levels, numbers them from 0 (the one-tile level) and requests LEVEL/COL_ROW.jpg of
// plane_j_files beside plane_j.dzi; the reader assembles every level from its tiles and checks
// each tile's size and overlap.
TEST_CASE("publish --tiles deepzoom writes the levels and tiles OpenLIME requests and the full level renders as surrogate render") {
  const fs::path dir = freshDir("tiles");
  const auto ptm = makePtm(formats::PtmFile::Format::Rgb);
  writeModel(dir / "m.ptm", ptm);
  publish::PublishOptions options;
  options.quality = 100;
  options.tiles = publish::TileLayout::DeepZoom;
  options.tileSize = 32;
  const auto models = publish::publish(dir / "m.ptm", dir / "web", options);
  REQUIRE(models.size() == 1);
  const int openLimeLevels = static_cast<int>(std::ceil(std::log2(double(std::max(kW, kH)) / 32))) + 1;
  CHECK(models[0].tiles == "deepzoom");
  CHECK(models[0].levels == openLimeLevels);
  for (int j = 0; j < 6; ++j) {
    const std::string stem = "plane_" + std::to_string(j);
    INFO(stem);
    CHECK_FALSE(fs::exists(dir / "web" / (stem + ".jpg")));
    const webtest::DeepZoomInfo dzi = webtest::readDzi(dir / "web" / (stem + ".dzi"));
    CHECK(dzi.tileSize == 32);
    CHECK(dzi.overlap == 1);
    CHECK(dzi.format == "jpg");
    CHECK(dzi.width == kW);
    CHECK(dzi.height == kH);
    REQUIRE(dzi.levels == openLimeLevels);
    std::size_t levelFolders = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "web" / (stem + "_files"))) ++levelFolders;
    CHECK(levelFolders == static_cast<std::size_t>(openLimeLevels));
    CHECK(webtest::deepZoomLevelSize(dzi, 0).width <= 32);
    // Each level below the top is the one above halved: 2x2 means, within the JPEG error.
    for (int level = 0; level + 1 < dzi.levels; ++level) {
      const cv::Mat below = webtest::assembleDeepZoomLevel(dir / "web", stem, level);
      cv::Mat above = webtest::assembleDeepZoomLevel(dir / "web", stem, level + 1), halved;
      cv::copyMakeBorder(above, above, 0, above.rows % 2, 0, above.cols % 2, cv::BORDER_REPLICATE);
      cv::resize(above, halved, cv::Size(above.cols / 2, above.rows / 2), 0, 0, cv::INTER_AREA);
      REQUIRE(halved.size() == below.size());
      CHECK(webtest::maxAbsDifference(webtest::rgbValues(halved), webtest::rgbValues(below)) <= 3);
    }
  }
  const webtest::WebModel web = webtest::readWebModel(dir / "web");  // the full level, from tiles
  const auto reference = fit::openRelightable(dir / "m.ptm");
  for (const auto& l : kLights) {
    const auto a = webtest::renderAt(web, l[0], l[1], l[2]);
    const auto b = test::renderedValues(*reference, l);
    CHECK(webtest::maxAbsDifference(a, b) <= kMaxDifferenceAtQuality100);
    CHECK(webtest::psnr(a, b) >= kMinPsnrAtQuality100);
  }
  fs::remove_all(dir);
}

TEST_CASE("publish writes the same bytes with one thread and with several tiles or not") {
  const fs::path dir = freshDir("threads");
  writeModel(dir / "m.rti", makeHsh(9));
  for (const auto tiles : {publish::TileLayout::DeepZoom, publish::TileLayout::None}) {
    publish::PublishOptions options;
    options.tiles = tiles;
    options.tileSize = 16;
    options.threads = 1;
    const std::string name = publish::tileLayoutName(tiles);
    publish::publish(dir / "m.rti", dir / (name + "-1"), options);
    options.threads = 5;
    publish::publish(dir / "m.rti", dir / (name + "-5"), options);
    const auto one = filesUnder(dir / (name + "-1")), five = filesUnder(dir / (name + "-5"));
    CHECK(one.size() > 4);
    CHECK(one == five);
  }
  fs::remove_all(dir);
}

TEST_CASE("auto tiles a model with a side over 4096 only and the viewer holds a level of at most 2048") {
  const fs::path dir = freshDir("auto");
  writeModel(dir / "wide.ptm", makePtm(formats::PtmFile::Format::Lrgb, 4097, 6));
  writeModel(dir / "edge.ptm", makePtm(formats::PtmFile::Format::Lrgb, 4096, 6));
  const auto wide = publish::publish(dir / "wide.ptm", dir / "wide", {});
  const auto edge = publish::publish(dir / "edge.ptm", dir / "edge", {});
  CHECK(wide[0].tiles == "deepzoom");
  CHECK(fs::is_regular_file(dir / "wide" / "plane_0.dzi"));
  CHECK(edge[0].tiles.empty());
  CHECK(fs::is_regular_file(dir / "edge" / "plane_0.jpg"));
  // 4097 -> 2049 -> 1025: the viewer's copy of the tiled model is its level of 1025 texels, the
  // untiled one's its level of 2048.
  const std::string wideJs = webtest::slurp(dir / "wide" / "viewer-data.js");
  CHECK(viewerNumber(wideJs, "width") == 1025);
  CHECK(viewerNumber(wideJs, "height") == 2);
  CHECK(viewerNumber(wideJs, "halvings") == 2);
  CHECK(viewerNumber(wideJs, "level") == wide[0].levels - 3);
  // Three planes, the normals and the albedo, all at the viewer's size.
  const std::vector<std::string> jpegs = webtest::jpegDataUris(wideJs);
  REQUIRE(jpegs.size() == 5);
  for (const std::string& jpeg : jpegs) {
    std::vector<uchar> buffer(jpeg.begin(), jpeg.end());
    const cv::Mat decoded = cv::imdecode(buffer, cv::IMREAD_COLOR);
    CHECK(decoded.cols == 1025);
    CHECK(decoded.rows == 2);
  }
  const std::string edgeJs = webtest::slurp(dir / "edge" / "viewer-data.js");
  CHECK(viewerNumber(edgeJs, "width") == 2048);
  CHECK(viewerNumber(edgeJs, "halvings") == 1);
  CHECK(viewerNumber(edgeJs, "level") == -1);
  fs::remove_all(dir);
}

TEST_CASE("the viewer of a model that fits on a screen holds the plane files' own bytes") {
  const fs::path dir = freshDir("viewer-bytes");
  writeModel(dir / "m.ptm", makePtm(formats::PtmFile::Format::Lrgb));
  publish::publish(dir / "m.ptm", dir / "web", {});
  const std::string js = webtest::slurp(dir / "web" / "viewer-data.js");
  CHECK(viewerNumber(js, "width") == kW);
  CHECK(viewerNumber(js, "halvings") == 0);
  CHECK(js.find(webtest::slurp(dir / "web" / "info.json")) != std::string::npos);
  // Three planes, then the normals and the albedo; the planes are plane_j.jpg byte for byte.
  const std::vector<std::string> jpegs = webtest::jpegDataUris(js);
  REQUIRE(jpegs.size() == 3 + 2);
  for (int j = 0; j < 3; ++j)
    CHECK(jpegs[static_cast<std::size_t>(j)] == webtest::slurp(dir / "web" / ("plane_" + std::to_string(j) + ".jpg")));
  for (std::size_t k = 3; k < 5; ++k) {
    std::vector<uchar> buffer(jpegs[k].begin(), jpegs[k].end());
    const cv::Mat decoded = cv::imdecode(buffer, cv::IMREAD_COLOR);
    CHECK(decoded.cols == kW);
    CHECK(decoded.rows == kH);
  }
  const std::string html = webtest::slurp(dir / "web" / "index.html");
  CHECK(html.find("<script src=\"viewer-data.js\"></script>") != std::string::npos);
  CHECK(html.find("default-src 'none'") != std::string::npos);  // no network access
  CHECK(html.find("http://") == std::string::npos);
  CHECK(html.find("https://") == std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("publish refuses a tile size outside 16 to 4096 and an unknown tile layout") {
  const fs::path dir = freshDir("bad-tiles");
  writeModel(dir / "m.ptm", makePtm(formats::PtmFile::Format::Lrgb));
  publish::PublishOptions options;
  options.tileSize = 8;
  CHECK_THROWS_AS(publish::publish(dir / "m.ptm", dir / "web", options), Error);
  CHECK_FALSE(fs::exists(dir / "web"));
  CHECK_THROWS_AS(publish::parseTileLayout("iiif"), Error);
  CHECK(publish::parseTileLayout("deepzoom") == publish::TileLayout::DeepZoom);
  fs::remove_all(dir);
}

TEST_CASE("the web copy's pages escape the description link only web addresses and percent-encode folder names") {
  publish::WebDescription d;
  d.title = "<b>Stela</b> & 'twelve' \"x\"";
  d.creators = {{"Ana <i>Silva</i>", "photographer"}};
  d.rights = "</p><script>alert(1)</script>";
  d.license = "javascript:alert(1)";
  // A folder named after a file may hold any byte; RFC 3986 leaves only A-Z a-z 0-9 - . _ ~ unencoded.
  const std::vector<publish::IndexedModel> models = {{"stela 12#b%", "hsh2"}, {"ptm-lrgb", "ptm-lrgb"}};
  const std::string index = publish::webIndexHtml(d, models);
  CHECK(index.find("<b>") == std::string::npos);
  CHECK(index.find("<i>") == std::string::npos);
  CHECK(index.find("<script") == std::string::npos);
  CHECK(index.find("<title>&lt;b&gt;Stela&lt;/b&gt; &amp; &#39;twelve&#39; &quot;x&quot;</title>") != std::string::npos);
  CHECK(index.find("Rights: &lt;/p&gt;&lt;script&gt;alert(1)&lt;/script&gt;</p>") != std::string::npos);
  CHECK(index.find("href=\"javascript") == std::string::npos);
  CHECK(index.find("Licence: javascript:alert(1)</p>") != std::string::npos);
  CHECK(index.find("<a href=\"stela%2012%23b%25/index.html\">HSH order 2</a>") != std::string::npos);
  CHECK(index.find("<a href=\"ptm-lrgb/index.html\">PTM LRGB</a>") != std::string::npos);
  CHECK(index == publish::webIndexHtml(d, models));  // no date, no path: the same bytes

  // A web address is a link; an empty description gives the plain title.
  d.license = "https://creativecommons.org/licenses/by/4.0/";
  CHECK(publish::webIndexHtml(d, models).find("<a href=\"https://creativecommons.org/licenses/by/4.0/\" rel=\"license\">") !=
        std::string::npos);
  CHECK(publish::webIndexHtml({}, models).find("<title>Relightable model</title>") != std::string::npos);
}
