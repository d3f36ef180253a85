// XMP sidecars (.xmp next to a raw file): Lightroom's and Camera Raw's develop settings and
// the photographer's descriptions. Kept verbatim; parsed only to check it is XMP at all.
#include <exiv2/exiv2.hpp>

#include <cstdlib>
#include <map>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "meta/exiv2_setup.h"
#include "meta/metadata.h"

namespace surrogate::meta {

namespace {

// Parses a sidecar's packet, holding the Exiv2 lock; throws Error(Input) naming the file when
// it is not XMP.
void parseSidecar(const std::filesystem::path& path, const std::string& packet, Exiv2::XmpData& parsed) {
  int failed = 1;
  try {
    failed = Exiv2::XmpParser::decode(parsed, packet);
  } catch (const std::exception&) {
    failed = 1;
  }
  if (failed != 0 || packet.find("rdf:RDF") == std::string::npos)
    throwInputError(path.string(), "metadata",
                    "is not a well-formed XMP sidecar (Exiv2 cannot parse it as an RDF/XML metadata packet)");
}

// A language alternative prints as `lang="x-default" text`: the text.
std::string plainText(const Exiv2::Xmpdatum& d) {
  std::string s = d.toString();
  if (d.typeId() == Exiv2::langAlt) {
    const std::string printed = d.print();
    const auto space = printed.find("\" ");
    s = printed.compare(0, 6, "lang=\"") == 0 && space != std::string::npos ? printed.substr(space + 2) : printed;
  }
  return s;
}

// One xmpMM:History entry's field, from a key such as "Xmp.xmpMM.History[2]/stEvt:action".
void addHistoryField(const std::string& key, const std::string& value,
                     std::map<long, XmpHistoryEvent>& events) {
  static const std::string prefix = "Xmp.xmpMM.History[";
  if (key.compare(0, prefix.size(), prefix) != 0) return;
  char* end = nullptr;
  const long index = std::strtol(key.c_str() + prefix.size(), &end, 10);
  const std::string field = end ? std::string(end) : "";
  XmpHistoryEvent& e = events[index];
  if (field == "]/stEvt:action") e.action = value;
  else if (field == "]/stEvt:when") e.when = value;
  else if (field == "]/stEvt:softwareAgent") e.software = value;
  else if (field == "]/stEvt:changed") e.changed = value;
}

}  // namespace

std::string readXmpSidecar(const std::filesystem::path& path, bool* escaped) {
  ensureExiv2Ready();
  std::string packet = readFile(path, "metadata");
  Exiv2::XmpData parsed;
  const std::lock_guard<std::mutex> lock(exiv2Mutex());
  parseSidecar(path, packet, parsed);
  // Text is data: a packet in another encoding, or with control characters, escaped.
  const bool clean = !needsEscaping(packet, true);
  if (escaped) *escaped = !clean;
  return clean ? packet : escapedText(packet, true);
}

XmpSidecarSummary summarizeXmpSidecar(const std::filesystem::path& path) {
  ensureExiv2Ready();
  const std::string packet = readFile(path, "metadata");
  XmpSidecarSummary s;
  s.bytes = packet.size();
  Exiv2::XmpData parsed;
  const std::lock_guard<std::mutex> lock(exiv2Mutex());
  parseSidecar(path, packet, parsed);
  std::map<long, XmpHistoryEvent> events;
  for (const Exiv2::Xmpdatum& d : parsed) {
    const std::string key = d.key();
    const std::string value = escapedText(plainText(d));
    if (key == "Xmp.xmp.CreatorTool") s.creatorTool = value;
    else if (key == "Xmp.xmp.Rating") s.rating = value;
    else if (key == "Xmp.xmp.MetadataDate" || (key == "Xmp.xmp.ModifyDate" && !s.modified)) s.modified = value;
    else if (key == "Xmp.dc.creator") s.creator = value;
    else if (key == "Xmp.dc.rights") s.rights = value;
    else if (key == "Xmp.crs.ProcessVersion") s.processVersion = value;
    if (d.groupName() == "crs") ++s.developSettings;
    addHistoryField(key, value, events);
  }
  for (auto& [index, e] : events) s.history.push_back(std::move(e));
  return s;
}

}  // namespace surrogate::meta
