#include "report/embed.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/image.h"
#include "formats/ptm.h"
#include "image/decode.h"
#include "image/write.h"
#include "formats/rti_hsh.h"
#include "report/html.h"

namespace surrogate::report {

namespace {
// A picture whose header claims more pixels than this is not decoded (a package is untrusted:
// a small file can claim a huge image).
constexpr std::uint64_t kMaxPicturePixels = 1ull << 28;

// The decoded picture as 8-bit RGB: 16-bit samples rounded to nearest, grey repeated.
cv::Mat displayRgb(const image::DecodedPixels& pixels) {
  const int w = pixels.width(), h = pixels.height(), c = pixels.channels();
  const std::size_t n = static_cast<std::size_t>(w) * h * c;
  std::vector<std::uint8_t> narrowed;
  const std::uint8_t* samples = nullptr;
  if (pixels.isNarrow()) {
    samples = static_cast<const std::uint8_t*>(pixels.data());
  } else {
    narrowed.resize(n);
    narrowSamples(pixels.wide.pixels.data(), n, narrowed.data());
    samples = narrowed.data();
  }
  cv::Mat rgb(h, w, CV_8UC3);
  if (c == 3) {
    std::copy(samples, samples + n, rgb.ptr<std::uint8_t>());
  } else {
    std::uint8_t* out = rgb.ptr<std::uint8_t>();
    for (std::size_t i = 0; i < n; ++i) out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = samples[i];
  }
  return rgb;
}
}  // namespace

std::optional<EmbeddedPicture> embedPicture(const std::string& bytes, int maxSide) {
  if (bytes.empty()) return std::nullopt;
  cv::Mat image;
  try {
    image = displayRgb(image::decodePicture(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                                            "picture", kMaxPicturePixels));
  } catch (const Error&) {
    return std::nullopt;  // not a complete PNG or JPEG: the page says so
  }
  EmbeddedPicture p;
  p.originalWidth = image.cols;
  p.originalHeight = image.rows;
  const int side = std::max(image.cols, image.rows);
  if (maxSide > 0 && side > maxSide) {
    const double f = static_cast<double>(maxSide) / side;
    cv::Mat small;
    cv::resize(image, small,
               cv::Size(std::max(1, static_cast<int>(std::lround(image.cols * f))),
                        std::max(1, static_cast<int>(std::lround(image.rows * f)))),
               0, 0, cv::INTER_AREA);
    image = small;
  }
  Image8 small;
  small.width = image.cols;
  small.height = image.rows;
  small.channels = 3;
  small.pixels.assign(image.ptr<std::uint8_t>(), image.ptr<std::uint8_t>() + image.total() * 3);
  std::string jpeg;
  try {
    jpeg = image::encodeJpeg(small, 88, "picture");
  } catch (const Error&) {
    return std::nullopt;
  }
  p.width = small.width;
  p.height = small.height;
  p.dataUri = "data:image/jpeg;base64," + base64(jpeg);
  return p;
}

namespace {

// Texels per block side so that the longer side is at most maxSide (1 = native resolution).
int blockSide(int width, int height, int maxSide) {
  const int side = std::max(width, height);
  return maxSide > 0 && side > maxSide ? (side + maxSide - 1) / maxSide : 1;
}

void writeNumbers(std::ostringstream& j, const char* name, const std::vector<double>& v) {
  j << ",\"" << name << "\":[";
  for (std::size_t k = 0; k < v.size(); ++k) j << (k ? "," : "") << v[k];
  j << "]";
}

std::string ptmRelightJson(const std::string& ptmBytes, int maxSide, const std::string& name) {
  const formats::PtmFile ptm = formats::parsePtm(
      reinterpret_cast<const std::uint8_t*>(ptmBytes.data()), ptmBytes.size(), name);
  const int step = blockSide(ptm.width, ptm.height, maxSide);
  const int w = (ptm.width + step - 1) / step, h = (ptm.height + step - 1) / step;
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  const int channels = lrgb ? 1 : 3;

  // Block average of bytes; rows top-first, texel-interleaved: ((c*h + y)*w + x)*6 + k.
  std::string coefficients(static_cast<std::size_t>(channels) * w * h * 6, '\0');
  std::string rgb(lrgb ? static_cast<std::size_t>(w) * h * 3 : 0, '\0');
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int x0 = x * step, y0 = y * step;
      const int x1 = std::min(ptm.width, x0 + step), y1 = std::min(ptm.height, y0 + step);
      const int n = (x1 - x0) * (y1 - y0);
      for (int c = 0; c < channels; ++c) {
        for (int k = 0; k < 6; ++k) {
          int sum = 0;
          for (int yy = y0; yy < y1; ++yy)
            for (int xx = x0; xx < x1; ++xx) sum += ptm.byte(xx, yy, k, c);
          coefficients[((static_cast<std::size_t>(c) * h + y) * w + x) * 6 + k] =
              static_cast<char>((sum + n / 2) / n);
        }
      }
      for (int c = 0; lrgb && c < 3; ++c) {
        int sum = 0;
        for (int yy = y0; yy < y1; ++yy)
          for (int xx = x0; xx < x1; ++xx)
            sum += ptm.rgb[(static_cast<std::size_t>(yy) * ptm.width + xx) * 3 + c];
        rgb[(static_cast<std::size_t>(y) * w + x) * 3 + c] = static_cast<char>((sum + n / 2) / n);
      }
    }
  }
  std::ostringstream j;
  j.precision(17);
  j << "{\"model\":\"ptm\",\"basis\":\"" << (lrgb ? "ptm-lrgb" : "ptm-rgb") << "\",\"format\":\""
    << (lrgb ? "lrgb" : "rgb") << "\",\"width\":" << w << ",\"height\":" << h
    << ",\"originalWidth\":" << ptm.width << ",\"originalHeight\":" << ptm.height;
  writeNumbers(j, "scale", std::vector<double>(ptm.scale.begin(), ptm.scale.end()));
  writeNumbers(j, "bias", std::vector<double>(ptm.bias.begin(), ptm.bias.end()));
  j << ",\"coefficients\":\"" << base64(coefficients) << "\",\"rgb\":\"" << base64(rgb) << "\"}";
  return j.str();
}

std::string hshRelightJson(const std::string& rtiBytes, int maxSide, const std::string& name) {
  const formats::HshFile hsh = formats::parseRti(
      reinterpret_cast<const std::uint8_t*>(rtiBytes.data()), rtiBytes.size(), name);
  const int step = blockSide(hsh.width, hsh.height, maxSide);
  const int w = (hsh.width + step - 1) / step, h = (hsh.height + step - 1) / step;
  const int terms = hsh.terms;
  // Block average of bytes, in the file's layout: ((y*w + x)*3 + c)*terms + k.
  std::string coefficients(static_cast<std::size_t>(w) * h * 3 * terms, '\0');
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int x0 = x * step, y0 = y * step;
      const int x1 = std::min(hsh.width, x0 + step), y1 = std::min(hsh.height, y0 + step);
      const int n = (x1 - x0) * (y1 - y0);
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < terms; ++k) {
          int sum = 0;
          for (int yy = y0; yy < y1; ++yy)
            for (int xx = x0; xx < x1; ++xx) sum += hsh.byte(xx, yy, c, k);
          coefficients[((static_cast<std::size_t>(y) * w + x) * 3 + c) * terms + k] =
              static_cast<char>((sum + n / 2) / n);
        }
      }
    }
  }
  std::ostringstream j;
  j.precision(17);
  j << "{\"model\":\"hsh\",\"basis\":\"" << (terms == 4 ? "hsh2" : terms == 9 ? "hsh3" : "hsh4")
    << "\",\"terms\":" << terms << ",\"width\":" << w << ",\"height\":" << h
    << ",\"originalWidth\":" << hsh.width << ",\"originalHeight\":" << hsh.height;
  writeNumbers(j, "scale", std::vector<double>(hsh.scale.begin(), hsh.scale.end()));
  writeNumbers(j, "bias", std::vector<double>(hsh.bias.begin(), hsh.bias.end()));
  j << ",\"coefficients\":\"" << base64(coefficients) << "\"}";
  return j.str();
}

}  // namespace

std::string relightJson(const std::string& modelBytes, int maxSide, const std::string& name) {
  if (modelBytes.compare(0, 4, "PTM_") == 0) return ptmRelightJson(modelBytes, maxSide, name);
  return hshRelightJson(modelBytes, maxSide, name);
}

}  // namespace surrogate::report
