#include "meta/metadata.h"

#include <exiv2/exiv2.hpp>

#include <cstdlib>
#include <initializer_list>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "meta/exiv2_setup.h"
#include "meta/xmp_packet_scan.h"

namespace surrogate::meta {

namespace {

constexpr const char* kStep = "metadata";

using ExifFinder = Exiv2::ExifData::const_iterator (*)(const Exiv2::ExifData&);

// A key this Exiv2 version does not know reads as absent, as does an empty value.
const Exiv2::Exifdatum* findExif(const Exiv2::ExifData& data, const char* key) {
  Exiv2::ExifData::const_iterator it;
  try {
    it = data.findKey(Exiv2::ExifKey(key));
  } catch (const Exiv2::AnyError&) {
    return nullptr;
  }
  return it == data.end() || it->count() == 0 ? nullptr : &*it;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  return s;
}

// The value as exiv2 prints it (`exiv2 -pa`): maker-note codes decoded ("Canon RF 70-200mm"),
// rationals as photographers write them ("1/125 s").
std::string printed(const Exiv2::Exifdatum& d, const Exiv2::ExifData& exif) {
  std::ostringstream s;
  d.write(s, &exif);
  return trimmed(s.str());
}

// Exiv2 prints maker-note values it cannot decode as "n/a", "Unknown" or "(code)".
bool meaningful(const std::string& s) {
  return !s.empty() && s != "n/a" && s != "Unknown" && s.front() != '(';
}

std::optional<std::string> exifText(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (const auto* d = findExif(exif, k))
      if (std::string s = trimmed(d->toString()); !s.empty()) return s;
  return std::nullopt;
}

std::optional<std::string> xmpText(const Exiv2::XmpData& xmp, std::initializer_list<const char*> keys) {
  for (const char* k : keys) {
    const auto it = xmp.findKey(Exiv2::XmpKey(k));
    if (it != xmp.end() && it->count() > 0)
      if (std::string s = trimmed(it->toString()); !s.empty()) return s;
  }
  return std::nullopt;
}

// Exiv2's "easy access" search across maker notes, as printed.
std::optional<std::string> makerNote(const Exiv2::ExifData& exif, ExifFinder find) {
  const auto it = find(exif);
  if (it == exif.end() || it->count() == 0) return std::nullopt;
  std::string s = printed(*it, exif);
  return meaningful(s) ? std::optional<std::string>(s) : std::nullopt;
}

// The n-th value as a double: a rational exactly (4.2 mm stored as 42/10 is 4.2, not the
// nearest float, 4.199999809), other types as Exiv2 converts them.
double numberAt(const Exiv2::Exifdatum& d, long n) {
  if (d.typeId() == Exiv2::unsignedRational || d.typeId() == Exiv2::signedRational) {
    const Exiv2::Rational r = d.toRational(n);
    return r.second == 0 ? 0.0 : static_cast<double>(r.first) / r.second;
  }
  return static_cast<double>(d.toFloat(n));
}

std::optional<double> exifNumber(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (const auto* d = findExif(exif, k)) return numberAt(*d, 0);
  return std::nullopt;
}

std::optional<long> exifInteger(const Exiv2::ExifData& exif, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    if (const auto* d = findExif(exif, k)) return d->toLong(0);
  return std::nullopt;
}

// The leading number of a printed value ("7.1 mm" -> 7.1, "200" -> 200); maker notes store
// encoded values whose printed form is the only reliable one.
std::optional<double> leadingNumber(const std::optional<std::string>& s) {
  if (!s) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(s->c_str(), &end);
  if (end == s->c_str() || !(v > 0)) return std::nullopt;
  return v;
}

// The lens's focal range as the file records it. LensSpecification and Nikon's Lens hold four
// rationals (shortest and longest focal length, then apertures; 0/0 when unknown); CanonCs.Lens
// holds the longest and shortest focal length and the units per mm.
void readLensRange(const Exiv2::ExifData& exif, CameraMetadata& m) {
  for (const char* key : {"Exif.Photo.LensSpecification", "Exif.Nikon3.Lens"}) {
    const auto* d = findExif(exif, key);
    if (!d || d->count() < 2) continue;
    const double lo = numberAt(*d, 0), hi = numberAt(*d, 1);
    if (lo > 0 && hi >= lo) {
      m.lensMinFocalMm = lo;
      m.lensMaxFocalMm = hi;
      return;
    }
  }
  if (const auto* d = findExif(exif, "Exif.CanonCs.Lens"); d && d->count() >= 3) {
    const double units = static_cast<double>(d->toLong(2));
    const double hi = static_cast<double>(d->toLong(0)), lo = static_cast<double>(d->toLong(1));
    if (units > 0 && lo > 0 && hi >= lo) {
      m.lensMinFocalMm = lo / units;
      m.lensMaxFocalMm = hi / units;
    }
  }
}

void readExif(const Exiv2::ExifData& exif, const Exiv2::XmpData& xmp, CameraMetadata& m) {
  m.make = exifText(exif, {"Exif.Image.Make"});
  if (!m.make) m.make = xmpText(xmp, {"Xmp.tiff.Make"});
  m.model = exifText(exif, {"Exif.Image.Model"});
  if (!m.model) m.model = xmpText(xmp, {"Xmp.tiff.Model"});

  m.bodySerial = exifText(exif, {"Exif.Photo.BodySerialNumber", "Exif.Image.CameraSerialNumber"});
  if (!m.bodySerial) m.bodySerial = xmpText(xmp, {"Xmp.exifEX.BodySerialNumber", "Xmp.aux.SerialNumber"});
  if (!m.bodySerial) m.bodySerial = makerNote(exif, Exiv2::serialNumber);

  m.lens = exifText(exif, {"Exif.Photo.LensModel"});
  if (!m.lens) m.lens = xmpText(xmp, {"Xmp.exifEX.LensModel", "Xmp.aux.Lens"});
  if (!m.lens) {
    m.lens = makerNote(exif, Exiv2::lensName);
    m.lensFromMakerNote = m.lens.has_value();
  }
  readLensRange(exif, m);

  m.focalLengthMm = exifNumber(exif, {"Exif.Photo.FocalLength", "Exif.Image.FocalLength"});
  if (!m.focalLengthMm) m.focalLengthMm = leadingNumber(makerNote(exif, Exiv2::focalLength));
  m.fNumber = exifNumber(exif, {"Exif.Photo.FNumber", "Exif.Image.FNumber"});

  for (const char* key : {"Exif.Photo.ExposureTime", "Exif.Image.ExposureTime"}) {
    if (const auto* d = findExif(exif, key)) {
      m.exposureTime = printed(*d, exif);
      m.exposureSeconds = numberAt(*d, 0);
      break;
    }
  }

  m.iso = exifInteger(exif, {"Exif.Photo.ISOSpeedRatings", "Exif.Image.ISOSpeedRatings"});
  if (!m.iso)
    if (const auto v = leadingNumber(xmpText(xmp, {"Xmp.exifEX.PhotographicSensitivity", "Xmp.exif.ISOSpeedRatings"})))
      m.iso = static_cast<long>(*v);
  if (!m.iso)
    if (const auto v = leadingNumber(makerNote(exif, Exiv2::isoSpeed))) m.iso = static_cast<long>(*v);

  // Exif.Image.DateTime is when the file was last changed, not when the photograph was taken.
  m.dateTimeOriginal = exifText(exif, {"Exif.Photo.DateTimeOriginal", "Exif.Image.DateTimeOriginal"});
  m.offsetTimeOriginal = exifText(exif, {"Exif.Photo.OffsetTimeOriginal"});
  m.orientation = exifInteger(exif, {"Exif.Image.Orientation"});
  if (m.orientation && (*m.orientation < 1 || *m.orientation > 8)) m.orientation.reset();

  m.pixelWidth = exifInteger(exif, {"Exif.Photo.PixelXDimension"});
  m.pixelHeight = exifInteger(exif, {"Exif.Photo.PixelYDimension"});
  m.focalPlaneXResolution = exifNumber(exif, {"Exif.Photo.FocalPlaneXResolution"});
  m.focalPlaneYResolution = exifNumber(exif, {"Exif.Photo.FocalPlaneYResolution"});
  m.focalPlaneResolutionUnit = exifInteger(exif, {"Exif.Photo.FocalPlaneResolutionUnit"});
}

// Text is data: values that are not valid UTF-8 or hold control characters (a camera's
// Latin-1 make, a stray byte) are kept escaped, with their raw bytes, so that every record and
// terminal can hold them (CameraMetadata::rawText).
void escapeText(CameraMetadata& m) {
  const std::pair<const char*, std::optional<std::string>*> fields[] = {
      {"make", &m.make}, {"model", &m.model}, {"serial", &m.bodySerial}, {"lens", &m.lens},
      {"exposureTime", &m.exposureTime}, {"dateTimeOriginal", &m.dateTimeOriginal},
      {"offsetTimeOriginal", &m.offsetTimeOriginal}};
  for (const auto& [name, value] : fields) {
    if (!*value || !needsEscaping(**value)) continue;
    m.rawText.emplace_back(name, hexBytes(**value));
    **value = escapedText(**value);
  }
  if (needsEscaping(m.xmpPacket, true)) {
    m.xmpPacket = escapedText(m.xmpPacket, true);
    m.xmpEscaped = true;
  }
}

// The stored bytes of the packet Exiv2 parsed but did not keep (BMFF): the scanned packet
// that parses to as many properties.
std::string storedPacket(const std::filesystem::path& path, long properties) {
  for (const std::string& packet : scanXmpPackets(readFile(path, kStep))) {
    Exiv2::XmpData parsed;
    if (Exiv2::XmpParser::decode(parsed, packet) == 0 && parsed.count() == properties) return packet;
  }
  return {};
}

}  // namespace

CameraMetadata readMetadata(const std::filesystem::path& path) {
  ensureExiv2Ready();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throwInputError(path.string(), kStep, "does not exist or is not a regular file");
  CameraMetadata m;
  const std::lock_guard<std::mutex> lock(exiv2Mutex());
  try {
    Exiv2::Image::AutoPtr image = Exiv2::ImageFactory::open(path.string());
    if (!image.get()) throwInputError(path.string(), kStep, "Exiv2 cannot open the file");
    image->readMetadata();
    // Without this, xmpPacket() re-serialises the parsed XMP: a different packet from the
    // stored one, whose namespace prefixes even depend on what the process parsed before.
    // (readMetadata clears the flag, so it is set afterwards.)
    image->writeXmpFromPacket(true);
    readExif(image->exifData(), image->xmpData(), m);
    if (!m.pixelWidth && image->pixelWidth() > 0) m.pixelWidth = image->pixelWidth();
    if (!m.pixelHeight && image->pixelHeight() > 0) m.pixelHeight = image->pixelHeight();
    m.xmpPacket = image->xmpPacket();
    if (m.xmpPacket.empty() && image->xmpData().count() > 0)
      m.xmpPacket = storedPacket(path, image->xmpData().count());
    escapeText(m);
  } catch (const Exiv2::AnyError& e) {
    throwInputError(path.string(), kStep, std::string("Exiv2 cannot read its metadata: ") + e.what());
  } catch (const std::bad_alloc&) {
    throwInputError(path.string(), kStep, "Exiv2 ran out of memory reading it (the metadata is damaged)");
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    // Exiv2 0.27 lets some standard exceptions (std::out_of_range, std::overflow_error) escape
    // from damaged files.
    throwInputError(path.string(), kStep, std::string("the metadata is damaged (Exiv2: ") + e.what() + ")");
  }
  return m;
}

std::string exiv2Version() { return Exiv2::versionString(); }

}  // namespace surrogate::meta
