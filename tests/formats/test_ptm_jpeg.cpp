// JPEG-compressed PTMs (PTM_FORMAT_JPEG_LRGB, PTM_FORMAT_JPEG_RGB), read by Surrogate.
//
// The files are made here by a small writer of our own, written from the published layout
// (docs/formats.md, "JPEG-compressed PTMs") and sharing no code with src/formats: OpenCV
// encodes and decodes each plane, the writer predicts planes from the *decoded* reference (as
// an encoder must, so that its decoder sees the same reference), and it records side
// information for every texel whose reconstruction is off by more than a threshold. The
// writer therefore knows exactly what a decoder following the layout must obtain; Surrogate's
// reader must obtain it too, and the result must lie within the JPEG error of the model.
//
// Error bounds. The planes of the model are smooth (a few cycles across the image, as fitted
// coefficients are), and at quality 90 baseline JPEG reconstructs them within
// kJpegErrorQ90 = 3 levels (measured: 2 on these planes, with one level of margin); a plane
// with side information at threshold T is within T by construction (T = 0: exact). A rendered
// LRGB value C * L / 255 then moves by at most (C dL + (L + dL) dC) / 255 with
// dL = sum_k dc_k s_k |w_k| (w_k the basis at the light) and dC the colour error, plus one
// level for the rounding of the two renders; the tests check that bound texel by texel.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "fit/render.h"
#include "formats/ptm.h"
#include "formats/summary.h"
#include "fuzz_support.h"

using namespace surrogate;

namespace {

constexpr int kJpegErrorQ90 = 3;  // see the error bounds above

// ---- the independent writer ------------------------------------------------------------
namespace jp {

using Bytes = std::vector<std::uint8_t>;

struct Plane {
  Bytes values;        // the model's bytes, image rows top first, width * height
  int reference = -1;  // plane predicted from, or -1
  int transform = 0;   // 1: predict from 255 - reference
  int order = 0;       // position in the decoding sequence
  int threshold = -1;  // side information for every texel off by more than this; -1: none
};

struct Written {
  std::string bytes;
  std::vector<Bytes> decoded;  // what a decoder must obtain per plane, rows top first
  std::size_t sideEntries = 0;
};

Bytes flipRows(const Bytes& v, int w, int h) {
  Bytes out(v.size());
  for (int y = 0; y < h; ++y)
    std::memcpy(&out[static_cast<std::size_t>(y) * w], &v[static_cast<std::size_t>(h - 1 - y) * w], w);
  return out;
}

std::string joined(const std::vector<long long>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + std::to_string(v[i]);
  return s;
}

Written write(bool lrgb, int w, int h, const std::array<double, 6>& scale,
              const std::array<int, 6>& bias, std::vector<Plane> planes, int quality) {
  const std::size_t n = planes.size(), texels = static_cast<std::size_t>(w) * h;
  std::vector<Bytes> jpegs(n), sides(n), recon(n);  // recon in file row order (bottom first)
  std::vector<std::size_t> sequence(n);
  for (std::size_t p = 0; p < n; ++p) sequence[static_cast<std::size_t>(planes[p].order)] = p;
  Written out;
  for (std::size_t p : sequence) {
    const Plane& pl = planes[p];
    const Bytes target = flipRows(pl.values, w, h);  // first JPEG row = bottom image row
    Bytes stored(texels), prediction(texels, 128);
    if (pl.reference >= 0)
      for (std::size_t i = 0; i < texels; ++i) {
        const int r = recon[static_cast<std::size_t>(pl.reference)][i];
        prediction[i] = static_cast<std::uint8_t>(pl.transform & 1 ? 255 - r : r);
      }
    for (std::size_t i = 0; i < texels; ++i)
      stored[i] = static_cast<std::uint8_t>(
          std::clamp(int(target[i]) - (pl.reference >= 0 ? int(prediction[i]) - 128 : 0), 0, 255));
    cv::Mat m(h, w, CV_8UC1, stored.data());
    std::vector<uchar> buf;
    REQUIRE(cv::imencode(".jpg", m, buf, {cv::IMWRITE_JPEG_QUALITY, quality}));
    jpegs[p].assign(buf.begin(), buf.end());
    const cv::Mat back = cv::imdecode(buf, cv::IMREAD_UNCHANGED);
    REQUIRE(back.type() == CV_8UC1);
    Bytes r(texels);
    for (std::size_t i = 0; i < texels; ++i) {
      const int d = back.data[i];
      r[i] = static_cast<std::uint8_t>(pl.reference >= 0 ? (d + prediction[i] - 128) & 0xFF : d);
    }
    for (std::size_t i = 0; pl.threshold >= 0 && i < texels; ++i) {
      if (std::abs(int(r[i]) - int(target[i])) <= pl.threshold) continue;
      const std::uint32_t index = static_cast<std::uint32_t>(i);
      for (int shift : {24, 16, 8, 0}) sides[p].push_back(static_cast<std::uint8_t>(index >> shift));
      sides[p].push_back(target[i]);
      r[i] = target[i];
      ++out.sideEntries;
    }
    recon[p] = std::move(r);
  }
  std::vector<long long> transforms, zeros(n, 0), order, refs, sizes, sideSizes;
  for (std::size_t p = 0; p < n; ++p) {
    transforms.push_back(planes[p].transform);
    order.push_back(planes[p].order);
    refs.push_back(planes[p].reference);
    sizes.push_back(static_cast<long long>(jpegs[p].size()));
    sideSizes.push_back(static_cast<long long>(sides[p].size()));
  }
  std::ostringstream head;
  head.precision(9);
  head << "PTM_1.2\n" << (lrgb ? "PTM_FORMAT_JPEG_LRGB" : "PTM_FORMAT_JPEG_RGB") << "\n"
       << w << "\n" << h << "\n";
  for (int k = 0; k < 6; ++k) head << (k ? " " : "") << scale[k];
  head << "\n";
  for (int k = 0; k < 6; ++k) head << (k ? " " : "") << bias[k];
  head << "\n" << quality << "\n" << joined(transforms) << "\n" << joined(zeros) << "\n"
       << joined(zeros) << "\n" << joined(order) << "\n" << joined(refs) << "\n" << joined(sizes)
       << "\n" << joined(sideSizes) << "\n";
  out.bytes = head.str();
  for (std::size_t p = 0; p < n; ++p) {
    out.bytes.append(jpegs[p].begin(), jpegs[p].end());
    out.bytes.append(sides[p].begin(), sides[p].end());
    out.decoded.push_back(flipRows(recon[p], w, h));
  }
  return out;
}

}  // namespace jp

// ---- the known model ---------------------------------------------------------------------
constexpr int kW = 37, kH = 29;  // not multiples of 8: JPEG's partial blocks are exercised
const std::array<double, 6> kScale = {0.75, 0.5, 0.625, 1.25, 1.5, 1.0};
const std::array<int, 6> kBias = {128, 120, 128, 100, 110, 0};

// Smooth, distinct planes, brighter towards the top so a flipped row order shows at once.
std::vector<std::uint8_t> modelPlane(int p) {
  std::vector<std::uint8_t> v(static_cast<std::size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const double s = 120 + 50 * std::sin(0.17 * x + 0.7 * p) * std::cos(0.13 * y + 0.3 * p) +
                       2.0 * (kH - 1 - y) - 0.5 * (p % 5) * x;
      v[static_cast<std::size_t>(y) * kW + x] = static_cast<std::uint8_t>(std::clamp(s, 0.0, 255.0));
    }
  return v;
}

std::vector<jp::Plane> modelPlanes(std::size_t n) {
  std::vector<jp::Plane> planes(n);
  for (std::size_t p = 0; p < n; ++p) {
    planes[p].values = modelPlane(static_cast<int>(p));
    planes[p].order = static_cast<int>(p);
  }
  return planes;
}

// The model's planes as Surrogate's in-memory PtmFile holds them.
std::uint8_t surrogateByte(const formats::PtmFile& f, std::size_t p, int x, int y) {
  const std::size_t t = static_cast<std::size_t>(y) * f.width + x;
  if (f.format == formats::PtmFile::Format::Lrgb)
    return p < 6 ? f.coefficients[t * 6 + p] : f.rgb[t * 3 + (p - 6)];
  return f.byte(x, y, static_cast<int>(p % 6), static_cast<int>(p / 6));
}

formats::PtmFile parse(const std::string& bytes, formats::PtmReadReport* report = nullptr) {
  return formats::parsePtm(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                           "j.ptm", report);
}

std::string parseError(const std::string& bytes) {
  try {
    parse(bytes);
  } catch (const Error& e) {
    CHECK(e.file() == "j.ptm");
    return e.message();
  }
  FAIL("no error");
  return "";
}

// Largest |read - expected| over all planes and texels.
int maxDifference(const formats::PtmFile& f, const std::vector<std::vector<std::uint8_t>>& expected) {
  int worst = 0;
  for (std::size_t p = 0; p < expected.size(); ++p)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        worst = std::max(worst, std::abs(int(surrogateByte(f, p, x, y)) -
                                         int(expected[p][static_cast<std::size_t>(y) * kW + x])));
  return worst;
}

formats::PtmFile rawModel(bool lrgb) {
  formats::PtmFile m;
  m.format = lrgb ? formats::PtmFile::Format::Lrgb : formats::PtmFile::Format::Rgb;
  m.width = kW;
  m.height = kH;
  m.scale = kScale;
  m.bias = kBias;
  const std::size_t texels = m.texels();
  m.coefficients.resize(texels * (lrgb ? 6 : 18));
  if (lrgb) m.rgb.resize(texels * 3);
  for (std::size_t p = 0; p < (lrgb ? 9u : 18u); ++p) {
    const auto v = modelPlane(static_cast<int>(p));
    for (std::size_t t = 0; t < texels; ++t) {
      if (lrgb) (p < 6 ? m.coefficients[t * 6 + p] : m.rgb[t * 3 + p - 6]) = v[t];
      else m.coefficients[((p / 6) * texels + t) * 6 + p % 6] = v[t];
    }
  }
  return m;
}

// Renders the model and the file read back at several lights; every texel must be within the
// bound derived above from the per-plane byte errors `err`.
void checkRenderedLrgb(const formats::PtmFile& read, const std::vector<int>& err) {
  const formats::PtmFile model = rawModel(true);
  for (const std::array<double, 3>& l : {std::array<double, 3>{0, 0, 1}, {0.6, 0.3, 0.74},
                                         {-0.5, -0.6, 0.62}, {0.9, -0.1, 0.42}}) {
    const double n = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const double u = l[0] / n, v = l[1] / n;
    const double wk[6] = {u * u, v * v, u * v, u, v, 1};
    double dL = 0;
    for (int k = 0; k < 6; ++k) dL += err[static_cast<std::size_t>(k)] * kScale[k] * std::abs(wk[k]);
    const Image a = fit::render(model, l), b = fit::render(read, l);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        double L = 0;
        for (int k = 0; k < 6; ++k) L += model.coefficient(x, y, k) * wk[k];
        for (int c = 0; c < 3; ++c) {
          const double C = model.rgb[(static_cast<std::size_t>(y) * kW + x) * 3 + c];
          const double dC = err[static_cast<std::size_t>(6 + c)];
          const double bound = (C * dL + (std::abs(L) + dL) * dC) / 255 + 1;
          const double diff = std::abs(a.at(x, y, c) / 257.0 - b.at(x, y, c) / 257.0);
          if (diff > bound) FAIL("texel " << x << "," << y << " channel " << c << ": " << diff << " > " << bound);
        }
      }
  }
}

}  // namespace

TEST_CASE("ptm jpeg: LRGB planes without prediction decode as the layout says, within the JPEG error") {
  const jp::Written w = jp::write(true, kW, kH, kScale, kBias, modelPlanes(9), 90);
  formats::PtmReadReport report;
  const formats::PtmFile f = parse(w.bytes, &report);
  CHECK(f.format == formats::PtmFile::Format::Lrgb);
  CHECK(f.width == kW);
  CHECK(f.height == kH);
  CHECK(f.scale == kScale);
  CHECK(f.bias == kBias);
  CHECK(report.formatLine == "PTM_FORMAT_JPEG_LRGB");
  CHECK(report.jpegQuality == 90);
  CHECK(report.trailingBytes == 0);
  // Exactly what the layout's decoder obtains (the same libjpeg decodes in both).
  CHECK(maxDifference(f, w.decoded) == 0);
  // Within the JPEG error of the model; row order right (a flip would be off by ~56).
  std::vector<std::vector<std::uint8_t>> model;
  for (int p = 0; p < 9; ++p) model.push_back(modelPlane(p));
  const int err = maxDifference(f, model);
  CHECK(err <= kJpegErrorQ90);
  checkRenderedLrgb(f, std::vector<int>(9, err));
}

TEST_CASE("ptm jpeg: LRGB with prediction, inversion, a decoding order and side information") {
  std::vector<jp::Plane> planes = modelPlanes(9);
  // a5 decoded first; a0 and a3 predicted from it, a1 from the inverse of a0; G from R, B from G.
  const int order[9] = {3, 4, 5, 1, 2, 0, 6, 7, 8};
  const int reference[9] = {5, 0, -1, 5, -1, -1, -1, 6, 7};
  for (int p = 0; p < 9; ++p) {
    planes[static_cast<std::size_t>(p)].order = order[p];
    planes[static_cast<std::size_t>(p)].reference = reference[p];
  }
  planes[1].transform = 1;
  for (auto& v : planes[1].values) v = static_cast<std::uint8_t>(255 - v);  // anti-correlated
  for (auto& pl : planes) pl.threshold = 1;  // side information for every texel off by > 1
  const jp::Written w = jp::write(true, kW, kH, kScale, kBias, planes, 90);
  REQUIRE(w.sideEntries > 0);
  const formats::PtmFile f = parse(w.bytes);
  CHECK(maxDifference(f, w.decoded) == 0);
  std::vector<std::vector<std::uint8_t>> model;
  for (const auto& pl : planes) model.push_back(pl.values);
  CHECK(maxDifference(f, model) <= 1);  // the side-information threshold
}

TEST_CASE("ptm jpeg: side information at threshold 0 makes the planes exact, LRGB and RGB") {
  for (const bool lrgb : {true, false}) {
    std::vector<jp::Plane> planes = modelPlanes(lrgb ? 9 : 18);
    for (std::size_t p = 0; p < planes.size(); ++p) {
      planes[p].threshold = 0;
      if (p % 6 != 0) planes[p].reference = static_cast<int>(p - 1);  // a chain a0 <- a1 <- ...
    }
    const jp::Written w = jp::write(lrgb, kW, kH, kScale, kBias, planes, 60);
    const formats::PtmFile f = parse(w.bytes);
    const formats::PtmFile model = rawModel(lrgb);
    CHECK(f == model);
  }
}

TEST_CASE("ptm jpeg: RGB planes with prediction read back within the JPEG error") {
  std::vector<jp::Plane> planes = modelPlanes(18);
  for (std::size_t p = 6; p < 18; ++p) {
    planes[p].reference = static_cast<int>(p - 6);  // green from red, blue from green
    planes[p].threshold = kJpegErrorQ90;  // where a residual was clipped (|difference| > 127)
  }
  const jp::Written w = jp::write(false, kW, kH, kScale, kBias, planes, 90);
  formats::PtmReadReport report;
  const formats::PtmFile f = parse(w.bytes, &report);
  CHECK(f.format == formats::PtmFile::Format::Rgb);
  CHECK(report.formatLine == "PTM_FORMAT_JPEG_RGB");
  CHECK(maxDifference(f, w.decoded) == 0);
  std::vector<std::vector<std::uint8_t>> model;
  for (int p = 0; p < 18; ++p) model.push_back(modelPlane(p));
  // The writer predicts from the decoded reference, so only the residual's JPEG error remains.
  CHECK(maxDifference(f, model) <= kJpegErrorQ90);
}

TEST_CASE("ptm jpeg: info and render read the file from disk") {
  TempDir temp("ptm-jpeg");
  const jp::Written w = jp::write(true, kW, kH, kScale, kBias, modelPlanes(9), 90);
  writeFileAtomically(temp.path() / "relight.ptm", w.bytes);
  const formats::FileSummary s = formats::summarize(temp.path() / "relight.ptm");
  CHECK(s.format == "PTM_FORMAT_JPEG_LRGB");
  CHECK(s.basis == "ptm-lrgb");
  CHECK(s.width == kW);
  CHECK(s.trailingBytes == 0);
  CHECK_THAT(s.toText(), Catch::Contains("JPEG-compressed (compression parameter 90"));
  const auto model = fit::openRelightable(temp.path() / "relight.ptm");
  CHECK(model->basis() == "ptm-lrgb");
  CHECK(model->render({0, 0, 1}, {}).width == kW);
  writeFileAtomically(temp.path() / "cut.ptm", w.bytes.substr(0, w.bytes.size() - 1));
  CHECK_THROWS_WITH(formats::summarize(temp.path() / "cut.ptm"), Catch::Contains("truncated"));
}

TEST_CASE("ptm jpeg: a damaged plane table or payload is refused with the plane named") {
  std::vector<jp::Plane> planes = modelPlanes(9);
  planes[7].reference = 6;
  planes[7].threshold = 0;
  const std::string good = jp::write(true, kW, kH, kScale, kBias, planes, 80).bytes;
  auto lineStart = [&](int line) {  // byte offset of 1-based header line `line`
    std::size_t pos = 0;
    for (int i = 1; i < line; ++i) pos = good.find('\n', pos) + 1;
    return pos;
  };
  auto withLine = [&](int line, const std::string& text) {
    const std::size_t a = lineStart(line), b = good.find('\n', a);
    return good.substr(0, a) + text + good.substr(b);
  };
  REQUIRE(parse(good).width == kW);
  // Lines: 7 compression, 8 transforms, 9/10 motion, 11 order, 12 references, 13 sizes, 14 sides.
  CHECK_THAT(parseError(withLine(8, "0 0 0 0 0 0 0 0")), Catch::Contains("9 integers"));
  CHECK_THAT(parseError(withLine(8, "0 0 0 0 0 0 0 7 0")), Catch::Contains("transforms"));
  CHECK_THAT(parseError(withLine(11, "0 1 2 3 4 5 6 7 7")), Catch::Contains("two planes"));
  CHECK_THAT(parseError(withLine(12, "-1 -1 -1 -1 -1 -1 -1 7 -1")), Catch::Contains("itself"));
  CHECK_THAT(parseError(withLine(12, "-1 -1 -1 -1 -1 -1 8 -1 -1")), Catch::Contains("after it"));
  CHECK_THAT(parseError(withLine(12, "-1 -1 -1 -1 -1 -1 -1 9 -1")), Catch::Contains("reference planes"));
  CHECK_THAT(parseError(withLine(8, "0 0 0 0 0 0 0 2 0").replace(lineStart(9), 17, "0 0 0 0 0 0 0 3 0")),
             Catch::Contains("motion compensation"));
  {
    std::string s = good;
    const std::size_t a = lineStart(14), b = good.find('\n', a);
    std::string sides = good.substr(a, b - a);
    sides.back() = '3';  // blue's side information: 3 bytes
    CHECK_THAT(parseError(good.substr(0, a) + sides + good.substr(b)), Catch::Contains("multiple of"));
  }
  CHECK_THAT(parseError(withLine(13, "1 1 1 1 1 1 1 1 1") ), Catch::Contains("plane 0 (a0)"));
  CHECK_THAT(parseError(good.substr(0, good.size() - 10)), Catch::Contains("truncated"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_JPEGLS_LRGB\n1\n1\n1 1 1 1 1 1\n0 0 0 0 0 0\n"),
             Catch::Contains("not supported"));
  CHECK_THAT(parseError("PTM_1.1\nPTM_FORMAT_JPEG_LRGB\n1\n1\n1 1 1 1 1 1\n0 0 0 0 0 0\n"),
             Catch::Contains("not supported"));
  CHECK_THAT(parseError("PTM_1.2\nPTM_FORMAT_JPEG_LRGB\n20000\n30000\n1 1 1 1 1 1\n0 0 0 0 0 0\n"),
             Catch::Contains("million texels"));
}

TEST_CASE("ptm jpeg: a plane of the wrong size, in colour, or with a stray correction is refused") {
  const int w = 8, h = 8;
  auto plane = [&](int width, int height, int type) {
    cv::Mat m(height, width, type, cv::Scalar::all(100));
    std::vector<uchar> buf;
    cv::imencode(".jpg", m, buf);
    return std::string(buf.begin(), buf.end());
  };
  auto file = [&](const std::string& first, const std::string& side) {
    const std::string other = plane(w, h, CV_8UC1);
    std::string sizes = std::to_string(first.size()), sides = std::to_string(side.size());
    for (int p = 1; p < 9; ++p) {
      sizes += " " + std::to_string(other.size());
      sides += " 0";
    }
    std::string s = "PTM_1.2\nPTM_FORMAT_JPEG_LRGB\n8\n8\n1 1 1 1 1 1\n0 0 0 0 0 0\n75\n"
                    "0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n0 1 2 3 4 5 6 7 8\n"
                    "-1 -1 -1 -1 -1 -1 -1 -1 -1\n" + sizes + "\n" + sides + "\n" + first + side;
    for (int p = 1; p < 9; ++p) s += other;
    return s;
  };
  REQUIRE(parse(file(plane(w, h, CV_8UC1), "")).width == 8);
  CHECK_THAT(parseError(file(plane(w, h + 8, CV_8UC1), "")), Catch::Contains("plane 0 (a0)"));
  CHECK_THAT(parseError(file(plane(w - 1, h, CV_8UC1), "")), Catch::Contains("the header announces 8 x 8"));
  CHECK_THAT(parseError(file(plane(w, h, CV_8UC3), "")), Catch::Contains("colour"));
  CHECK_THAT(parseError(file(plane(w, h, CV_8UC1), std::string("\0\0\0\100\7", 5))),
             Catch::Contains("outside the 64 texels"));
  CHECK(parse(file(plane(w, h, CV_8UC1), std::string("\0\0\0\77\7", 5))).byte(7, 0, 0) == 7);
  std::string broken = plane(w, h, CV_8UC1);
  broken.resize(broken.size() / 2);
  CHECK_THAT(parseError(file(broken, "")), Catch::Contains("cannot be decoded"));
}

TEST_CASE("ptm jpeg: every prefix and thousands of mutations parse or throw Error") {
  std::vector<jp::Plane> planes = modelPlanes(9);
  for (auto& pl : planes) pl.values.resize(64);
  for (std::size_t p = 1; p < 9; ++p) {
    planes[p].reference = static_cast<int>(p - 1);
    planes[p].threshold = 2;
  }
  const std::string bytes = jp::write(true, 8, 8, kScale, kBias, planes, 50).bytes;
  for (std::size_t n = 0; n < bytes.size(); n += 7) CHECK_THROWS_AS(parse(bytes.substr(0, n)), Error);
  auto parser = [](const std::uint8_t* d, std::size_t n) {
    formats::validatePtm(formats::parsePtm(d, n, "f.ptm"), "f.ptm");
  };
  test::fuzz(parser, bytes, 250, 3000, 17);
}

// Not run by default: writes the seeds of fuzz/corpus/formats from this file's writer
// (`test_formats "[.seeds]"` with SURROGATE_SEED_DIR set).
TEST_CASE("ptm jpeg: write fuzz seeds", "[.seeds]") {
  const char* dir = std::getenv("SURROGATE_SEED_DIR");
  REQUIRE(dir);
  std::vector<jp::Plane> planes = modelPlanes(9);
  for (auto& pl : planes) pl.values.resize(64);
  writeFileAtomically(std::filesystem::path(dir) / "jpeg-lrgb.ptm",
                      jp::write(true, 8, 8, kScale, kBias, planes, 50).bytes);
  planes = modelPlanes(18);
  for (std::size_t p = 0; p < 18; ++p) {
    planes[p].values.resize(64);
    if (p) planes[p].reference = static_cast<int>(p - 1);
    planes[p].transform = static_cast<int>(p % 2);
    planes[p].threshold = 3;
  }
  writeFileAtomically(std::filesystem::path(dir) / "jpeg-rgb-predicted.ptm",
                      jp::write(false, 8, 8, kScale, kBias, planes, 50).bytes);
}
