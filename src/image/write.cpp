#include "image/write.h"

#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/png_encoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image write";

// The Mat OpenCV's encoders expect: BGR order, 8-bit (core/image.h narrowSamples).
cv::Mat encoderMat(const Image& image) {
  cv::Mat m(image.height, image.width, CV_MAKETYPE(CV_8U, image.channels));
  narrowSamples(image.pixels.data(), image.pixels.size(), m.ptr<std::uint8_t>());
  if (m.channels() == 3) cv::cvtColor(m, m, cv::COLOR_RGB2BGR);
  return m;
}

void encode(const Image& image, const fs::path& path, const std::string& ext, const std::vector<int>& params) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, path.string(), kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  std::vector<unsigned char> bytes;
  bool ok = false;
  try {
    ok = cv::imencode(ext, encoderMat(image), bytes, params);
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
  encode(image, path, ".jpg", {cv::IMWRITE_JPEG_QUALITY, quality});
}

std::string opencvVersion() { return CV_VERSION; }

}  // namespace surrogate::image
