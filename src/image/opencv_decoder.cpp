#include "image/opencv_decoder.h"

#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "image/jpeg_structure.h"
#include "image/opencv_bridge.h"
#include "image/png_structure.h"
#include "image/tiff_structure.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {
constexpr const char* kStep = "image decode";
}  // namespace

ImageProbe checkExportStructure(const fs::path& path, SourceKind kind) {
  ImageProbe probe;
  probe.kind = kind;
  std::string problem;
  switch (kind) {
    case SourceKind::Jpeg: {
      const JpegStructure s = readJpegStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = s.problem;
      break;
    }
    case SourceKind::Png: {
      const PngStructure s = readPngStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = s.problem;
      break;
    }
    case SourceKind::Tiff: {
      const TiffStructure s = readTiffStructure(path);
      probe.width = s.width;
      probe.height = s.height;
      problem = tiffProblem(s);
      break;
    }
    case SourceKind::CameraRaw:
      throw Error(ErrorKind::Internal, path.string(), kStep, "camera raw files are LibRaw's to check");
  }
  if (!problem.empty()) throwInputError(path.string(), kStep, problem);
  if (probe.width <= 0 || probe.height <= 0)
    throwInputError(path.string(), kStep, "the image declares no size (0 pixels wide or high)");
  return probe;
}

Image decodeExport(const fs::path& path, SourceKind kind, DecodeReport* report) {
  checkExportStructure(path, kind);
  cv::Mat m;
  try {
    m = cv::imread(path.string(),
                   cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH | cv::IMREAD_IGNORE_ORIENTATION);
  } catch (const cv::Exception& e) {
    throwInputError(path.string(), kStep, "OpenCV cannot decode it: " + e.msg);
  }
  if (m.empty())
    throwInputError(path.string(), kStep, "OpenCV cannot decode it: the image data is damaged");
  if (m.depth() != CV_8U && m.depth() != CV_16U)
    throwInputError(path.string(), kStep,
                    "unsupported pixel type: Surrogate reads 8- and 16-bit integer images only");
  cv::Mat rgb;
  switch (m.channels()) {
    case 1: rgb = m; break;
    case 3: cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB); break;
    case 4: cv::cvtColor(m, rgb, cv::COLOR_BGRA2RGB); break;
    default:
      throwInputError(path.string(), kStep,
                      "unsupported channel count " + std::to_string(m.channels()) + " (1, 3 or 4 expected)");
  }
  Image im = fromMat(rgb, Transfer::Srgb, m.depth() == CV_8U ? 8 : 16);
  if (report) {
    *report = DecodeReport{};
    report->decoder = "OpenCV " + opencvVersion();
  }
  return im;
}

std::string opencvVersion() { return CV_VERSION; }

}  // namespace surrogate::image
