#include "image/write_any.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "image/opencv_bridge.h"
#include "image/write.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {
constexpr const char* kStep = "image write";
}  // namespace

std::optional<PictureFormat> pictureFormatFor(const fs::path& path) {
  const std::string ext = lowerCase(path.extension().string());
  if (ext == ".png") return PictureFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return PictureFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return PictureFormat::Tiff;
  return std::nullopt;
}

const char* pictureFormatName(PictureFormat format) {
  switch (format) {
    case PictureFormat::Png: return "PNG";
    case PictureFormat::Jpeg: return "JPEG";
    case PictureFormat::Tiff: return "TIFF";
  }
  return "PNG";
}

void writeTiff(const Image& image, const fs::path& path) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, path.string(), kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  cv::Mat m = toMat(image);
  if (image.bitsPerSample <= 8) {
    // Rounded to nearest as writePng does.
    cv::Mat m8(m.rows, m.cols, CV_MAKETYPE(CV_8U, m.channels()));
    narrowSamples(image.pixels.data(), image.pixels.size(), m8.ptr<std::uint8_t>());
    m = m8;
  }
  if (m.channels() == 3) cv::cvtColor(m, m, cv::COLOR_RGB2BGR);
  std::vector<unsigned char> bytes;
  bool ok = false;
  try {
    ok = cv::imencode(".tiff", m, bytes, {cv::IMWRITE_TIFF_COMPRESSION, 1});  // 1: none
  } catch (const cv::Exception& e) {
    throw Error(ErrorKind::Internal, path.string(), kStep, "OpenCV could not encode the TIFF: " + e.msg);
  }
  if (!ok) throw Error(ErrorKind::Internal, path.string(), kStep, "OpenCV could not encode the TIFF");
  writeFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

void writePicture(const Image& image, const fs::path& path, int jpegQuality) {
  const auto format = pictureFormatFor(path);
  if (!format)
    throw Error(ErrorKind::Usage, path.string(), kStep,
                "the picture's format comes from its name: end it in .png, .jpg, .jpeg, .tif or .tiff");
  switch (*format) {
    case PictureFormat::Png: writePng(image, path); return;
    case PictureFormat::Jpeg: writeJpeg(image, path, jpegQuality); return;
    case PictureFormat::Tiff: writeTiff(image, path); return;
  }
}

}  // namespace surrogate::image
