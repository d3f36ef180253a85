// Camera metadata of an original: the EXIF summary a scholar needs to judge a capture (which
// camera and lens, how exposed, when) and the whole XMP packet, where Lightroom and Photoshop
// keep the editing history of exported files.
//
// Each field comes from the standard EXIF tag first, then the XMP equivalent, then the camera
// maker's private notes (as Exiv2 decodes them); a field no source holds stays empty:
//
//   bodySerial  Exif.Photo.BodySerialNumber, Exif.Image.CameraSerialNumber, maker notes
//               (Exif.Canon.SerialNumber, Exif.Nikon3.SerialNO, ...), Xmp.aux.SerialNumber
//   lens        Exif.Photo.LensModel, Xmp.aux.Lens, maker notes (Exif.CanonCs.LensType, ...)
//   lens range  Exif.Photo.LensSpecification, Exif.Nikon3.Lens, Exif.CanonCs.Lens (the focal
//               range the camera wrote, in mm; a maker-note LensType is a code that Exiv2
//               reads through a table, guessing among lenses that share it)
//   iso         Exif.Photo.ISOSpeedRatings (PhotographicSensitivity), Xmp.exifEX, maker notes
//
//   CameraMetadata m = readMetadata("original-captures/IMG_0001.CR2");
//   if (m.model) std::cout << *m.model;          // "Canon EOS R6"
//
// Exiv2 0.27 reads every format here, CR3 included (BMFF support is switched on). Its warnings
// are silenced: the user cannot act on an odd maker-note entry, and the values needed are read
// regardless. Safe to call from several threads at once.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::meta {

struct CameraMetadata {
  std::optional<std::string> make, model, bodySerial, lens;
  // True when `lens` is Exiv2's reading of a maker-note lens code (a table lookup that guesses
  // among lenses sharing a code), false when the file names the lens itself (LensModel, XMP).
  bool lensFromMakerNote = false;
  std::optional<double> lensMinFocalMm, lensMaxFocalMm;  // the recorded focal range
  std::optional<double> focalLengthMm;          // actual focal length, not 35 mm equivalent
  std::optional<double> fNumber;
  std::optional<std::string> exposureTime;      // as Exiv2 prints it, e.g. "1/125 s"
  std::optional<double> exposureSeconds;
  std::optional<long> iso;
  std::optional<std::string> dateTimeOriginal;  // "YYYY:MM:DD HH:MM:SS" as stored
  std::optional<std::string> offsetTimeOriginal;  // its zone, "+02:00" (Exif.Photo.OffsetTimeOriginal)
  std::optional<long> orientation;              // EXIF 1..8 (1 = as stored, 6 = rotate 90 CW)
  std::optional<long> pixelWidth, pixelHeight;  // EXIF pixel dimensions, else the file's
  std::optional<double> focalPlaneXResolution, focalPlaneYResolution;  // sensor pixels per unit
  std::optional<long> focalPlaneResolutionUnit;  // EXIF: 2 inch, 3 cm, 4 mm
  std::string xmpPacket;                         // verbatim as stored; empty when none
  // Text is data (core/text.h, escapedText): a text field above whose bytes were not valid
  // UTF-8 or held a control character holds them escaped, and its name and raw bytes (hex) are
  // here; a packet not clean likewise holds escapedText (line breaks kept) and xmpEscaped.
  std::vector<std::pair<std::string, std::string>> rawText;  // field ("make"), hexBytes
  bool xmpEscaped = false;
};

// Reads EXIF and XMP with Exiv2. Throws Error(Input) naming the file when it is missing or
// Exiv2 cannot read it (unknown format, damaged metadata).
CameraMetadata readMetadata(const std::filesystem::path& path);

// The XMP packet of an .xmp sidecar file, verbatim (escaped as core/text.h's escapedText, line
// breaks kept, when it is not valid UTF-8 or holds control characters). Throws Error(Input) naming the file when it
// cannot be read or is not a well-formed XMP packet.
// *escaped (when given) says whether it was.
std::string readXmpSidecar(const std::filesystem::path& path, bool* escaped = nullptr);

// What an .xmp sidecar records about its image: the software that wrote it, the rating, the
// develop settings (Camera Raw / Lightroom, crs:) and the editing history (xmpMM:History).
struct XmpHistoryEvent {
  std::string action, when, software, changed;  // stEvt:action, when, softwareAgent, changed
};
struct XmpSidecarSummary {
  std::optional<std::string> creatorTool;   // Xmp.xmp.CreatorTool
  std::optional<std::string> rating;        // Xmp.xmp.Rating, "0".."5" (-1: rejected)
  std::optional<std::string> modified;      // Xmp.xmp.MetadataDate, else ModifyDate
  std::optional<std::string> creator, rights;  // dc:creator, dc:rights
  int developSettings = 0;                  // how many crs: properties
  std::optional<std::string> processVersion;  // crs:ProcessVersion
  std::vector<XmpHistoryEvent> history;     // in recorded order
  std::size_t bytes = 0;
};

// Reads and summarizes an .xmp sidecar. Throws Error(Input) as readXmpSidecar does.
XmpSidecarSummary summarizeXmpSidecar(const std::filesystem::path& path);

std::string exiv2Version();  // "0.27.6"

}  // namespace surrogate::meta
