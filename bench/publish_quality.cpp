// The quality and size of the web copy on a real-size capture (issue 18, item 3).
//
// 1. Takes a capture `surrogate run` has fitted (--capture DIR), or generates one (36 JPEG
//    shots of 3000x2000 by default, kept in --dir between runs) and runs the pipeline on it in
//    this process with the four bases (ptm-lrgb, ptm-rgb, hsh2, hsh3).
// 2. For each model in finished-files/ and each JPEG quality: publishes it into a temporary
//    folder (publish/web_layout.h), reads the folder back (publish/web_reader.h), and relights
//    the file and the read-back model at every captured light (assembly-files/lights.lp) with
//    the renderer of `surrogate render` (fit/render.h).
// 3. Prints a Markdown table: per quality and basis, the worst and median PSNR of the 8-bit
//    relit images over the captured lights, the layout's size (info.json and planes) and the
//    whole folder's (with the viewer) as a share of the file's, and the time to publish.
//
//   publish_quality [--capture DIR | --dir DIR --images N --width W --height H]
//                   [--quality Q]... [--threads N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "fit/render.h"
#include "formats/lp.h"
#include "generator/capture_generator.h"
#include "publish/web_layout.h"
#include "publish/web_reader.h"
#include "run/plan.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// PSNR in dB of two relit images over their 8-bit values (the renderer widens 8 bits by 257);
// infinity when identical.
double psnr8(const Image& a, const Image& b) {
  double sumSq = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = (double(a.pixels[i]) - double(b.pixels[i])) / 257.0;
    sumSq += d * d;
  }
  if (sumSq == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 * double(a.pixels.size()) / sumSq);
}

// The capture the default run measures: generated once, fitted with the four bases; a stamp
// names what was made so that the next run with the same size reuses it.
fs::path fittedCapture(const fs::path& dir, const generator::GeneratorOptions& o, int threads) {
  const fs::path capture = dir / "capture", stamp = dir / "fitted.txt";
  const std::string want = std::to_string(o.images) + " " + std::to_string(o.width) + "x" + std::to_string(o.height);
  std::string have;
  if (FILE* f = std::fopen(stamp.c_str(), "r")) {
    char buffer[64] = {0};
    if (std::fgets(buffer, sizeof buffer, f)) have = buffer;
    std::fclose(f);
  }
  if (have == want) return capture;
  fs::remove_all(dir);
  std::printf("generating %s JPEG shots in %s ...\n", want.c_str(), capture.c_str());
  std::fflush(stdout);
  auto t0 = std::chrono::steady_clock::now();
  generator::writeCapture(o, capture);
  fs::remove_all(capture / "truth");  // the truth is for tests, not part of a capture
  std::printf("  generated in %.1f s; running the pipeline with the four bases ...\n", secondsSince(t0));
  std::fflush(stdout);
  t0 = std::chrono::steady_clock::now();
  run::RunRequest request;
  request.source = "export";
  request.bases = std::vector<std::string>{"ptm-lrgb", "ptm-rgb", "hsh2", "hsh3"};
  pipeline::RunSettings settings;
  settings.threads = threads;
  run::runCapture(capture, request, settings);
  std::printf("  run in %.1f s\n", secondsSince(t0));
  FILE* f = std::fopen(stamp.c_str(), "w");
  std::fputs(want.c_str(), f);
  std::fclose(f);
  return capture;
}

struct Row {
  int quality = 0;
  std::string basis;
  double worst = 0, median = 0;
  double layoutShare = 0, folderShare = 0;  // % of the model file's size
  double publishSeconds = 0;
};

// Publishes `model` at `quality` into `out` and compares the read-back model with the file at
// every light.
Row measure(const fs::path& model, const fit::Relightable& reference, const std::vector<formats::LightEntry>& lights,
            int quality, int threads, const fs::path& out) {
  Row row;
  row.quality = quality;
  row.basis = reference.basis();
  publish::PublishOptions options;
  options.quality = quality;
  options.threads = threads;
  fs::remove_all(out);
  const auto t0 = std::chrono::steady_clock::now();
  publish::publish(model, out, options);
  row.publishSeconds = secondsSince(t0);

  std::uintmax_t layout = 0, folder = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    if (!e.is_regular_file()) continue;
    const bool ofViewer = e.path().extension() == ".html" || e.path().extension() == ".js";
    folder += e.file_size();
    if (!ofViewer) layout += e.file_size();
  }
  row.layoutShare = 100.0 * double(layout) / double(fs::file_size(model));
  row.folderShare = 100.0 * double(folder) / double(fs::file_size(model));

  publish::WebLayoutModel web = publish::readWebLayout(out);
  const auto readBack = web.isPtm ? fit::makeRelightable(std::move(web.ptm)) : fit::makeRelightable(std::move(web.hsh));
  fit::RenderOptions render;
  render.threads = threads;
  std::vector<double> psnrs;
  for (const formats::LightEntry& l : lights)
    psnrs.push_back(psnr8(reference.render({l.x, l.y, l.z}, render), readBack->render({l.x, l.y, l.z}, render)));
  std::sort(psnrs.begin(), psnrs.end());
  row.worst = psnrs.front();
  const std::size_t n = psnrs.size();
  row.median = n % 2 ? psnrs[n / 2] : 0.5 * (psnrs[n / 2 - 1] + psnrs[n / 2]);
  fs::remove_all(out);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path capture, dir = fs::temp_directory_path() / "surrogate-publish-quality";
  std::vector<int> qualities;
  int threads = 0;
  generator::GeneratorOptions o;
  o.images = 36;
  o.width = 3000;
  o.height = 2000;
  o.formats = generator::OutputFormats::Jpeg;
  const auto usage = [] {
    std::fprintf(stderr, "usage: publish_quality [--capture DIR | --dir DIR --images N --width W --height H] "
                         "[--quality Q]... [--threads N]\n");
    return 2;
  };
  for (int i = 1; i < argc; i += 2) {
    if (i + 1 >= argc) return usage();
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--capture") capture = v;
    else if (a == "--dir") dir = v;
    else if (a == "--images") o.images = std::atoi(v.c_str());
    else if (a == "--width") o.width = std::atoi(v.c_str());
    else if (a == "--height") o.height = std::atoi(v.c_str());
    else if (a == "--quality") qualities.push_back(std::atoi(v.c_str()));
    else if (a == "--threads") threads = std::atoi(v.c_str());
    else return usage();
  }
  if (qualities.empty()) qualities = {100, 95, 90, 75};
  o.sphereRadius = std::min(o.width, o.height) / 13.0;
  try {
    if (capture.empty()) capture = fittedCapture(dir, o, threads);
    const auto lights = formats::readLp(capture / "assembly-files" / "lights.lp");
    std::vector<fs::path> models;
    for (const auto& e : fs::directory_iterator(capture / "finished-files"))
      if (e.path().extension() == ".ptm" || e.path().extension() == ".rti") models.push_back(e.path());
    std::sort(models.begin(), models.end());

    std::vector<Row> rows;
    const fs::path out = dir / "web";
    fs::create_directories(dir);
    for (const fs::path& model : models) {
      const auto reference = fit::openRelightable(model);
      std::printf("%s: %s, %dx%d, %ju bytes, %zu captured lights\n", model.filename().c_str(),
                  reference->basis().c_str(), reference->width(), reference->height(),
                  static_cast<std::uintmax_t>(fs::file_size(model)), lights.size());
      std::fflush(stdout);
      for (int q : qualities) rows.push_back(measure(model, *reference, lights, q, threads, out));
    }
    // Highest quality first; the bases in the order of docs/formats.md's tables.
    const std::vector<std::string> order = {"ptm-lrgb", "ptm-rgb", "hsh2", "hsh3"};
    const auto rank = [&](const std::string& b) { return std::find(order.begin(), order.end(), b) - order.begin(); };
    std::stable_sort(rows.begin(), rows.end(), [&](const Row& a, const Row& b) {
      return a.quality != b.quality ? a.quality > b.quality : rank(a.basis) < rank(b.basis);
    });
    std::printf("\n| quality | basis | worst PSNR | median PSNR | layout / file | with viewer | publish |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows)
      std::printf("| %d | %s | %.1f dB | %.1f dB | %.0f %% | %.0f %% | %.2f s |\n", r.quality, r.basis.c_str(),
                  r.worst, r.median, r.layoutShare, r.folderShare, r.publishSeconds);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
