// surrogate info FILE: what a carrier, capture folder, image, .ptm, .rti or .lp holds.
#include <filesystem>
#include <iostream>
#include <sstream>
#include <system_error>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "image/decode.h"
#include "meta/metadata.h"
#include "formats/summary.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// The carrier as a JSON object, written into `j` (alone, or nested in a capture's object).
void carrierJson(JsonWriter& j, const carrier::Carrier& c) {
  int images = 0;
  for (const carrier::FileRecord& f : c.files) images += f.imageSize.has_value();
  j.beginObject().key("kind").value("carrier").key("title").value(c.header.title)
      .key("created").value(c.header.created).key("files").value(static_cast<int>(c.files.size()))
      .key("images").value(images).key("steps").beginArray();
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    j.beginObject().key("id").value(s.id).key("component").value(s.component)
        .key("version").value(s.version).key("status").value(r ? r->status : "not run")
        .key("interventions").value(static_cast<int>(s.interventions.size())).endObject();
  }
  j.endArray().key("creators").beginArray();
  for (const carrier::Creator& cr : c.header.creators)
    j.beginObject().key("name").value(cr.name).key("role").value(cr.role).endObject();
  j.endArray().key("decisions").beginArray();
  for (const carrier::Step& s : c.process)
    for (const carrier::Intervention& i : s.interventions)
      j.beginObject().key("step").value(s.id).key("component").value(s.component)
          .key("kind").value(i.kind).key("target").value(i.target).key("value").value(i.value)
          .key("who").value(i.who).key("time").value(i.time).key("reason").value(i.reason).endObject();
  j.endArray().key("runs").beginArray();
  for (const carrier::RunRecord& r : c.header.runs) {
    j.beginObject().key("id").value(r.id).key("command").value(r.command).key("who").value(r.who)
        .key("started").value(r.started).key("ended").value(r.ended).key("outcome").value(r.outcome)
        .key("arguments").beginArray();
    for (const std::string& a : r.arguments) j.value(a);
    j.endArray().key("notes").beginArray();
    for (const std::string& n : r.notes) j.value(n);
    j.endArray().endObject();
  }
  j.endArray().endObject();
}

// The standing decisions (human interventions, with who, when and why) and the run history,
// as text.
void printDecisionsAndRuns(const carrier::Carrier& c) {
  std::cout << "  standing decisions:";
  int n = 0;
  for (const carrier::Step& s : c.process) {
    for (const carrier::Intervention& i : s.interventions) {
      std::cout << "\n    " << i.kind << " " << i.target << (i.value.empty() ? "" : " = " + i.value)
                << " (" << s.component << ")\n      by " << i.who << ", " << i.time << ": "
                << i.reason;
      ++n;
    }
  }
  for (const carrier::Step& s : c.process)
    if (s.component == "CaptureIngest" && s.hasParam("lp"))
      std::cout << "\n    lights from " << s.param("lp") << " (dome capture)", ++n;
  std::cout << (n ? "\n" : " none\n");
  if (c.header.runs.empty()) return;
  std::cout << "  runs:\n";
  for (const carrier::RunRecord& r : c.header.runs) {
    std::string args;
    for (const std::string& a : r.arguments) args += " " + (a.find(' ') != std::string::npos || a.empty() ? "\"" + a + "\"" : a);
    std::cout << "    " << r.id << " " << r.started << " " << r.who << ": surrogate " << r.command
              << args << " -> " << r.outcome << "\n";
    for (const std::string& note : r.notes) std::cout << "      " << note << "\n";
  }
}

void printCarrier(const fs::path& path, bool json) {
  const carrier::Carrier c = carrier::loadCarrier(path);
  if (json) {
    JsonWriter j;
    carrierJson(j, c);
    std::cout << j.str() << "\n";
    return;
  }
  int images = 0;
  for (const carrier::FileRecord& f : c.files) images += f.imageSize.has_value();
  std::cout << path.string() << ": Surrogate carrier\n"
            << "  title:   " << c.header.title << "\n"
            << "  created: " << c.header.created << " on " << c.header.machine.hostname << "\n";
  for (const carrier::Creator& cr : c.header.creators)
    std::cout << "  " << cr.role << ": " << cr.name << "\n";
  std::cout << "  files:   " << c.files.size() << " (" << images << " images)\n  steps:\n";
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    std::cout << "    " << s.id << " " << s.component << " v" << s.version << ": "
              << (r ? r->status : "not run");
    if (!s.interventions.empty()) std::cout << ", " << s.interventions.size() << " intervention(s)";
    std::cout << "\n";
  }
  printDecisionsAndRuns(c);
}

// A capture folder; with --json, a processed capture's carrier is nested under "carrier".
void printCapture(const fs::path& path, bool json) {
  // A dome capture's .lp is a decision the carrier records (`run --lp`).
  const fs::path carrierPath = path / capture::kAssemblyDir / "carrier.xml";
  std::string domeLp;
  if (fs::exists(carrierPath))
    for (const carrier::Step& s : carrier::loadCarrier(carrierPath).process)
      if (s.component == "CaptureIngest") domeLp = s.param("lp", "");
  const capture::CaptureLayout layout = capture::scanCapture(path, 0, domeLp);
  int originals = 0, exports = 0;
  for (const capture::Shot& s : layout.shots) {
    originals += s.original.has_value();
    exports += s.exported.has_value();
  }
  const capture::Shot& first = layout.shots.front();
  const capture::ImageFile& sample = first.original ? *first.original : *first.exported;
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("capture").key("shots").value(static_cast<int>(layout.shots.size()))
        .key("originals").value(originals).key("exports").value(exports)
        .key("width").value(sample.width).key("height").value(sample.height)
        .key("lp").value(layout.lp.value_or(""));
    if (fs::exists(carrierPath)) {
      j.key("carrier");
      carrierJson(j, carrier::loadCarrier(carrierPath));
    }
    j.endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": capture folder\n"
            << "  shots:     " << layout.shots.size() << " (" << originals << " originals in "
            << (layout.originalsDir.empty() ? "-" : layout.originalsDir + "/") << ", " << exports
            << " exports)\n"
            << "  image:     " << sample.width << "x" << sample.height << " " << sample.format << "\n"
            << "  lights:    " << (layout.lp ? "given by " + *layout.lp + " (dome capture)" : "to be detected from the spheres")
            << "\n";
  for (const std::string& other : layout.others)
    if (other.find('/') == std::string::npos && lowerCase(fs::path(other).extension().string()) == ".lp")
      std::cout << "  note:      " << other << " is kept as a file of the capture but not used; for "
                << "a dome capture whose lights it gives, run with --lp " << other << "\n";
}

void printImage(const fs::path& path, bool json) {
  const image::ImageProbe probe = image::probeImage(path);
  const meta::CameraMetadata m = meta::readMetadata(path);
  auto opt = [](const auto& v) {
    std::ostringstream s;
    if (v) s << *v;
    return s.str();
  };
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("image").key("width").value(probe.width)
        .key("height").value(probe.height).key("make").value(opt(m.make))
        .key("model").value(opt(m.model)).key("serial").value(opt(m.bodySerial))
        .key("lens").value(opt(m.lens)).key("exposureTime").value(opt(m.exposureTime))
        .key("iso").value(opt(m.iso)).key("dateTimeOriginal").value(opt(m.dateTimeOriginal))
        .key("xmp").value(!m.xmpPacket.empty()).endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": image " << probe.width << "x" << probe.height << "\n"
            << "  camera:   " << opt(m.make) << " " << opt(m.model) << "  serial " << opt(m.bodySerial) << "\n"
            << "  lens:     " << opt(m.lens) << "  " << opt(m.focalLengthMm) << " mm  f/" << opt(m.fNumber) << "\n"
            << "  exposure: " << opt(m.exposureTime) << "  ISO " << opt(m.iso) << "\n"
            << "  taken:    " << opt(m.dateTimeOriginal) << "\n"
            << "  XMP:      " << (m.xmpPacket.empty() ? "none" : std::to_string(m.xmpPacket.size()) + " bytes") << "\n";
}

}  // namespace

int runCommandInfo(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {{"json", false, false, "print as JSON"}};
  Args args(argc, argv, 1, specs);
  if (args.helpRequested()) {
    std::cout << usageHeader("surrogate info FILE",
                             "Describe a carrier (carrier.xml), a capture folder, an image, or a "
                             ".ptm, .rti or .lp file.")
              << Args::describe(specs);
    return 0;
  }
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line", "give one file or folder: surrogate info FILE");
  const fs::path path = args.positional()[0];
  const bool json = args.has("json");
  // Error codes, not exceptions: a loop of symbolic links is the user's path, not a bug.
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec == std::errc::too_many_symbolic_link_levels)
    throwInputError(path.string(), "info", "is a loop of symbolic links; give the file or folder itself");
  if (!fs::exists(st)) throwInputError(path.string(), "info", "does not exist");
  const std::string ext = lowerCase(path.extension().string());
  if (fs::is_directory(st)) {
    if (fs::exists(path / capture::kAssemblyDir / "carrier.xml", ec) && !json) {
      printCapture(path, false);
      printCarrier(path / capture::kAssemblyDir / "carrier.xml", false);  // JSON: nested by printCapture
    } else {
      printCapture(path, json);
    }
  } else if (ext == ".xml") {
    printCarrier(path, json);
  } else if (ext == ".ptm" || ext == ".rti" || ext == ".lp") {
    const formats::FileSummary s = formats::summarize(path);
    std::cout << (json ? s.toJson() : s.toText()) << "\n";
  } else {
    printImage(path, json);
  }
  return 0;
}

}  // namespace surrogate::cli
