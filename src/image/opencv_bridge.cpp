#include "image/opencv_bridge.h"

#include <cstring>
#include <string>

#include "core/error.h"

namespace surrogate::image {

cv::Mat toMat(const Image& image) {
  cv::Mat m(image.height, image.width, CV_MAKETYPE(CV_16U, image.channels));
  const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
  for (int y = 0; y < image.height; ++y)
    std::memcpy(m.ptr<std::uint16_t>(y), &image.pixels[y * row], row * sizeof(std::uint16_t));
  return m;
}

Image fromMat(const cv::Mat& mat, Transfer transfer, int bitsPerSample) {
  const int depth = mat.depth();
  const int channels = mat.channels();
  if ((depth != CV_8U && depth != CV_16U) || (channels != 1 && channels != 3 && channels != 4))
    throw Error(ErrorKind::Internal, "", "image conversion",
                "fromMat needs an 8- or 16-bit Mat with 1, 3 or 4 channels, not type " +
                    std::to_string(mat.type()));
  const int kept = channels == 4 ? 3 : channels;
  Image im(mat.cols, mat.rows, kept);
  im.transfer = transfer;
  im.bitsPerSample = bitsPerSample;
  for (int y = 0; y < mat.rows; ++y) {
    std::uint16_t* out = &im.pixels[im.index(0, y)];
    if (depth == CV_8U) {
      const std::uint8_t* in = mat.ptr<std::uint8_t>(y);
      for (int x = 0; x < mat.cols; ++x)
        for (int c = 0; c < kept; ++c) *out++ = static_cast<std::uint16_t>(in[x * channels + c] * 257);
    } else if (kept == channels) {
      std::memcpy(out, mat.ptr<std::uint16_t>(y), std::size_t(mat.cols) * channels * sizeof(std::uint16_t));
    } else {
      const std::uint16_t* in = mat.ptr<std::uint16_t>(y);
      for (int x = 0; x < mat.cols; ++x)
        for (int c = 0; c < kept; ++c) *out++ = in[x * channels + c];
    }
  }
  return im;
}

}  // namespace surrogate::image
