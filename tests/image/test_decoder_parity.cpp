// JPEG, PNG and TIFF are decoded by libjpeg-turbo, libpng and libtiff called directly (so their
// warnings reach Surrogate). Before, OpenCV's imread decoded them; the decoded values must not
// change: each file here decodes to exactly what imread (IMREAD_UNCHANGED | IMREAD_ANYDEPTH |
// IMREAD_IGNORE_ORIENTATION, then RGB order, alpha dropped, 8-bit widened by 257) gave.
#include <cstdio>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <png.h>
#include <tiffio.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fixtures.h"
#include "image/decode.h"
#include "image/opencv_bridge.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {

Image viaOpenCv(const fs::path& p) {
  const cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH | cv::IMREAD_IGNORE_ORIENTATION);
  REQUIRE_FALSE(m.empty());
  cv::Mat rgb;
  if (m.channels() == 1) rgb = m;
  else if (m.channels() == 3) cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB);
  else cv::cvtColor(m, rgb, cv::COLOR_BGRA2RGB);
  return image::fromMat(rgb, Transfer::Srgb, m.depth() == CV_8U ? 8 : 16);
}

void checkSame(const fs::path& p, bool acceptDamage = false) {
  INFO(p.filename().string());
  image::DecodeOptions options;
  options.acceptDamage = acceptDamage;
  const Image ours = image::decodeImage(p, image::RawDecodeSettings(), nullptr, options);
  const Image theirs = viaOpenCv(p);
  REQUIRE(ours.width == theirs.width);
  REQUIRE(ours.height == theirs.height);
  REQUIRE(ours.channels == theirs.channels);
  CHECK(ours.bitsPerSample == theirs.bitsPerSample);
  CHECK(ours.transfer == theirs.transfer);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) differ += ours.pixels[i] != theirs.pixels[i];
  CHECK(differ == 0);
}

// Smooth gradients with texture, so that every coding path (DCT, prediction) has work.
cv::Mat scene(int w, int h, int type) {
  cv::Mat m(h, w, type);
  cv::RNG rng(7);
  const int channels = CV_MAT_CN(type);
  const double top = CV_MAT_DEPTH(type) == CV_16U ? 65535 : 255;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        const double v = top * (0.5 + 0.35 * std::sin(0.11 * x * (c + 1) + 0.07 * y) + rng.uniform(-0.1, 0.1));
        const double clamped = std::min(top, std::max(0.0, v));
        if (CV_MAT_DEPTH(type) == CV_16U) m.ptr<std::uint16_t>(y)[x * channels + c] = static_cast<std::uint16_t>(clamped);
        else m.ptr<std::uint8_t>(y)[x * channels + c] = static_cast<std::uint8_t>(clamped);
      }
  return m;
}

void writeCmykJpeg(const fs::path& p, int w, int h) {
  FILE* f = std::fopen(p.c_str(), "wb");
  REQUIRE(f);
  jpeg_compress_struct c;
  jpeg_error_mgr err;
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  jpeg_stdio_dest(&c, f);
  c.image_width = w;
  c.image_height = h;
  c.input_components = 4;
  c.in_color_space = JCS_CMYK;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 90, TRUE);
  jpeg_start_compress(&c, TRUE);
  std::vector<std::uint8_t> row(4 * w);
  while (c.next_scanline < c.image_height) {
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 4; ++k) row[4 * x + k] = static_cast<std::uint8_t>((x * (k + 3) + c.next_scanline * 5) & 0xFF);
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&c, &r, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::fclose(f);
}

// A PNG of any colour type and depth, optionally interlaced and with a tRNS chunk.
void writePng(const fs::path& p, int w, int h, int colorType, int depth, bool interlace, bool trns) {
  FILE* f = std::fopen(p.c_str(), "wb");
  REQUIRE(f);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, w, h, depth, colorType, interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (colorType == PNG_COLOR_TYPE_PALETTE) {
    png_color palette[16];
    for (int i = 0; i < 16; ++i) palette[i] = {static_cast<png_byte>(i * 16), static_cast<png_byte>(255 - i * 9), static_cast<png_byte>(i * i)};
    png_set_PLTE(png, info, palette, 16);
    if (trns) {
      png_byte alpha[4] = {0, 100, 200, 255};
      png_set_tRNS(png, info, alpha, 4, nullptr);
    }
  } else if (trns) {
    png_color_16 colour{};
    colour.red = colour.green = colour.blue = colour.gray = 3;
    png_set_tRNS(png, info, nullptr, 0, &colour);
  }
  png_write_info(png, info);
  const int channels = png_get_channels(png, info);
  const std::size_t rowBytes = png_get_rowbytes(png, info);
  std::vector<std::vector<png_byte>> rows(h, std::vector<png_byte>(rowBytes));
  for (int y = 0; y < h; ++y)
    for (std::size_t i = 0; i < rowBytes; ++i)
      rows[y][i] = static_cast<png_byte>(colorType == PNG_COLOR_TYPE_PALETTE && depth == 8 ? (i + y) % 16 : (i * 37 + y * 11 + channels) & 0xFF);
  std::vector<png_bytep> pointers(h);
  for (int y = 0; y < h; ++y) pointers[y] = rows[y].data();
  png_write_image(png, pointers.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

// A TIFF of any photometric, depth, planar configuration, in strips or tiles.
void writeTiff(const fs::path& p, int w, int h, int photometric, int bits, int spp, bool tiled, int planar,
               int compression) {
  TIFF* t = TIFFOpen(p.c_str(), "w");
  REQUIRE(t);
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, w);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, h);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, bits);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, spp);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, photometric);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, planar);
  TIFFSetField(t, TIFFTAG_COMPRESSION, compression);
  TIFFSetField(t, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
  if (spp == 4 || spp == 2) {
    std::uint16_t extra = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(t, TIFFTAG_EXTRASAMPLES, 1, &extra);
  }
  if (photometric == PHOTOMETRIC_PALETTE) {
    std::vector<std::uint16_t> r(1u << bits), g(1u << bits), b(1u << bits);
    for (std::size_t i = 0; i < r.size(); ++i) {
      r[i] = static_cast<std::uint16_t>(i * 257);
      g[i] = static_cast<std::uint16_t>(65535 - i * 200);
      b[i] = static_cast<std::uint16_t>((i * 1000) & 0xFFFF);
    }
    TIFFSetField(t, TIFFTAG_COLORMAP, r.data(), g.data(), b.data());
  }
  const int planes = planar == PLANARCONFIG_SEPARATE ? spp : 1;
  const int perPixel = planar == PLANARCONFIG_SEPARATE ? 1 : spp;
  auto sample = [&](int x, int y, int s) { return (x * 7 + y * 3 + s * 50) % (1 << std::min(bits, 16)); };
  if (tiled) {
    TIFFSetField(t, TIFFTAG_TILEWIDTH, 16);
    TIFFSetField(t, TIFFTAG_TILELENGTH, 16);
    std::vector<std::uint8_t> tile(TIFFTileSize(t));
    for (int plane = 0; plane < planes; ++plane)
      for (int ty = 0; ty < h; ty += 16)
        for (int tx = 0; tx < w; tx += 16) {
          std::fill(tile.begin(), tile.end(), 0);
          for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
              for (int s = 0; s < perPixel; ++s) {
                const int v = sample(tx + x, ty + y, plane + s);
                const std::size_t i = (static_cast<std::size_t>(y) * 16 + x) * perPixel + s;
                if (bits == 16) reinterpret_cast<std::uint16_t*>(tile.data())[i] = static_cast<std::uint16_t>(v);
                else tile[i] = static_cast<std::uint8_t>(v);
              }
          TIFFWriteTile(t, tile.data(), tx, ty, 0, static_cast<std::uint16_t>(plane));
        }
  } else {
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 5);
    std::vector<std::uint8_t> row(TIFFScanlineSize(t));
    for (int plane = 0; plane < planes; ++plane)
      for (int y = 0; y < h; ++y) {
        std::fill(row.begin(), row.end(), 0);
        for (int x = 0; x < w; ++x)
          for (int s = 0; s < perPixel; ++s) {
            const int v = sample(x, y, plane + s);
            const std::size_t i = static_cast<std::size_t>(x) * perPixel + s;
            if (bits == 16) reinterpret_cast<std::uint16_t*>(row.data())[i] = static_cast<std::uint16_t>(v);
            else if (bits == 8) row[i] = static_cast<std::uint8_t>(v);
            else if (v & 1) row[i * bits / 8] |= static_cast<std::uint8_t>(((1 << bits) - 1) << (8 - bits - (i * bits) % 8));
          }
        TIFFWriteScanline(t, row.data(), y, static_cast<std::uint16_t>(plane));
      }
  }
  TIFFClose(t);
}

}  // namespace

TEST_CASE("JPEGs decode to exactly what OpenCV's imread gave") {
  const fs::path dir = test::scratchDir("parity-jpeg");
  const cv::Mat colour = scene(77, 45, CV_8UC3), grey = scene(61, 33, CV_8UC1);
  REQUIRE(cv::imwrite((dir / "q90.jpg").string(), colour, {cv::IMWRITE_JPEG_QUALITY, 90}));
  REQUIRE(cv::imwrite((dir / "q40-optimised.jpg").string(), colour, {cv::IMWRITE_JPEG_QUALITY, 40, cv::IMWRITE_JPEG_OPTIMIZE, 1}));
  REQUIRE(cv::imwrite((dir / "progressive.jpg").string(), colour, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  REQUIRE(cv::imwrite((dir / "restarts.jpg").string(), colour, {cv::IMWRITE_JPEG_RST_INTERVAL, 2}));
  REQUIRE(cv::imwrite((dir / "chroma.jpg").string(), colour, {cv::IMWRITE_JPEG_CHROMA_QUALITY, 30}));
  REQUIRE(cv::imwrite((dir / "grey.jpg").string(), grey));
  REQUIRE(cv::imwrite((dir / "grey-progressive.jpg").string(), grey, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  writeCmykJpeg(dir / "cmyk.jpg", 40, 24);
  for (const auto& e : fs::directory_iterator(dir)) checkSame(e.path());
  // Real camera JPEGs (4:2:2 and 4:2:0, EXIF thumbnails, an orientation tag).
  checkSame(test::fixture("raw-metadata/exiv2-nikon-d70.jpg"));
  checkSame(test::fixture("raw-metadata/DSC_3079.jpg"));
  fs::remove_all(dir);
}

TEST_CASE("PNGs of every colour type decode to exactly what OpenCV's imread gave") {
  const fs::path dir = test::scratchDir("parity-png");
  REQUIRE(cv::imwrite((dir / "rgb8.png").string(), scene(30, 20, CV_8UC3)));
  REQUIRE(cv::imwrite((dir / "rgb16.png").string(), scene(30, 20, CV_16UC3)));
  REQUIRE(cv::imwrite((dir / "grey8.png").string(), scene(30, 20, CV_8UC1)));
  REQUIRE(cv::imwrite((dir / "grey16.png").string(), scene(30, 20, CV_16UC1)));
  REQUIRE(cv::imwrite((dir / "rgba8.png").string(), scene(30, 20, CV_8UC4)));
  REQUIRE(cv::imwrite((dir / "rgba16.png").string(), scene(30, 20, CV_16UC4)));
  writePng(dir / "palette.png", 21, 13, PNG_COLOR_TYPE_PALETTE, 8, false, false);
  writePng(dir / "palette-trns.png", 21, 13, PNG_COLOR_TYPE_PALETTE, 8, false, true);
  writePng(dir / "palette4.png", 21, 13, PNG_COLOR_TYPE_PALETTE, 4, false, false);
  writePng(dir / "grey1.png", 21, 13, PNG_COLOR_TYPE_GRAY, 1, false, false);
  writePng(dir / "grey4.png", 21, 13, PNG_COLOR_TYPE_GRAY, 4, false, false);
  writePng(dir / "grey-alpha8.png", 21, 13, PNG_COLOR_TYPE_GRAY_ALPHA, 8, false, false);
  writePng(dir / "grey-alpha16.png", 21, 13, PNG_COLOR_TYPE_GRAY_ALPHA, 16, false, false);
  writePng(dir / "grey-trns.png", 21, 13, PNG_COLOR_TYPE_GRAY, 8, false, true);
  writePng(dir / "rgb-trns.png", 21, 13, PNG_COLOR_TYPE_RGB, 8, false, true);
  writePng(dir / "rgb16-interlaced.png", 21, 13, PNG_COLOR_TYPE_RGB, 16, true, false);
  writePng(dir / "rgba8-interlaced.png", 21, 13, PNG_COLOR_TYPE_RGB_ALPHA, 8, true, false);
  for (const auto& e : fs::directory_iterator(dir)) checkSame(e.path());
  fs::remove_all(dir);
}

TEST_CASE("TIFFs in the usual layouts decode to exactly what OpenCV's imread gave") {
  const fs::path dir = test::scratchDir("parity-tiff");
  REQUIRE(cv::imwrite((dir / "rgb8-opencv.tif").string(), scene(30, 20, CV_8UC3)));
  REQUIRE(cv::imwrite((dir / "rgb16-opencv.tif").string(), scene(30, 20, CV_16UC3)));
  REQUIRE(cv::imwrite((dir / "grey8-opencv.tif").string(), scene(30, 20, CV_8UC1)));
  REQUIRE(cv::imwrite((dir / "grey16-opencv.tif").string(), scene(30, 20, CV_16UC1)));
  REQUIRE(cv::imwrite((dir / "rgb16-none.tif").string(), scene(30, 20, CV_16UC3), {cv::IMWRITE_TIFF_COMPRESSION, 1}));
  writeTiff(dir / "rgb16-tiled-lzw.tif", 37, 21, PHOTOMETRIC_RGB, 16, 3, true, PLANARCONFIG_CONTIG, COMPRESSION_LZW);
  writeTiff(dir / "rgb8-tiled.tif", 37, 21, PHOTOMETRIC_RGB, 8, 3, true, PLANARCONFIG_CONTIG, COMPRESSION_NONE);
  writeTiff(dir / "grey16-deflate.tif", 37, 21, PHOTOMETRIC_MINISBLACK, 16, 1, false, PLANARCONFIG_CONTIG, COMPRESSION_ADOBE_DEFLATE);
  writeTiff(dir / "rgba16.tif", 37, 21, PHOTOMETRIC_RGB, 16, 4, false, PLANARCONFIG_CONTIG, COMPRESSION_NONE);
  writeTiff(dir / "palette8.tif", 37, 21, PHOTOMETRIC_PALETTE, 8, 1, false, PLANARCONFIG_CONTIG, COMPRESSION_NONE);
  writeTiff(dir / "miniswhite8.tif", 37, 21, PHOTOMETRIC_MINISWHITE, 8, 1, false, PLANARCONFIG_CONTIG, COMPRESSION_NONE);
  writeTiff(dir / "rgb8-planar.tif", 37, 21, PHOTOMETRIC_RGB, 8, 3, false, PLANARCONFIG_SEPARATE, COMPRESSION_NONE);
  writeTiff(dir / "bilevel.tif", 37, 21, PHOTOMETRIC_MINISBLACK, 1, 1, false, PLANARCONFIG_CONTIG, COMPRESSION_NONE);
  for (const auto& e : fs::directory_iterator(dir)) checkSame(e.path());

  // OpenCV writes 4-channel TIFFs without an ExtraSamples tag, which libtiff warns about: such a
  // file is refused with libtiff's words, and decodes as before once that is accepted.
  const fs::path rgba = dir / "rgba8-opencv.tif";
  REQUIRE(cv::imwrite(rgba.string(), scene(30, 20, CV_8UC4)));
  CHECK_THROWS_AS(image::decodeImage(rgba, image::RawDecodeSettings()), image::DamagedImageError);
  CHECK_THAT(test::inputErrorOf(rgba, [&] { image::decodeImage(rgba, image::RawDecodeSettings()); }),
             Catch::Contains("ExtraSamples"));
  checkSame(rgba, true);
  fs::remove_all(dir);
}
