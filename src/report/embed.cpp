#include "report/embed.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/base64.h"
#include "core/error.h"
#include "core/image.h"
#include "core/resident.h"
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

// 8-bit RGB at full size as the display copy: downscaled so the longer side is at most maxSide.
DisplayPicture displayOf(const cv::Mat& rgb, int maxSide) {
  DisplayPicture d;
  d.originalWidth = rgb.cols;
  d.originalHeight = rgb.rows;
  d.maxSide = maxSide;
  cv::Mat image = rgb;
  const int side = std::max(rgb.cols, rgb.rows);
  if (maxSide > 0 && side > maxSide) {
    const double f = static_cast<double>(maxSide) / side;
    cv::Mat small;  // a buffer of its own: `image` still shares rgb's pixels here
    cv::resize(rgb, small,
               cv::Size(std::max(1, static_cast<int>(std::lround(rgb.cols * f))),
                        std::max(1, static_cast<int>(std::lround(rgb.rows * f)))),
               0, 0, cv::INTER_AREA);
    image = small;
  }
  d.rgb.width = image.cols;
  d.rgb.height = image.rows;
  d.rgb.channels = 3;
  d.rgb.pixels.assign(image.ptr<std::uint8_t>(), image.ptr<std::uint8_t>() + image.total() * 3);
  return d;
}

// Fills an 8-bit RGB picture of w x h from 1- or 3-channel samples, row by row:
// narrowRow(y, out) writes row y's w * c 8-bit samples. Grey is repeated.
template <typename NarrowRow>
cv::Mat rgbOf(int w, int h, int c, NarrowRow narrowRow) {
  cv::Mat rgb(h, w, CV_8UC3);
  makeResident(rgb.data, rgb.total() * rgb.elemSize());  // every row is written below
  std::vector<std::uint8_t> grey(c == 3 ? 0 : static_cast<std::size_t>(w));
  for (int y = 0; y < h; ++y) {
    std::uint8_t* out = rgb.ptr<std::uint8_t>(y);
    if (c == 3) {
      narrowRow(y, out);
      continue;
    }
    narrowRow(y, grey.data());
    for (int x = 0; x < w; ++x) out[3 * x] = out[3 * x + 1] = out[3 * x + 2] = grey[x];
  }
  return rgb;
}

DisplayPicture displayOf(const image::DecodedPixels& pixels, int maxSide) {
  const int w = pixels.width(), c = pixels.channels();
  const std::size_t row = static_cast<std::size_t>(w) * c;
  return displayOf(rgbOf(w, pixels.height(), c,
                         [&](int y, std::uint8_t* out) {
                           if (pixels.isNarrow()) {
                             const auto* in = static_cast<const std::uint8_t*>(pixels.data()) + y * row;
                             std::copy(in, in + row, out);
                           } else {
                             narrowSamples(pixels.wide.pixels.data() + y * row, row, out);
                           }
                         }),
                   maxSide);
}
}  // namespace

DisplayPicture displayPicture(const Image& picture, int maxSide) {
  // The PNG of an 8-bit picture holds narrowSamples of its values, which decode as they are;
  // that of a 16-bit picture holds the values, which the display copy narrows the same way.
  const std::size_t row = static_cast<std::size_t>(picture.width) * picture.channels;
  return displayOf(rgbOf(picture.width, picture.height, picture.channels,
                         [&](int y, std::uint8_t* out) { narrowSamples(picture.pixels.data() + y * row, row, out); }),
                   maxSide);
}

std::optional<EmbeddedPicture> embedPicture(const DisplayPicture& picture) {
  std::string jpeg;
  try {
    jpeg = image::encodeJpeg(picture.rgb, 88, "picture");
  } catch (const Error&) {
    return std::nullopt;
  }
  EmbeddedPicture p;
  p.originalWidth = picture.originalWidth;
  p.originalHeight = picture.originalHeight;
  p.width = picture.rgb.width;
  p.height = picture.rgb.height;
  p.dataUri = "data:image/jpeg;base64," + base64(jpeg);
  return p;
}

std::optional<EmbeddedPicture> embedPicture(const std::string& bytes, int maxSide) {
  if (bytes.empty()) return std::nullopt;
  DisplayPicture display;
  try {
    display = displayOf(image::decodePicture(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                                             "picture", kMaxPicturePixels),
                        maxSide);
  } catch (const Error&) {
    return std::nullopt;  // not a complete PNG or JPEG: the page says so
  }
  return embedPicture(display);
}

namespace {

void writeNumbers(std::ostringstream& j, const char* name, const std::vector<double>& v) {
  j << ",\"" << name << "\":[";
  for (std::size_t k = 0; k < v.size(); ++k) j << (k ? "," : "") << v[k];
  j << "]";
}

// Block averages of `values` bytes a texel (held together, rows of `width` texels one after
// the other): each value averaged over the texels of each block of step x step (fewer at the
// right and bottom edges), rounded half up, (sum + n/2) / n. Written row by row of the model,
// which it reads once in order; integer sums, so the order of the additions changes nothing.
void blockAverage(const std::uint8_t* in, int width, int height, int values, int step, char* out) {
  const int w = (width + step - 1) / step, h = (height + step - 1) / step;
  const std::size_t rowValues = static_cast<std::size_t>(width) * values;
  std::vector<std::uint64_t> sums(static_cast<std::size_t>(w) * values);
  for (int by = 0; by < h; ++by) {
    std::fill(sums.begin(), sums.end(), 0);
    const int y0 = by * step, y1 = std::min(height, y0 + step);
    for (int y = y0; y < y1; ++y) {
      const std::uint8_t* row = in + static_cast<std::size_t>(y) * rowValues;
      for (int bx = 0; bx < w; ++bx) {
        std::uint64_t* sum = &sums[static_cast<std::size_t>(bx) * values];
        const std::uint8_t* texel = row + static_cast<std::size_t>(bx) * step * values;
        const std::uint8_t* end = row + static_cast<std::size_t>(std::min(width, (bx + 1) * step)) * values;
        for (; texel < end; texel += values)
          for (int v = 0; v < values; ++v) sum[v] += texel[v];
      }
    }
    for (int bx = 0; bx < w; ++bx) {
      const std::uint64_t n = static_cast<std::uint64_t>(std::min(width, (bx + 1) * step) - bx * step) * (y1 - y0);
      char* block = out + (static_cast<std::size_t>(by) * w + bx) * values;
      for (int v = 0; v < values; ++v)
        block[v] = static_cast<char>((sums[static_cast<std::size_t>(bx) * values + v] + n / 2) / n);
    }
  }
}

// Bytes to embed: a model's own array, or a block-averaged copy of it.
struct Bytes {
  const void* data;
  std::size_t size;
};

// The JSON object `head` (open: its fields so far) closed with the given fields as base64
// strings, appended in place: the model's copy is tens of megabytes at 1200 pixels a side, and
// a stream would grow and copy it several times.
std::string withBase64(std::string head, std::initializer_list<std::pair<const char*, Bytes>> fields) {
  std::size_t size = head.size() + 2;
  for (const auto& [name, bytes] : fields) size += std::char_traits<char>::length(name) + 6 + 4 * ((bytes.size + 2) / 3);
  reserveResident(head, size);
  for (const auto& [name, bytes] : fields) {
    head.append(",\"").append(name).append("\":\"");
    appendBase64(head, bytes.data, bytes.size);
    head += '"';
  }
  head += '}';
  return head;
}

// `planes` arrays of width x height texels of `values` bytes, one after the other: themselves
// when each block is one texel (a model no larger than the copy's side, as at 1200x800: a copy
// would be the same bytes), else each plane's block averages (blockAverage), one after the
// other in `averaged`.
Bytes blockAveraged(const std::uint8_t* in, int width, int height, int values, int planes, int step,
                    std::string& averaged) {
  const std::size_t plane = static_cast<std::size_t>(width) * height * values;
  if (step == 1) return {in, plane * planes};
  const int w = (width + step - 1) / step, h = (height + step - 1) / step;
  const std::size_t averagedPlane = static_cast<std::size_t>(w) * h * values;
  resizeResident(averaged, averagedPlane * planes);
  for (int c = 0; c < planes; ++c)
    blockAverage(in + c * plane, width, height, values, step, &averaged[c * averagedPlane]);
  return {averaged.data(), averaged.size()};
}

}  // namespace

std::size_t relightShare(std::size_t totalBytes, std::size_t models) {
  if (totalBytes == 0) return 0;
  return std::min(kRelightModelBytes, totalBytes / std::max<std::size_t>(1, models));
}

int relightBlockSide(int width, int height, std::size_t bytesPerTexel, int maxSide, std::size_t maxBytes) {
  const int side = std::max(width, height);
  int step = maxSide > 0 && side > maxSide ? (side + maxSide - 1) / maxSide : 1;
  const auto bytesAt = [&](int s) {
    return static_cast<std::uint64_t>((width + s - 1) / s) * static_cast<std::uint64_t>((height + s - 1) / s) * bytesPerTexel;
  };
  // At most sqrt(width * height * bytesPerTexel / maxBytes) + 1 steps: a few hundred for the
  // largest model a budget admits.
  if (maxBytes > 0)
    while (step < side && bytesAt(step) > maxBytes) ++step;
  return step;
}

std::string relightJson(const formats::PtmFile& ptm, int maxSide, std::size_t maxBytes) {
  const bool lrgb = ptm.format == formats::PtmFile::Format::Lrgb;
  const int step = relightBlockSide(ptm.width, ptm.height, lrgb ? 9 : 18, maxSide, maxBytes);
  const int w = (ptm.width + step - 1) / step, h = (ptm.height + step - 1) / step;

  // Block averages; rows top-first, texel-interleaved: ((c*h + y)*w + x)*6 + k, as the
  // model's planes are (the 6 bytes of a texel together, one plane per channel).
  std::string coefficients, rgb;
  const Bytes coefficientBytes =
      blockAveraged(ptm.coefficients.data(), ptm.width, ptm.height, 6, lrgb ? 1 : 3, step, coefficients);
  const Bytes rgbBytes = lrgb ? blockAveraged(ptm.rgb.data(), ptm.width, ptm.height, 3, 1, step, rgb) : Bytes{nullptr, 0};
  std::ostringstream j;
  j.precision(17);
  j << "{\"model\":\"ptm\",\"basis\":\"" << (lrgb ? "ptm-lrgb" : "ptm-rgb") << "\",\"format\":\""
    << (lrgb ? "lrgb" : "rgb") << "\",\"width\":" << w << ",\"height\":" << h
    << ",\"originalWidth\":" << ptm.width << ",\"originalHeight\":" << ptm.height;
  writeNumbers(j, "scale", std::vector<double>(ptm.scale.begin(), ptm.scale.end()));
  writeNumbers(j, "bias", std::vector<double>(ptm.bias.begin(), ptm.bias.end()));
  return withBase64(j.str(), {{"coefficients", coefficientBytes}, {"rgb", rgbBytes}});
}

std::string relightJson(const formats::HshFile& hsh, int maxSide, std::size_t maxBytes) {
  const int step = relightBlockSide(hsh.width, hsh.height, 3 * static_cast<std::size_t>(hsh.terms), maxSide, maxBytes);
  const int w = (hsh.width + step - 1) / step, h = (hsh.height + step - 1) / step;
  const int terms = hsh.terms;
  // Block averages, in the file's layout: ((y*w + x)*3 + c)*terms + k.
  std::string averaged;
  const Bytes coefficients = blockAveraged(hsh.coefficients.data(), hsh.width, hsh.height, 3 * terms, 1, step, averaged);
  std::ostringstream j;
  j.precision(17);
  j << "{\"model\":\"hsh\",\"basis\":\"" << (terms == 4 ? "hsh2" : terms == 9 ? "hsh3" : "hsh4")
    << "\",\"terms\":" << terms << ",\"width\":" << w << ",\"height\":" << h
    << ",\"originalWidth\":" << hsh.width << ",\"originalHeight\":" << hsh.height;
  writeNumbers(j, "scale", std::vector<double>(hsh.scale.begin(), hsh.scale.end()));
  writeNumbers(j, "bias", std::vector<double>(hsh.bias.begin(), hsh.bias.end()));
  return withBase64(j.str(), {{"coefficients", coefficients}});
}

std::string relightJson(const std::string& modelBytes, int maxSide, const std::string& name, std::size_t maxBytes) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(modelBytes.data());
  if (modelBytes.compare(0, 4, "PTM_") == 0)
    return relightJson(formats::parsePtm(bytes, modelBytes.size(), name), maxSide, maxBytes);
  return relightJson(formats::parseRti(bytes, modelBytes.size(), name), maxSide, maxBytes);
}

}  // namespace surrogate::report
