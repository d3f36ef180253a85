#include "meta/metadata.h"

#include <exiv2/exiv2.hpp>

#include <mutex>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace surrogate::meta {

namespace {

constexpr const char* kStep = "metadata";

// Exiv2 writes warnings about odd maker notes to stderr; a user cannot act on them, and the
// values Surrogate needs are read regardless. Silence them once per process.
void initialiseExiv2() {
  static std::once_flag once;
  std::call_once(once, [] {
    Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);
#ifdef EXV_ENABLE_BMFF
    Exiv2::enableBMFF(true);
#endif
  });
}

// Keys are fixed strings of this file; a key this Exiv2 version does not know reads as absent.
const Exiv2::Exifdatum* findExif(const Exiv2::ExifData& data, const char* key) {
  Exiv2::ExifData::const_iterator it;
  try {
    it = data.findKey(Exiv2::ExifKey(key));
  } catch (const Exiv2::AnyError&) {
    return nullptr;
  }
  if (it == data.end() || it->count() == 0) return nullptr;
  return &*it;
}

const Exiv2::Xmpdatum* findXmp(const Exiv2::XmpData& data, const char* key) {
  auto it = data.findKey(Exiv2::XmpKey(key));
  if (it == data.end() || it->count() == 0) return nullptr;
  return &*it;
}

std::optional<std::string> text(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys) {
    if (const auto* d = findExif(exif, k)) {
      std::string s = d->toString();
      while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
      if (!s.empty()) return s;
    }
  }
  return std::nullopt;
}

std::optional<std::string> xmpText(const Exiv2::XmpData& xmp, const char* key) {
  if (const auto* d = findXmp(xmp, key)) {
    const std::string s = d->toString();
    if (!s.empty()) return s;
  }
  return std::nullopt;
}

std::optional<double> number(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (const auto* d = findExif(exif, k)) return d->toFloat(0);
  return std::nullopt;
}

std::optional<long> integer(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (const auto* d = findExif(exif, k)) return d->toLong(0);
  return std::nullopt;
}

std::optional<std::string> printed(const Exiv2::ExifData& exif, const char* key) {
  if (const auto* d = findExif(exif, key)) {
    std::ostringstream s;
    d->write(s, &exif);
    return s.str();
  }
  return std::nullopt;
}

}  // namespace

CameraMetadata readMetadata(const std::filesystem::path& path) {
  initialiseExiv2();
  CameraMetadata m;
  try {
    Exiv2::Image::AutoPtr image = Exiv2::ImageFactory::open(path.string());
    if (!image.get()) throwInputError(path.string(), kStep, "Exiv2 cannot open the file");
    image->readMetadata();
    const Exiv2::ExifData& exif = image->exifData();
    const Exiv2::XmpData& xmp = image->xmpData();
    m.make = text(exif, {"Exif.Image.Make"});
    m.model = text(exif, {"Exif.Image.Model"});
    m.bodySerial = text(exif, {"Exif.Photo.BodySerialNumber", "Exif.Image.CameraSerialNumber",
                               "Exif.Canon.SerialNumber", "Exif.Nikon3.SerialNumber"});
    if (!m.bodySerial) m.bodySerial = xmpText(xmp, "Xmp.aux.SerialNumber");
    m.lens = text(exif, {"Exif.Photo.LensModel"});
    if (!m.lens) m.lens = xmpText(xmp, "Xmp.aux.Lens");
    m.focalLengthMm = number(exif, {"Exif.Photo.FocalLength", "Exif.Image.FocalLength"});
    m.fNumber = number(exif, {"Exif.Photo.FNumber", "Exif.Image.FNumber"});
    m.exposureTime = printed(exif, "Exif.Photo.ExposureTime");
    if (!m.exposureTime) m.exposureTime = printed(exif, "Exif.Image.ExposureTime");
    m.exposureSeconds = number(exif, {"Exif.Photo.ExposureTime", "Exif.Image.ExposureTime"});
    m.iso = integer(exif, {"Exif.Photo.ISOSpeedRatings", "Exif.Image.ISOSpeedRatings"});
  if (!m.iso) {
    if (const auto v = xmpText(xmp, "Xmp.exifEX.PhotographicSensitivity")) m.iso = std::atol(v->c_str());
  }
    m.dateTimeOriginal = text(exif, {"Exif.Photo.DateTimeOriginal", "Exif.Image.DateTimeOriginal",
                                     "Exif.Image.DateTime"});
    m.orientation = integer(exif, {"Exif.Image.Orientation"});
    m.pixelWidth = integer(exif, {"Exif.Photo.PixelXDimension"});
    m.pixelHeight = integer(exif, {"Exif.Photo.PixelYDimension"});
    if (!m.pixelWidth && image->pixelWidth() > 0) m.pixelWidth = image->pixelWidth();
    if (!m.pixelHeight && image->pixelHeight() > 0) m.pixelHeight = image->pixelHeight();
    m.focalPlaneXResolution = number(exif, {"Exif.Photo.FocalPlaneXResolution"});
    m.focalPlaneYResolution = number(exif, {"Exif.Photo.FocalPlaneYResolution"});
    m.focalPlaneResolutionUnit = integer(exif, {"Exif.Photo.FocalPlaneResolutionUnit"});
    m.xmpPacket = image->xmpPacket();
  } catch (const Exiv2::AnyError& e) {
    throwInputError(path.string(), kStep, std::string("Exiv2 cannot read its metadata: ") + e.what());
  } catch (const std::bad_alloc&) {
    throwInputError(path.string(), kStep, "Exiv2 ran out of memory reading it (damaged metadata)");
  }
  return m;
}

std::string readXmpSidecar(const std::filesystem::path& path) {
  return readFile(path, kStep);
}

std::string exiv2Version() { return Exiv2::versionString(); }

}  // namespace surrogate::meta
