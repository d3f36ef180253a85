#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "generator/capture_generator.h"
#include "generator/chart.h"
#include "generator/scene.h"
#include "image/decode.h"
#include "image/write.h"

namespace surrogate::generator {

namespace fs = std::filesystem;

namespace {

std::string shotName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "IMG_%04d", index + 1);
  return name;
}

std::string describe(const GeneratorOptions& o) {
  std::ostringstream s;
  s << "images " << o.images << "\nwidth " << o.width << "\nheight " << o.height << "\nspheres "
    << o.spheres << "\nsphere-radius " << o.sphereRadius << "\nnoise " << o.noise
    << "\njpeg-quality " << o.jpegQuality << "\nseed " << o.seed << "\ntexture "
    << (o.strongTexture ? "strong" : "normal") << "\nshadows " << (o.shadows ? "yes" : "no") << "\n";
  // The hard cases only when used: the file of a capture without them keeps its bytes.
  if (o.reflections) s << "reflections yes\n";
  if (o.dustSpecks > 0) s << "dust " << o.dustSpecks << "\n";
  if (o.glare > 0) s << "glare " << o.glare << "\n";
  if (o.darkFrame >= 0) s << "dark-frame " << o.darkFrame + 1 << "\n";
  if (o.noFlashFrame >= 0) s << "no-flash-frame " << o.noFlashFrame + 1 << "\n";
  if (o.lightConeDeg > 0) s << "light-cone " << o.lightConeDeg << "\nlight-cone-elevation " << o.lightConeElevationDeg << "\n";
  if (o.lightDistance > 0) s << "light-distance " << o.lightDistance << "\n";
  if (o.sphereSeparation > 0) s << "sphere-separation " << o.sphereSeparation << "\n";
  if (o.colourChart) s << "colour-chart " << o.chartReference << "\n";
  if (o.colourCast != kNoColourCast) {
    s << "colour-cast";
    for (std::size_t k = 0; k < o.colourCast.size(); ++k) s << (k ? "," : " ") << o.colourCast[k];
    s << "\n";
  }
  if (o.exposure != 1) s << "exposure " << o.exposure << "\n";
  return s.str();
}

}  // namespace

void writeCapture(const GeneratorOptions& o, const fs::path& dir) {
  const CaptureTruth truth = planCapture(o);
  if (fs::exists(dir) && !fs::is_empty(dir))
    throw Error(ErrorKind::Usage, dir.string(), "generator", "is not empty; give a new folder");
  const bool dng = o.formats != OutputFormats::Jpeg, jpeg = o.formats != OutputFormats::Dng;
  if (dng) fs::create_directories(dir / "original-captures");
  if (jpeg) fs::create_directories(dir / "jpeg-exports");
  fs::create_directories(dir / "truth");
  const Scene scene(o, truth);

  // Shots one after another, each rendered with all threads: memory stays at one image.
  GeneratorOptions inner = o;
  for (int i = 0; i < o.images; ++i) {
    const Image linear = renderShot(scene, inner, truth, i);
    if (dng) {
      DngInfo info;
      char date[32];
      std::snprintf(date, sizeof date, "2026:01:01 12:%02d:%02d", (i / 60) % 60, i % 60);
      info.dateTimeOriginal = date;
      info.serial = "SYN-" + std::to_string(o.seed);
      writeDng(linear, info, dir / "original-captures" / (shotName(i) + ".dng"));
    }
    if (jpeg) {
      Image srgb = image::srgbEncode(linear);
      srgb.bitsPerSample = 8;
      image::writeJpeg(srgb, dir / "jpeg-exports" / (shotName(i) + ".jpg"), o.jpegQuality);
    }
  }

  const auto fileName = [&](std::size_t i) {
    return jpeg ? "jpeg-exports/" + shotName(static_cast<int>(i)) + ".jpg"
                : "original-captures/" + shotName(static_cast<int>(i)) + ".dng";
  };
  std::ostringstream lp;
  lp << truth.lights.size() << "\n";
  char line[256];
  for (std::size_t i = 0; i < truth.lights.size(); ++i) {
    std::snprintf(line, sizeof line, "%s %.9f %.9f %.9f\n", fileName(i).c_str(), truth.lights[i][0],
                  truth.lights[i][1], truth.lights[i][2]);
    lp << line;
  }
  writeFileAtomically(dir / "truth/lights.lp", lp.str());
  if (!truth.positions.empty()) {
    std::ostringstream positions;
    positions << "# file X Y Z (pixels; origin at image point ((W-1)/2, (H-1)/2) on the object's plane, X right, "
                 "Y up, Z towards the camera) distance (|X| in frame widths)\n";
    for (std::size_t i = 0; i < truth.positions.size(); ++i) {
      const auto& x = truth.positions[i];
      std::snprintf(line, sizeof line, "%s %.6f %.6f %.6f %.9g\n", fileName(i).c_str(), x[0], x[1], x[2],
                    std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / o.width);
      positions << line;
    }
    writeFileAtomically(dir / "truth/light-positions.txt", positions.str());
  }
  image::writePng(trueNormals(scene, o), dir / "truth/normals.png");
  std::ostringstream spheres;
  for (const SphereTruth& s : truth.spheres) {
    std::snprintf(line, sizeof line, "%.9f %.9f %.9f\n", s.cx, s.cy, s.r);
    spheres << line;
  }
  writeFileAtomically(dir / "truth/spheres.txt", spheres.str());
  writeFileAtomically(dir / "truth/generator.txt", describe(o));
  std::string readme =
      "The truth of this generated capture (not part of the capture itself):\n"
      "  lights.lp    the true light direction of every shot (x right, y up, z to the camera)\n"
      "  spheres.txt  the true sphere circles: cx cy r in pixels (origin at the centre of\n"
      "               the top-left pixel, y down)\n"
      "  generator.txt  the options used\n"
      "  normals.png  the true normals, encoded as the pipeline's normals.png: 16-bit RGB,\n"
      "               value = round((n + 1) / 2 * 65535), x right, y up, z to the camera,\n"
      "               rows top first; on a sphere, the sphere's own normal\n";
  if (!truth.positions.empty())
    readme +=
        "  light-positions.txt  every light's position: file, X Y Z in pixels (origin at image point\n"
        "               ((W-1)/2, (H-1)/2) on the object's plane, X right, Y up, Z to the camera),\n"
        "               and its distance from there in frame widths. Each point p of the scene is\n"
        "               lit from normalize(X - p), at (|X| / |X - p|)^2 the intensity of the\n"
        "               light at infinity; lights.lp gives X / |X|\n";
  if (!truth.chart.reference.empty()) {
    writeFileAtomically(dir / "truth/colour-chart.txt", chartTruthText(truth.chart, o.width, o.height));
    readme +=
        "  colour-chart.txt  the ColorChecker Classic lying flat in the frame: its reference (the\n"
        "               edition whose values painted it), the grid's four corners (the outer corners\n"
        "               of patches 0, 5, 23, 18, src/colour/chart_detection.h's order) and every\n"
        "               patch's centre and side in pixels (x right, y down, pixel centres at\n"
        "               integer coordinates), its reference Lab (D50) and its albedo (linear sRGB);\n"
        "               bench/chart_error measures an image's colour error on it\n";
  }
  writeFileAtomically(dir / "truth/README.txt", readme);
}

}  // namespace surrogate::generator
