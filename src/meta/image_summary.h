// ImageSummary: what an image file is, as plain data for `surrogate info` and any page that
// shows a photograph's record: whether Surrogate decodes its pixels (image/decode.h,
// probeImage) and its camera metadata (readMetadata). A camera format LibRaw does not decode
// (CR3, some DNGs) still has its metadata described, the refusal given with it.
//
//   const meta::ImageSummary s = meta::describeImage("original-captures/IMG_0001.CR2");
//   if (s.decodable) std::cout << s.width << "x" << s.height << " " << s.format << "\n";
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "meta/metadata.h"

namespace surrogate::meta {

struct ImageSummary {
  bool decodable = false;
  int width = 0, height = 0;  // as decoded with default settings, when decodable
  std::string format;         // "camera raw", "JPEG", "TIFF", "PNG", when decodable
  std::string decodeProblem;  // why the pixels cannot be decoded, otherwise
  std::optional<CameraMetadata> camera;
  std::string metadataProblem;  // why the metadata cannot be read, when it cannot
};

// Throws the decoder's Error(Input) when neither the pixels nor the metadata can be read: not
// an image Surrogate reads.
ImageSummary describeImage(const std::filesystem::path& path);

}  // namespace surrogate::meta
