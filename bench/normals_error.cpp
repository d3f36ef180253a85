// normals_error: the angle between a measured normal map and the true one, per pixel, as the
// figures of issue 53 give it (median, mean and 95th percentile, degrees).
//
//   normals_error MEASURED.png TRUE.png [--exclude-circles FILE] [--margin PX]
//
// Both are 16-bit RGB PNGs in the encoding of the pipeline's normals.png (src/fit/normals.h:
// value = round((n + 1) / 2 * 65535), x right, y up, z towards the camera), e.g. a run's
// finished-files/normals.png against a generated capture's truth/normals.png. Left out: the
// discs of the circles in FILE ("cx cy r" per line, pixels, y down: a generated capture's
// truth/spheres.txt, taken from beside TRUE.png when not given) grown by 10 px, where the
// sphere is not the object; and a margin of PX pixels (default 8) along the frame's edges,
// where the normals' finite differences reach out of the frame.
// The 95th percentile is the nearest rank; the median the middle value (or the mean of the two).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace fs = std::filesystem;

namespace {

constexpr double kCircleGrowth = 10;  // pixels around a sphere's disc left out too

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "normals_error: %s\n", message.c_str());
  std::exit(2);
}

cv::Mat readNormals(const std::string& path) {
  const cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (m.empty()) fail(path + ": cannot be read as an image; give a normals.png");
  if (m.type() != CV_16UC3) fail(path + ": is not a 16-bit RGB PNG (the encoding of normals.png, src/fit/normals.h)");
  return m;
}

struct Circle { double cx, cy, r; };

std::vector<Circle> readCircles(const fs::path& path) {
  std::ifstream in(path);
  if (!in) fail(path.string() + ": cannot be read; give the circles as \"cx cy r\" per line (truth/spheres.txt)");
  std::vector<Circle> out;
  Circle c;
  while (in >> c.cx >> c.cy >> c.r) out.push_back(c);
  if (!in.eof()) fail(path.string() + ": holds something other than \"cx cy r\" lines");
  return out;
}

// The unit normal of a pixel: OpenCV reads RGB PNGs as BGR.
cv::Vec3d normalAt(const cv::Mat& m, int x, int y) {
  const cv::Vec3w v = m.at<cv::Vec3w>(y, x);
  cv::Vec3d n(v[2] / 65535.0 * 2 - 1, v[1] / 65535.0 * 2 - 1, v[0] / 65535.0 * 2 - 1);
  const double len = cv::norm(n);
  return len > 0 ? n / len : n;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string circlesFile;
  int margin = 8;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("usage: normals_error MEASURED.png TRUE.png [--exclude-circles FILE] [--margin PX]\n");
      return 0;
    }
    if (a == "--exclude-circles" || a == "--margin") {
      if (i + 1 >= argc) fail(a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--exclude-circles") {
        circlesFile = v;
      } else {
        char* end = nullptr;
        const long m = std::strtol(v.c_str(), &end, 10);
        if (!end || *end != '\0' || m < 0) fail("--margin needs a number of pixels, not " + v);
        margin = static_cast<int>(m);
      }
      continue;
    }
    if (!a.empty() && a[0] == '-') fail(a + " is not an option (--exclude-circles FILE, --margin PX)");
    files.push_back(a);
  }
  if (files.size() != 2) fail("give MEASURED.png and TRUE.png (see --help)");
  const cv::Mat measured = readNormals(files[0]), truth = readNormals(files[1]);
  if (measured.size() != truth.size())
    fail(files[0] + " is " + std::to_string(measured.cols) + "x" + std::to_string(measured.rows) + " pixels but " + files[1] +
         " is " + std::to_string(truth.cols) + "x" + std::to_string(truth.rows) + ": compare maps of the same frame");
  if (circlesFile.empty() && fs::exists(fs::path(files[1]).parent_path() / "spheres.txt"))
    circlesFile = (fs::path(files[1]).parent_path() / "spheres.txt").string();
  const std::vector<Circle> circles = circlesFile.empty() ? std::vector<Circle>{} : readCircles(circlesFile);

  std::vector<double> errors;
  errors.reserve(std::size_t(truth.rows) * truth.cols);
  for (int y = margin; y < truth.rows - margin; ++y)
    for (int x = margin; x < truth.cols - margin; ++x) {
      bool excluded = false;
      for (const Circle& c : circles) excluded = excluded || std::hypot(x - c.cx, y - c.cy) < c.r + kCircleGrowth;
      if (excluded) continue;
      const double cosine = std::clamp(normalAt(measured, x, y).dot(normalAt(truth, x, y)), -1.0, 1.0);
      errors.push_back(std::acos(cosine) * 180 / M_PI);
    }
  if (errors.empty()) fail("no pixel left to compare (margin and circles cover the frame)");
  std::sort(errors.begin(), errors.end());
  const std::size_t n = errors.size();
  const double median = n % 2 ? errors[n / 2] : (errors[n / 2 - 1] + errors[n / 2]) / 2;
  double sum = 0;
  for (double e : errors) sum += e;
  const std::size_t rank95 = static_cast<std::size_t>(std::ceil(0.95 * n));
  std::printf("pixels %zu (margin %d px, %zu circle(s) + %.0f px left out%s%s)\n", n, margin, circles.size(), kCircleGrowth,
              circlesFile.empty() ? "" : ": ", circlesFile.c_str());
  std::printf("angle error, degrees: median %.2f  mean %.2f  p95 %.2f\n", median, sum / n, errors[std::max<std::size_t>(rank95, 1) - 1]);
  return 0;
}
