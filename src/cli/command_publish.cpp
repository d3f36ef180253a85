// surrogate publish FILE.ptm|FILE.rti|CAPTURE -o DIR [--quality Q]: the web layout that
// OpenLIME and Relight's web viewer read (publish/web_layout.h).
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "publish/web_layout.h"

namespace surrogate::cli {

namespace {
void printJson(const std::string& out, const publish::PublishOptions& options,
               const std::vector<publish::PublishedModel>& models) {
  JsonWriter j;
  j.beginObject().key("output").value(out).key("quality").value(options.quality).key("models").beginArray();
  for (const publish::PublishedModel& m : models) {
    j.beginObject().key("source").value(m.source).key("folder").value(m.folder).key("type").value(m.type)
        .key("colorspace").value(m.colorspace).key("width").value(m.width).key("height").value(m.height)
        .key("nplanes").value(m.nplanes).key("files").beginArray();
    for (const std::string& f : m.files) j.value(f);
    j.endArray().endObject();
  }
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}
}  // namespace

int runCommandPublish(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"o", true, false, "the folder to write (new, or empty)", "DIR"},
      {"output", true, false, "same as -o", "DIR"},
      {"quality", true, false, "JPEG quality 1..100 of the coefficient planes (default 95)", "Q"},
      {"json", false, false, "print what was written as JSON"},
  };
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs, "surrogate publish FILE.ptm|FILE.rti|CAPTURE -o DIR [--quality Q]",
                "Write a PTM or HSH model, or every one a capture's carrier records in finished-files/, "
                "in the web layout OpenLIME and Relight's web viewer read: info.json and JPEG "
                "coefficient planes."))
    return 0;
  const auto out = outputOption(args);
  if (args.positional().size() != 1 || !out)
    throw Error(ErrorKind::Usage, "", "command line",
                "give the model or capture and the folder to write: surrogate publish FILE.ptm -o DIR");
  publish::PublishOptions options;
  if (const auto q = args.value("quality")) {
    options.quality = args.intValue("quality", 95);
    if (options.quality < 1 || options.quality > 100)
      throw Error(ErrorKind::Usage, "--quality " + *q, "command line", "needs a JPEG quality from 1 to 100");
  }
  const auto models = publish::publish(args.positional()[0], *out, options);
  if (args.has("json")) {
    printJson(*out, options, models);
    return 0;
  }
  for (const publish::PublishedModel& m : models)
    std::cout << "wrote " << (std::filesystem::path(*out) / m.folder).generic_string() << "/ (" << m.type << " "
              << m.colorspace << ", " << m.width << "x" << m.height << ", " << m.files.size() - 1
              << " JPEG planes, quality " << options.quality << ") from " << m.source << "\n";
  return 0;
}

}  // namespace surrogate::cli
