// XMP sidecars (.xmp next to a raw file): Lightroom's and Camera Raw's develop settings and
// the photographer's descriptions. Kept verbatim; parsed only to check it is XMP at all.
#include <exiv2/exiv2.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "meta/exiv2_setup.h"
#include "meta/metadata.h"

namespace surrogate::meta {

std::string readXmpSidecar(const std::filesystem::path& path) {
  ensureExiv2Ready();
  std::string packet = readFile(path, "metadata");
  Exiv2::XmpData parsed;
  int failed = 1;
  const std::lock_guard<std::mutex> lock(exiv2Mutex());
  try {
    failed = Exiv2::XmpParser::decode(parsed, packet);
  } catch (const std::exception&) {
    failed = 1;
  }
  if (failed != 0 || packet.find("rdf:RDF") == std::string::npos)
    throwInputError(path.string(), "metadata",
                    "is not a well-formed XMP sidecar (Exiv2 cannot parse it as an RDF/XML metadata packet)");
  return packet;
}

}  // namespace surrogate::meta
