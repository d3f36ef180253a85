// surrogate render FILE.ptm|FILE.rti|DIR --light x,y,z -o OUT.png|OUT.jpg|OUT.tif [--gain g]
// [--specular] [--quality Q]: the output's format is the one its name ends in. DIR (or
// DIR/info.json) is a web layout, read back by publish/web_reader.h (PTM, HSH, or a learned
// rbf or bilinear basis, fit/learned_relightable.h).
#include <algorithm>
#include <cmath>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "core/error.h"
#include "core/json.h"
#include "core/memory_budget.h"
#include "core/text.h"
#include "fit/learned_relightable.h"
#include "fit/render.h"
#include "image/write_any.h"
#include "publish/web_reader.h"

namespace surrogate::cli {

namespace {
// The model to relight: a .ptm or .rti, or a web layout's folder or info.json. `from` says
// which web layout was read, for the output line ("" for a file).
std::unique_ptr<fit::Relightable> openModel(const std::string& path, std::uint64_t memory, std::string* from) {
  const formats::ModelBudget budget{memory, fit::kRenderBytesPerTexel};
  if (!publish::isWebLayoutPath(path)) return fit::openRelightable(path, budget);
  publish::WebLayoutModel web = publish::readWebLayout(path, budget);
  *from = "from the web layout " + web.infoJson.string();
  if (web.requantised) *from += ", its coefficients re-quantised to 8 bits per term";
  if (web.isLearned) return fit::makeRelightable(std::move(web.learned));
  return web.isPtm ? fit::makeRelightable(std::move(web.ptm)) : fit::makeRelightable(std::move(web.hsh));
}
}  // namespace

int runCommandRender(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"light", true, false, "light direction x,y,z (x right, y up, z to the camera); |x,y| > 1 "
                             "extrapolates beyond grazing (PTM)", "X,Y,Z"},
      {"gain", true, false, "diffuse gain g (PTM; 1 = none; > 1 shows relief more strongly)", "G"},
      {"specular", false, false, "add specular enhancement from the recovered normals"},
      {"threads", true, false, "worker threads (default: all cores)", "N"},
      {"memory", true, false, "memory budget (default 2G): a larger model is refused from its header", "SIZE"},
      {"o", true, false, "the picture to write: .png, .jpg/.jpeg (JPEG) or .tif/.tiff (TIFF)", "OUT", OptionGroup::Output},
      {"output", true, false, "same as -o", "OUT", OptionGroup::Output},
      {"quality", true, false, "JPEG quality 1..100 (default 95; JPEG output only)", "Q", OptionGroup::Output},
      {"quiet", false, false, "print nothing but errors", "", OptionGroup::Output},
      {"verbose", false, false, "also the light as elevation and azimuth, and the gain, enhancement and quality used",
       "", OptionGroup::Output},
      {"json", false, false, "print what was written as JSON", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  const Verbosity verbosity = verbosityOf(args);
  if (helpShown(args, specs,
                {"surrogate render FILE.ptm|FILE.rti|DIR --light x,y,z -o OUT.png|OUT.jpg|OUT.tif [--gain g] [--specular]",
                 "Relight a PTM or HSH file, or a web layout (a folder `surrogate publish` wrote, or its "
                 "info.json, of a PTM, HSH or learned rbf or bln basis), under any light and save the picture, in "
                 "the format its name ends in.",
                 {{"surrogate render stela12/finished-files/ptm-lrgb.ptm --light -0.5,0.3,0.81 -o raking.png",
                   "the model lit from the upper left at about 54 degrees elevation"},
                  {"surrogate render coin.ptm --light 0,0,1 --gain 3 -o relief.jpg",
                   "lit from the camera, with the relief shown more strongly, as a JPEG"}},
                 commonExitCodes("the picture is written")}))
    return 0;
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out || !args.has("light"))
    throw Error(ErrorKind::Usage, "", "command line",
                "give the model, the light and the output: surrogate render FILE --light x,y,z -o OUT.png");
  // The output first: a name whose format is unknown, a folder, a missing folder or a path the
  // output rule forbids is refused before the model is read.
  checkOutputFile("-o", *out, "relit.png");
  const auto format = image::pictureFormatFor(*out);
  if (!format)
    throw Error(ErrorKind::Usage, "-o " + *out, "command line",
                "the picture's format comes from its name: end it in .png (PNG), .jpg or .jpeg "
                "(JPEG) or .tif or .tiff (TIFF)");
  int quality = 95;
  if (const auto q = args.value("quality")) {
    if (*format != image::PictureFormat::Jpeg)
      throw Error(ErrorKind::Usage, "--quality " + *q, "command line",
                  "applies to JPEG output only (-o NAME.jpg); " + *out + " is written as " +
                      image::pictureFormatName(*format));
    quality = args.intValue("quality", 95);
    if (quality < 1 || quality > 100)
      throw Error(ErrorKind::Usage, "--quality " + *q, "command line", "needs a JPEG quality from 1 to 100");
  }
  const std::vector<double> l = parseNumberList(*args.value("light"), 3, "--light");
  fit::RenderOptions options;
  options.diffuseGain = args.doubleValue("gain", 1.0);
  if (!(options.diffuseGain > 0))
    throw Error(ErrorKind::Usage, "--gain", "command line", "needs a number above 0");
  options.specular = args.has("specular");
  options.threads = threadsOption(args);
  std::uint64_t memory = kDefaultMemoryBudget;
  if (const auto m = args.value("memory")) memory = parseByteSize(*m, "--memory");
  std::string from;
  const auto model = openModel(args.positional()[0], memory, &from);
  image::writePicture(model->render({l[0], l[1], l[2]}, options), *out, quality);
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("format").value(image::pictureFormatName(*format))
        .key("basis").value(model->basis())
        .key("width").value(model->width()).key("height").value(model->height()).key("light").beginArray()
        .value(l[0]).value(l[1]).value(l[2]).endArray().endObject();
    std::cout << j.str() << "\n";
    return 0;
  }
  if (verbosity == Verbosity::Quiet) return 0;
  std::cout << "wrote " << *out << " (" << image::pictureFormatName(*format) << ", " << model->width() << "x"
            << model->height() << ", " << model->basis() << (from.empty() ? "" : ", " + from) << ")\n";
  if (verbosity == Verbosity::Verbose) {
    // The direction as a photographer sets a lamp: elevation above the object's plane, azimuth
    // anticlockwise from the right (x right, y up).
    const double length = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    constexpr double kDegrees = 180.0 / 3.14159265358979323846;
    const double elevation = length > 0 ? std::asin(std::clamp(l[2] / length, -1.0, 1.0)) * kDegrees : 0.0;
    const double azimuth = std::atan2(l[1], l[0]) * kDegrees;
    std::cout << "  light " << l[0] << "," << l[1] << "," << l[2] << ": elevation " << fixedDecimals(elevation, 1)
              << " deg, azimuth " << fixedDecimals(azimuth < 0 ? azimuth + 360 : azimuth, 1) << " deg\n"
              << "  gain " << options.diffuseGain << ", specular enhancement " << (options.specular ? "on" : "off");
    if (*format == image::PictureFormat::Jpeg) std::cout << ", JPEG quality " << quality;
    std::cout << "\n";
  }
  return 0;
}

}  // namespace surrogate::cli
