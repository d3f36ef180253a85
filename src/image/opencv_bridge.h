// Internal: include only from .cpp files. It pulls in OpenCV's core header (about a second to
// parse), and public headers of src/ folders never expose cv::Mat (docs/developer-guide.md,
// "Code conventions").
//
// surrogate::Image <-> cv::Mat, keeping RGB order. OpenCV's own codecs use BGR; these
// functions do not reorder channels, so a Mat from toMat() is RGB and must be converted
// (cv::COLOR_RGB2BGR) before cv::imwrite, and a Mat from cv::imread must be converted to RGB
// before fromMat().
//
//   cv::Mat m = toMat(image);                       // CV_16UC3, RGB
//   cv::GaussianBlur(m, m, cv::Size(5, 5), 1.5);
//   Image out = fromMat(m, image.transfer, image.bitsPerSample);
#pragma once

#include <opencv2/core.hpp>

#include "core/image.h"

namespace surrogate::image {

// A copy (the Mat owns its pixels; the Image may be destroyed afterwards): CV_16UC1 or
// CV_16UC3 (or CV_16UC4 for 4 channels) in the Image's channel order.
cv::Mat toMat(const Image& image);

// A copy of a CV_8U or CV_16U Mat with 1, 3 or 4 channels (a 4th channel is dropped) into an
// Image. 8-bit samples are widened by *257 (255 -> 65535). `bitsPerSample` records the source
// depth (8 or 16); `transfer` how the values relate to light. Throws Error(Internal) for other
// Mat types.
Image fromMat(const cv::Mat& mat, Transfer transfer, int bitsPerSample);

}  // namespace surrogate::image
