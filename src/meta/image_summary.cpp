#include "meta/image_summary.h"

#include "core/error.h"
#include "image/decode.h"

namespace surrogate::meta {

namespace {

const char* kindName(image::SourceKind kind) {
  switch (kind) {
    case image::SourceKind::CameraRaw: return "camera raw";
    case image::SourceKind::Jpeg: return "JPEG";
    case image::SourceKind::Tiff: return "TIFF";
    case image::SourceKind::Png: return "PNG";
  }
  return "image";
}

}  // namespace

ImageSummary describeImage(const std::filesystem::path& path) {
  ImageSummary s;
  std::optional<Error> refusal;
  try {
    const image::ImageProbe probe = image::probeImage(path);
    s.decodable = true;
    s.width = probe.width;
    s.height = probe.height;
    s.format = kindName(probe.kind);
  } catch (const Error& e) {
    s.decodeProblem = e.message();
    refusal = e;
  }
  try {
    s.camera = readMetadata(path);
  } catch (const Error& e) {
    if (refusal) throw *refusal;  // neither pixels nor metadata: not an image Surrogate reads
    s.metadataProblem = e.message();
  }
  return s;
}

}  // namespace surrogate::meta
