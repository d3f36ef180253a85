// surrogate-generate: writes a synthetic HRTI capture with known truth (see
// capture_generator.h). Used by the demo, the tests and the benchmarks.
#include <cstdlib>
#include <iostream>
#include <string>

#include "core/error.h"
#include "generator/capture_generator.h"

using namespace surrogate;

namespace {
const char* kHelp =
    "usage: surrogate-generate --out DIR [options]\n\n"
    "Writes a synthetic Highlight-RTI capture: DNG originals (real Bayer mosaic) in\n"
    "DIR/original-captures/, JPEG exports in DIR/jpeg-exports/, the truth in DIR/truth/\n"
    "(light directions, sphere circles, true normals as a normals.png; README.txt there).\n\n"
    "options:\n"
    "  --images N           number of shots (default 24)\n"
    "  --width W --height H image size (default 1200x800)\n"
    "  --spheres 1|2        glossy spheres in the frame (default 1)\n"
    "  --sphere-radius R    pixels (default 80)\n"
    "  --noise SIGMA        read noise in 16-bit levels (default 100)\n"
    "  --jpeg-quality Q     of the exports (default 95)\n"
    "  --seed S             everything random derives from it (default 1)\n"
    "  --texture normal|strong\n"
    "  --no-shadows         no cast shadows\n"
    "  --formats both|dng|jpeg\n"
    "  --threads T          (default: all cores; output identical at any count)\n"
    "  --light-distance D   near lights: each D frame widths from the frame's centre along its\n"
    "                       direction (at least 1, and above the spheres); every point lit\n"
    "                       from its own direction with inverse-square fall-off; truth/\n"
    "                       light-positions.txt gives the positions (default 0: at infinity)\n"
    "  --sphere-separation S\n"
    "                       with --spheres 2: the second sphere S pixels left of the first,\n"
    "                       on its row (default: the two top corners)\n\n"
    "hard cases (each off by default; docs/hrti-math.md, \"Generated hard cases\"):\n"
    "  --reflections        a bright window and a dim room mirrored in the sphere(s), the\n"
    "                       same in every shot\n"
    "  --dust N             N bright specks of dust fixed on each sphere (0-100), lit by the flash\n"
    "  --glare G            a lens glare streak through each highlight, G of full scale next\n"
    "                       to the core (0-2; 0.5 is a strong streak)\n"
    "  --dark-frame N       shot N (IMG_000N, from 1) exposed at 5 % (a weak flash)\n"
    "  --no-flash-frame N   shot N (from 1) lit by the room's ambient light alone\n"
    "  --light-cone DEG     every light within DEG degrees of one direction (a narrow cone)\n"
    "  --light-cone-elevation E\n"
    "                       that direction's elevation in degrees (default 90, the view\n"
    "                       axis); the cone must stay 5 degrees above the horizon\n\n"
    "colour (issue 54; each off by default):\n"
    "  --colour-chart       a ColorChecker Classic lying flat in the bottom-left of the frame,\n"
    "                       turned 3 degrees, painted with its reference values; truth/\n"
    "                       colour-chart.txt gives its corners and patches\n"
    "  --chart-reference ID its edition (default colorchecker-classic-2014; also\n"
    "                       colorchecker-classic-pre-2014)\n"
    "  --colour-cast C      the camera's response in linear light, camera RGB = M * scene RGB:\n"
    "                       none (default), warm (rows 1.10 0.14 0.04 / 0.10 0.88 0.08 /\n"
    "                       0.03 0.16 0.72), cool (0.80 0.06 0.00 / 0.04 0.94 0.06 /\n"
    "                       0.02 0.08 1.14) or nine numbers m00,m01,...,m22 (row-major)\n"
    "  --exposure F         multiplies the exposure of every shot (default 1)\n";

double number(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (!end || *end != '\0') throw Error(ErrorKind::Usage, option, "command line", std::string("needs a number, not ") + text);
  return v;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    generator::GeneratorOptions o;
    std::string out, chartReference;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::cout << kHelp;
        return 0;
      }
      if (a == "--no-shadows") {
        o.shadows = false;
        continue;
      }
      if (a == "--colour-chart") {
        o.colourChart = true;
        continue;
      }
      if (a == "--reflections") {
        o.reflections = true;
        continue;
      }
      if (i + 1 >= argc) throw Error(ErrorKind::Usage, a, "command line", "needs a value (see --help)");
      const char* v = argv[++i];
      if (a == "--out") out = v;
      else if (a == "--images") o.images = static_cast<int>(number(a, v));
      else if (a == "--width") o.width = static_cast<int>(number(a, v));
      else if (a == "--height") o.height = static_cast<int>(number(a, v));
      else if (a == "--spheres") o.spheres = static_cast<int>(number(a, v));
      else if (a == "--sphere-radius") o.sphereRadius = number(a, v);
      else if (a == "--noise") o.noise = number(a, v);
      else if (a == "--jpeg-quality") o.jpegQuality = static_cast<int>(number(a, v));
      else if (a == "--seed") o.seed = static_cast<std::uint64_t>(number(a, v));
      else if (a == "--threads") o.threads = static_cast<int>(number(a, v));
      else if (a == "--dust") o.dustSpecks = static_cast<int>(number(a, v));
      else if (a == "--glare") o.glare = number(a, v);
      else if (a == "--dark-frame") o.darkFrame = static_cast<int>(number(a, v)) - 1;  // IMG_000N is index N-1
      else if (a == "--no-flash-frame") o.noFlashFrame = static_cast<int>(number(a, v)) - 1;
      else if (a == "--light-cone") o.lightConeDeg = number(a, v);
      else if (a == "--light-cone-elevation") o.lightConeElevationDeg = number(a, v);
      else if (a == "--light-distance") o.lightDistance = number(a, v);
      else if (a == "--sphere-separation") o.sphereSeparation = number(a, v);
      else if (a == "--chart-reference") chartReference = v;
      else if (a == "--colour-cast") o.colourCast = generator::parseColourCast(v);
      else if (a == "--exposure") o.exposure = number(a, v);
      else if (a == "--texture") {
        if (std::string(v) != "normal" && std::string(v) != "strong")
          throw Error(ErrorKind::Usage, a, "command line", "is normal or strong");
        o.strongTexture = std::string(v) == "strong";
      } else if (a == "--formats") {
        const std::string f = v;
        if (f == "both") o.formats = generator::OutputFormats::Both;
        else if (f == "dng") o.formats = generator::OutputFormats::Dng;
        else if (f == "jpeg") o.formats = generator::OutputFormats::Jpeg;
        else throw Error(ErrorKind::Usage, a, "command line", "is both, dng or jpeg");
      } else {
        throw Error(ErrorKind::Usage, a, "command line", "is not an option (see --help)");
      }
    }
    if (!chartReference.empty() && !o.colourChart)
      throw Error(ErrorKind::Usage, "--chart-reference", "command line", "names the chart's edition: give --colour-chart with it");
    if (!chartReference.empty()) o.chartReference = chartReference;
    if (out.empty()) throw Error(ErrorKind::Usage, "--out", "command line", "is required (see --help)");
    generator::writeCapture(o, out);
    std::cout << "wrote " << o.images << " shots to " << out << "\n";
    return 0;
  } catch (const Error& e) {
    std::cerr << "surrogate-generate: " << e.what() << "\n";
    return e.exitCode();
  }
}
