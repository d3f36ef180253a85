#include "image/write.h"

#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/opencv_bridge.h"
#include "image/png_encoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image write";

// The Mat OpenCV's encoders expect: BGR order, 8-bit (rounded to nearest, integer arithmetic
// so the bytes never depend on floating-point rounding) or 16-bit.
cv::Mat encoderMat(const Image& image, bool eightBit) {
  cv::Mat m = toMat(image);
  if (eightBit) {
    cv::Mat m8(m.rows, m.cols, CV_MAKETYPE(CV_8U, m.channels()));
    for (int y = 0; y < m.rows; ++y) {
      const std::uint16_t* in = m.ptr<std::uint16_t>(y);
      std::uint8_t* out = m8.ptr<std::uint8_t>(y);
      for (int i = 0; i < m.cols * m.channels(); ++i)
        out[i] = static_cast<std::uint8_t>((in[i] + 128u) / 257u);
    }
    m = m8;
  }
  if (m.channels() == 3) cv::cvtColor(m, m, cv::COLOR_RGB2BGR);
  return m;
}

void encode(const Image& image, const fs::path& path, const std::string& ext, bool eightBit,
            const std::vector<int>& params) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, path.string(), kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  std::vector<unsigned char> bytes;
  bool ok = false;
  try {
    ok = cv::imencode(ext, encoderMat(image, eightBit), bytes, params);
  } catch (const cv::Exception& e) {
    throw Error(ErrorKind::Internal, path.string(), kStep, "OpenCV could not encode the image: " + e.msg);
  }
  if (!ok) throw Error(ErrorKind::Internal, path.string(), kStep, "OpenCV could not encode the image");
  writeFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace

void writePng(const Image& image, const fs::path& path) {
  writeFileAtomically(path, encodePng(image, path.string()));
}

void writeJpeg(const Image& image, const fs::path& path, int quality) {
  if (quality < 1 || quality > 100)
    throw Error(ErrorKind::Usage, path.string(), kStep, "JPEG quality must be 1 to 100");
  encode(image, path, ".jpg", true, {cv::IMWRITE_JPEG_QUALITY, quality});
}

std::string opencvVersion() { return CV_VERSION; }

}  // namespace surrogate::image
