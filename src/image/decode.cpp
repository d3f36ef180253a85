#include "image/decode.h"

#include "image/libraw_decoder.h"
#include "image/opencv_decoder.h"

namespace surrogate::image {

ImageProbe probeImage(const std::filesystem::path& path) {
  const SourceKind kind = classifyImageFile(path);
  return kind == SourceKind::CameraRaw ? probeCameraRaw(path) : checkExportStructure(path, kind);
}

Image decodeImage(const std::filesystem::path& path, const RawDecodeSettings& settings,
                  DecodeReport* report) {
  const SourceKind kind = classifyImageFile(path);
  return kind == SourceKind::CameraRaw ? decodeCameraRaw(path, settings, report)
                                       : decodeExport(path, kind, report);
}

}  // namespace surrogate::image
