// Bad frames made from real photographs at test time (tests/data/real-rti/SOURCE.md): what an
// adversary or an unlucky shoot does to one frame of a good light-probe set. Each is derived
// with OpenCV only (none of Surrogate's code), from the set's own reference lights and circle,
// so the tests of tests/e2e/test_bad_frames_e2e.cpp judge Surrogate against something outside it.
//
//   ProbeSet set = probeSet("lightprobe-1");
//   cv::Mat gone = paintedOut(set, 4);        // Image_05 with its highlight filled by the median
//   cv::Mat moved = shifted(set.frames[4], 40, 0);
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace e2e {

struct ProbeSet {
  std::filesystem::path dir;
  std::vector<std::string> names;  // Image_01 .. Image_12
  std::vector<cv::Mat> frames;     // 8-bit BGR, as decoded
  std::vector<std::array<double, 3>> lights;  // reference, x right, y up, z to the camera
  double cx = 0, cy = 0, r = 0;    // the reference circle in pixels, origin top-left, y down
  cv::Mat median;                  // per-pixel, per-channel median of the frames
};

// The set's frames, reference lights and circle (circle_data.txt: origin at the bottom-left,
// 1-based), and the per-pixel median of its frames.
inline ProbeSet probeSet(const std::filesystem::path& dir) {
  ProbeSet s;
  s.dir = dir;
  for (int i = 1; i <= 12; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "Image_%02d", i);
    s.names.push_back(name);
    s.frames.push_back(cv::imread((dir / (std::string(name) + ".JPG")).string(), cv::IMREAD_COLOR));
  }
  std::ifstream circle(dir / "circle_data.txt");
  double bx = 0, by = 0;
  circle >> bx >> by >> s.r;
  s.cx = bx - 1;
  s.cy = s.frames[0].rows - by;
  std::ifstream lights(dir / "light_directions.txt");
  std::vector<double> v;
  for (double t; lights >> t;) v.push_back(t);
  const std::size_t n = v.size() / 3;
  for (std::size_t i = 0; i < n; ++i) s.lights.push_back({v[i], v[n + i], v[2 * n + i]});
  // The median over 12 values per pixel and channel: the lower of the two middle ones.
  const cv::Mat& f0 = s.frames[0];
  s.median.create(f0.size(), f0.type());
  std::vector<uchar> values(s.frames.size());
  for (int y = 0; y < f0.rows; ++y)
    for (int x = 0; x < f0.cols * 3; ++x) {
      for (std::size_t k = 0; k < s.frames.size(); ++k) values[k] = s.frames[k].ptr<uchar>(y)[x];
      std::nth_element(values.begin(), values.begin() + (values.size() - 1) / 2, values.end());
      s.median.ptr<uchar>(y)[x] = values[(values.size() - 1) / 2];
    }
  return s;
}

// Where frame i's highlight is by the reference: the sphere's point whose normal halves the
// angle between the light and the view (orthographic camera, view (0, 0, 1)).
inline cv::Point2d referenceHighlight(const ProbeSet& s, std::size_t i) {
  const auto& l = s.lights[i];
  const double hx = l[0], hy = l[1], hz = l[2] + 1, n = std::sqrt(hx * hx + hy * hy + hz * hz);
  return {s.cx + s.r * hx / n, s.cy - s.r * hy / n};
}

// Frame i with its highlight painted out: a disc of 10 % of the sphere's radius (the saturated
// core and the glare's brightest part, 42 px on these sets) filled with the median of the frames,
// as if the light had not reached the sphere there.
inline cv::Mat paintedOut(const ProbeSet& s, std::size_t i, double discRadius = 0.10) {
  cv::Mat out = s.frames[i].clone();
  cv::Mat mask = cv::Mat::zeros(out.size(), CV_8U);
  cv::circle(mask, referenceHighlight(s, i), static_cast<int>(std::lround(discRadius * s.r)), 255, cv::FILLED);
  s.median.copyTo(out, mask);
  return out;
}

// The frame moved by (dx, dy) pixels (the edge repeated), as a sphere or a camera knocked.
inline cv::Mat shifted(const cv::Mat& frame, double dx, double dy) {
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat out;
  cv::warpAffine(frame, out, m, frame.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

// The frame turned by `degrees` about its centre (a camera bumped on its tripod).
inline cv::Mat rotated(const cv::Mat& frame, double degrees) {
  const cv::Mat m = cv::getRotationMatrix2D(cv::Point2f((frame.cols - 1) / 2.0f, (frame.rows - 1) / 2.0f), degrees, 1);
  cv::Mat out;
  cv::warpAffine(frame, out, m, frame.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

// The frame at `factor` times its exposure: sRGB decoded to linear light (IEC 61966-2-1),
// scaled, clipped at full scale and encoded again.
inline cv::Mat exposed(const cv::Mat& frame, double factor) {
  cv::Mat lut(1, 256, CV_8U);
  for (int v = 0; v < 256; ++v) {
    const double c = v / 255.0;
    double lin = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    lin = std::min(1.0, lin * factor);
    const double e = lin <= 0.0031308 ? 12.92 * lin : 1.055 * std::pow(lin, 1 / 2.4) - 0.055;
    lut.at<uchar>(v) = cv::saturate_cast<uchar>(e * 255 + 0.5);
  }
  cv::Mat out;
  cv::LUT(frame, lut, out);
  return out;
}

}  // namespace e2e
