// surrogate info on an image (meta::describeImage), an .xmp sidecar (meta::summarizeXmpSidecar)
// or a web layout (publish::describeWebLayout), as text or JSON.
#include <iostream>
#include <optional>
#include <string>

#include "cli/info_print.h"
#include "core/text.h"
#include "formats/pronom.h"
#include "meta/camera_text.h"
#include "meta/image_summary.h"
#include "meta/metadata.h"
#include "publish/web_layout.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// The camera metadata as JSON members: every field the carrier records under <camera>, with
// numbers as numbers and the date in ISO 8601, and `shown`, the text `info` prints.
void cameraJson(JsonWriter& j, const meta::CameraMetadata& m) {
  auto text = [&](const char* k, const std::optional<std::string>& v) {
    if (v && !v->empty()) j.key(k).value(*v);
  };
  auto number = [&](const char* k, const auto& v) {
    if (v) j.key(k).value(static_cast<double>(*v));
  };
  text("make", m.make);
  text("model", m.model);
  text("serial", m.bodySerial);
  text("lens", m.lens);
  if (m.lens) j.key("lensFromMakerNote").value(m.lensFromMakerNote);
  if (m.lensMinFocalMm && m.lensMaxFocalMm)
    j.key("lensFocalRangeMm").beginArray().value(*m.lensMinFocalMm).value(*m.lensMaxFocalMm).endArray();
  number("focalLengthMm", m.focalLengthMm);
  number("fNumber", m.fNumber);
  text("exposureTime", m.exposureTime);
  number("exposureSeconds", m.exposureSeconds);
  number("iso", m.iso);
  if (m.dateTimeOriginal) j.key("dateTimeOriginal").value(meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  text("offsetTimeOriginal", m.offsetTimeOriginal);
  number("orientation", m.orientation);
  number("pixelWidth", m.pixelWidth);
  number("pixelHeight", m.pixelHeight);
  number("focalPlaneXResolution", m.focalPlaneXResolution);
  number("focalPlaneYResolution", m.focalPlaneYResolution);
  number("focalPlaneResolutionUnit", m.focalPlaneResolutionUnit);
  j.key("xmp").value(!m.xmpPacket.empty()).key("xmpBytes").value(static_cast<unsigned long long>(m.xmpPacket.size()));
  j.key("shown").beginObject();
  auto shown = [&](const char* k, const std::string& v) {
    if (!v.empty()) j.key(k).value(v);
  };
  shown("camera", meta::cameraText(m));
  shown("lens", meta::lensText(m));
  if (m.focalLengthMm) shown("focalLength", meta::focalLengthText(*m.focalLengthMm));
  if (m.fNumber) shown("aperture", meta::apertureText(*m.fNumber));
  if (m.exposureSeconds) shown("exposure", meta::exposureText(*m.exposureSeconds));
  if (m.dateTimeOriginal) shown("taken", meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  j.endObject();
}

void printImageJson(const meta::ImageSummary& s, const formats::PronomIdentity& id) {
  JsonWriter j;
  j.beginObject().key("kind").value("image").key("puid").value(id.puid).key("pronom").value(id.describe());
  j.key("decodable").value(s.decodable);
  if (s.decodable) j.key("width").value(s.width).key("height").value(s.height).key("format").value(s.format);
  else j.key("decodeProblem").value(s.decodeProblem);
  if (s.camera) cameraJson(j, *s.camera);
  else j.key("metadataProblem").value(s.metadataProblem);
  j.endObject();
  std::cout << j.str() << "\n";
}

void printCameraText(const meta::CameraMetadata& m) {
  auto line = [](const char* label, const std::string& value) {
    if (!value.empty()) std::cout << "  " << label << value << "\n";
  };
  const std::string camera = meta::cameraText(m);
  line("camera:      ", camera + (m.bodySerial ? (camera.empty() ? "serial " : ", serial ") + *m.bodySerial : ""));
  line("lens:        ", meta::lensText(m));
  line("exposure:    ", meta::exposureSettingsText(m));
  if (m.dateTimeOriginal) line("taken:       ", meta::dateTimeText(*m.dateTimeOriginal, m.offsetTimeOriginal));
  if (m.pixelWidth && m.pixelHeight)
    line("EXIF size:   ", std::to_string(*m.pixelWidth) + "x" + std::to_string(*m.pixelHeight));
  if (m.orientation)
    line("orientation: ", std::to_string(*m.orientation) + " (" + meta::orientationText(*m.orientation) + ")");
  if (m.focalPlaneXResolution) {
    const std::string x = fixedDecimals(*m.focalPlaneXResolution, 1);
    const std::string y = m.focalPlaneYResolution ? fixedDecimals(*m.focalPlaneYResolution, 1) : x;
    line("focal plane: ", (x == y ? x : x + " x " + y) + " " +
                              meta::resolutionUnitText(m.focalPlaneResolutionUnit.value_or(2)));
  }
  line("XMP:         ", m.xmpPacket.empty() ? "none" : std::to_string(m.xmpPacket.size()) + " bytes");
}

}  // namespace

void printImage(const fs::path& path, bool json) {
  const meta::ImageSummary s = meta::describeImage(path);
  const formats::PronomIdentity id = formats::identifyPronomFile(path);
  if (json) return printImageJson(s, id);
  std::cout << path.string() << ": ";
  if (s.decodable) std::cout << "image " << s.width << "x" << s.height << ", " << s.format << "\n";
  else std::cout << "image whose metadata Surrogate reads but whose pixels it cannot decode\n";
  std::cout << "  PRONOM:      " << id.describe() << "\n";
  if (s.camera) printCameraText(*s.camera);
  else std::cout << "  metadata:    cannot be read: " << s.metadataProblem << "\n";
  if (!s.decodable) std::cout << "  decoding:    refused: " << s.decodeProblem << "\n";
}

// An .xmp sidecar: what it records about its image, not the image itself.
void printXmpSidecar(const fs::path& path, bool json) {
  const meta::XmpSidecarSummary s = meta::summarizeXmpSidecar(path);
  const formats::PronomIdentity id = formats::identifyPronomFile(path);
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("xmp-sidecar").key("bytes").value(static_cast<unsigned long long>(s.bytes));
    auto text = [&](const char* k, const std::optional<std::string>& v) {
      if (v && !v->empty()) j.key(k).value(*v);
    };
    text("software", s.creatorTool);
    text("rating", s.rating);
    text("modified", s.modified);
    text("creator", s.creator);
    text("rights", s.rights);
    j.key("developSettings").value(s.developSettings);
    text("processVersion", s.processVersion);
    j.key("history").beginArray();
    for (const meta::XmpHistoryEvent& e : s.history)
      j.beginObject().key("action").value(e.action).key("when").value(e.when)
          .key("software").value(e.software).key("changed").value(e.changed).endObject();
    j.endArray().key("puid").value(id.puid).key("pronom").value(id.describe()).endObject();
    std::cout << j.str() << "\n";
    return;
  }
  auto line = [](const char* label, const std::optional<std::string>& v) {
    if (v && !v->empty()) std::cout << "  " << label << *v << "\n";
  };
  std::cout << path.string() << ": XMP sidecar (metadata kept next to an image, " << s.bytes
            << " bytes; Surrogate records it verbatim with its original)\n";
  std::cout << "  PRONOM:      " << id.describe() << "\n";
  line("written by:  ", s.creatorTool);
  line("modified:    ", s.modified);
  line("rating:      ", s.rating ? std::optional<std::string>(*s.rating == "-1" ? "rejected" : *s.rating + " of 5") : std::nullopt);
  line("creator:     ", s.creator);
  line("rights:      ", s.rights);
  std::cout << "  develop:     "
            << (s.developSettings ? std::to_string(s.developSettings) + " Camera Raw / Lightroom settings" +
                                        (s.processVersion ? " (process version " + *s.processVersion + ")" : "")
                                  : "no develop settings")
            << "\n";
  std::cout << "  history:     " << (s.history.empty() ? "none recorded" : std::to_string(s.history.size()) + " event(s)") << "\n";
  for (const meta::XmpHistoryEvent& e : s.history) {
    std::cout << "    " << (e.when.empty() ? "-" : e.when) << " " << e.action;
    if (!e.changed.empty()) std::cout << " (" << e.changed << ")";
    if (!e.software.empty()) std::cout << " by " << e.software;
    std::cout << "\n";
  }
}

// A web layout (publish/web_layout.h): what its info.json says and whether its planes are there.
void printWebLayout(const fs::path& path, bool json) {
  const publish::WebLayoutSummary s = publish::describeWebLayout(path);
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("web-layout").key("type").value(s.type).key("colorspace").value(s.colorspace)
        .key("basis").value(s.basis).key("width").value(s.width).key("height").value(s.height)
        .key("nplanes").value(s.nplanes).key("format").value(s.format);
    if (s.quality >= 0) j.key("quality").value(s.quality);
    if (s.resolution > 0) j.key("resolution").value(s.resolution);
    if (s.nodes > 0) j.key("nodes").value(s.nodes);
    j.key("planes").beginArray();
    for (const std::string& p : s.planes) j.value(p);
    j.endArray().key("missingPlanes").beginArray();
    for (const std::string& p : s.missingPlanes) j.value(p);
    j.endArray();
    if (!s.tiles.empty()) j.key("tiles").value(s.tiles);
    j.key("bytes").value(static_cast<unsigned long long>(s.bytes)).endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": web layout (OpenLIME, relight)\n"
            << "  model:   " << s.type << " " << s.colorspace << (s.basis.empty() ? "" : " (" + s.basis + ")") << ", "
            << s.width << "x" << s.height << ", " << s.nplanes << " coefficients per texel\n";
  // A learned basis (rbf, bilinear): where its interpolation's nodes are.
  if (s.type == "bilinear" && s.resolution > 0)
    std::cout << "  basis:   learned, " << s.resolution << "x" << s.resolution << " grid of light nodes (" << s.nodes
              << "), " << s.nplanes << " planes\n";
  else if (s.type == "rbf" && s.nodes > 0)
    std::cout << "  basis:   learned, radial basis over " << s.nodes << " light nodes, " << s.nplanes << " planes\n";
  std::cout
            << "  planes:  " << s.planes.size() << " " << s.format << " images"
            << (s.tiles.empty() ? std::string() : " (" + s.tiles + " tiles)")
            << (s.quality >= 0 ? ", quality " + std::to_string(s.quality) : std::string()) << ", " << s.bytes
            << " bytes with info.json\n";
  for (const std::string& p : s.missingPlanes) std::cout << "  missing: " << p << " (the viewers cannot show the model)\n";
}

}  // namespace surrogate::cli
