// Image <-> cv::Mat for other folders' .cpp files: copies, RGB order kept, 8-bit widened.
#include "fixtures.h"
#include "image/opencv_bridge.h"

using namespace surrogate;

TEST_CASE("toMat copies an RGB image into a CV_16UC3 Mat in the same channel order") {
  Image im(3, 2, 3);
  im.at(2, 1, 0) = 111;
  im.at(2, 1, 2) = 333;
  const cv::Mat m = image::toMat(im);
  CHECK(m.type() == CV_16UC3);
  CHECK(m.at<cv::Vec3w>(1, 2)[0] == 111);
  CHECK(m.at<cv::Vec3w>(1, 2)[2] == 333);
  im.at(2, 1, 0) = 999;  // a copy: the Mat does not see later changes
  CHECK(m.at<cv::Vec3w>(1, 2)[0] == 111);
}

TEST_CASE("fromMat widens 8-bit values, drops a fourth channel and round-trips 16-bit") {
  cv::Mat m8(2, 2, CV_8UC4, cv::Scalar(1, 2, 255, 9));
  const Image a = image::fromMat(m8, Transfer::Srgb, 8);
  CHECK(a.channels == 3);
  CHECK(a.bitsPerSample == 8);
  CHECK(a.at(1, 1, 0) == 257);
  CHECK(a.at(1, 1, 2) == 65535);

  Image grey(4, 3, 1);
  grey.transfer = Transfer::Linear;
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = static_cast<std::uint16_t>(i * 5000);
  const Image back = image::fromMat(image::toMat(grey), Transfer::Linear, 16);
  CHECK(back.pixels == grey.pixels);
  CHECK(back.transfer == Transfer::Linear);

  CHECK_THROWS_AS(image::fromMat(cv::Mat(2, 2, CV_32FC1), Transfer::Srgb, 16), Error);
}
