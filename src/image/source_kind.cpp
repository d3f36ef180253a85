#include "image/source_kind.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/text.h"
#include "image/raw_signature.h"
#include "image/tiff_structure.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

bool startsWith(const std::array<unsigned char, 16>& head, std::size_t have, const char* sig,
                std::size_t n, std::size_t at = 0) {
  return have >= at + n && std::memcmp(head.data() + at, sig, n) == 0;
}

}  // namespace

bool isCameraRawExtension(const fs::path& path) {
  static const char* kRaw[] = {".cr2", ".crw", ".cr3", ".nef", ".nrw", ".arw", ".srf", ".sr2",
                               ".raf", ".rw2", ".orf", ".pef", ".dng", ".srw", ".3fr", ".iiq",
                               ".x3f", ".erf", ".kdc", ".dcr", ".mef", ".mos", ".mrw", ".raw",
                               ".rwl", ".fff", ".gpr"};
  const std::string ext = lowerCase(path.extension().string());
  return std::any_of(std::begin(kRaw), std::end(kRaw), [&](const char* e) { return ext == e; });
}

std::optional<SourceKind> jpegOrPngBySignature(const std::uint8_t* head, std::size_t size) {
  if (size >= 3 && std::memcmp(head, "\xFF\xD8\xFF", 3) == 0) return SourceKind::Jpeg;
  if (size >= 8 && std::memcmp(head, "\x89PNG\r\n\x1A\n", 8) == 0) return SourceKind::Png;
  return std::nullopt;
}

SourceKind classifyImageFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throwInputError(path.string(), kStep, "does not exist");
  if (!fs::is_regular_file(path, ec)) throwInputError(path.string(), kStep, "is not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path.string(), kStep, "cannot be opened for reading (check its permissions)");
  std::array<unsigned char, 16> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const std::size_t n = static_cast<std::size_t>(in.gcount());
  if (n == 0) throwInputError(path.string(), kStep, "is empty (0 bytes); copy it from the card again");

  if (const auto kind = jpegOrPngBySignature(head.data(), n)) return *kind;
  if (startsWith(head, n, "II*\0", 4) || startsWith(head, n, "MM\0*", 4)) {
    if (isCameraRawExtension(path)) return SourceKind::CameraRaw;
    // A DNG renamed .tif is still a raw mosaic: OpenCV would show its preview or fail.
    return readTiffStructure(path).isDng ? SourceKind::CameraRaw : SourceKind::Tiff;
  }
  if (rawContainerOf(head.data(), n) != RawContainer::None || isCameraRawExtension(path)) return SourceKind::CameraRaw;
  throwInputError(path.string(), kStep,
                  "unsupported file format: its content is not an image Surrogate reads (camera "
                  "raw, DNG, JPEG, TIFF or PNG)");
}

bool isDngFile(const fs::path& path) {
  try {
    return rawContainerOf(path) == RawContainer::Tiff && readTiffStructure(path).isDng;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace surrogate::image
