// surrogate render FILE.ptm|FILE.rti --light x,y,z -o OUT.png [--gain g] [--specular]
#include <cmath>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "fit/render.h"
#include "image/decode.h"

namespace surrogate::cli {

int runCommandRender(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"light", true, false, "light direction x,y,z (x right, y up, z to the camera); |x,y| > 1 "
                             "extrapolates beyond grazing (PTM)", "X,Y,Z"},
      {"o", true, false, "the PNG to write", "OUT.png"},
      {"output", true, false, "same as -o", "OUT.png"},
      {"gain", true, false, "diffuse gain g (PTM; 1 = none; > 1 shows relief more strongly)", "G"},
      {"specular", false, false, "add specular enhancement from the recovered normals"},
      {"threads", true, false, "worker threads (default: all cores)", "N"},
      {"json", false, false, "print what was written as JSON"},
  };
  Args args(argc, argv, 1, specs);
  if (args.helpRequested()) {
    std::cout << usageHeader("surrogate render FILE.ptm|FILE.rti --light x,y,z -o OUT.png [--gain g] [--specular]",
                             "Relight a PTM or HSH file under any light and save the picture.")
              << Args::describe(specs);
    return 0;
  }
  const auto out = args.has("o") ? args.value("o") : args.value("output");
  if (args.positional().size() != 1 || !out || !args.has("light"))
    throw Error(ErrorKind::Usage, "", "command line",
                "give the model, the light and the output: surrogate render FILE --light x,y,z -o OUT.png");
  const std::vector<double> l = parseNumberList(*args.value("light"), 3, "--light");
  fit::RenderOptions options;
  options.diffuseGain = args.doubleValue("gain", 1.0);
  if (!(options.diffuseGain > 0))
    throw Error(ErrorKind::Usage, "--gain", "command line", "needs a number above 0");
  options.specular = args.has("specular");
  options.threads = args.intValue("threads", 0);
  const auto model = fit::openRelightable(args.positional()[0]);
  image::writePng(model->render({l[0], l[1], l[2]}, options), *out);
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("output").value(*out).key("basis").value(model->basis())
        .key("width").value(model->width()).key("height").value(model->height()).key("light").beginArray()
        .value(l[0]).value(l[1]).value(l[2]).endArray().endObject();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::cout << "wrote " << *out << " (" << model->width() << "x" << model->height() << ", "
            << model->basis() << ")\n";
  return 0;
}

}  // namespace surrogate::cli
