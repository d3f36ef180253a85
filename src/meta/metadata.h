// Camera metadata of an original: the EXIF summary a scholar needs to judge a capture (which
// camera and lens, exposure, when) and the whole XMP packet, where Lightroom and Photoshop
// keep the editing history of exported files.
//
//   CameraMetadata m = readMetadata("original-captures/IMG_0001.CR2");
//   if (m.model) ... *m.model ...
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace surrogate::meta {

struct CameraMetadata {
  std::optional<std::string> make, model, bodySerial, lens;
  std::optional<double> focalLengthMm;
  std::optional<double> fNumber;
  std::optional<std::string> exposureTime;  // as Exiv2 prints it, e.g. "1/125 s"
  std::optional<double> exposureSeconds;
  std::optional<long> iso;
  std::optional<std::string> dateTimeOriginal;  // "YYYY:MM:DD HH:MM:SS" as stored
  std::optional<long> orientation;              // EXIF 1..8
  std::optional<long> pixelWidth, pixelHeight;
  std::optional<double> focalPlaneXResolution, focalPlaneYResolution;
  std::optional<long> focalPlaneResolutionUnit;  // EXIF: 2 inch, 3 cm, 4 mm
  std::string xmpPacket;                         // verbatim; empty when none
};

// Reads EXIF and XMP with Exiv2. Throws Error(Input) naming the file when Exiv2 cannot read it.
CameraMetadata readMetadata(const std::filesystem::path& path);

// The XMP packet of an .xmp sidecar file, verbatim.
std::string readXmpSidecar(const std::filesystem::path& path);

std::string exiv2Version();

}  // namespace surrogate::meta
