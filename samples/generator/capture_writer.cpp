#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "generator/capture_generator.h"
#include "generator/scene.h"
#include "image/decode.h"

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

  std::ostringstream lp;
  lp << truth.lights.size() << "\n";
  char line[256];
  for (std::size_t i = 0; i < truth.lights.size(); ++i) {
    std::snprintf(line, sizeof line, "%s %.9f %.9f %.9f\n",
                  (jpeg ? "jpeg-exports/" + shotName(static_cast<int>(i)) + ".jpg"
                        : "original-captures/" + shotName(static_cast<int>(i)) + ".dng").c_str(),
                  truth.lights[i][0], truth.lights[i][1], truth.lights[i][2]);
    lp << line;
  }
  writeFileAtomically(dir / "truth/lights.lp", lp.str());
  std::ostringstream spheres;
  for (const SphereTruth& s : truth.spheres) {
    std::snprintf(line, sizeof line, "%.9f %.9f %.9f\n", s.cx, s.cy, s.r);
    spheres << line;
  }
  writeFileAtomically(dir / "truth/spheres.txt", spheres.str());
  writeFileAtomically(dir / "truth/generator.txt", describe(o));
  writeFileAtomically(dir / "truth/README.txt",
                      "The truth of this generated capture (not part of the capture itself):\n"
                      "  lights.lp    the true light direction of every shot (x right, y up, z to the camera)\n"
                      "  spheres.txt  the true sphere circles: cx cy r in pixels (origin at the centre of\n"
                      "               the top-left pixel, y down)\n"
                      "  generator.txt  the options used\n");
}

}  // namespace surrogate::generator
