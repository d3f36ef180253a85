// Camera values as photographers write them, for display (`surrogate info`); the carrier
// records the numbers themselves (core/text.h, formatNumber).
//
//   apertureText(5.65685)    "f/5.6"   (Av 5: the marked third-stop value)
//   apertureText(2.92184)    "f/2.9"   (not a third stop: one decimal below 10, whole above)
//   exposureText(0.008)      "1/125 s"
//   focalLengthText(31)      "31 mm"
//   cameraText("Canon", "Canon EOS D30")   "Canon EOS D30"
//   dateTimeText("2018:01:01 13:03:32", "+02:00")   "2018-01-01T13:03:32+02:00"
#pragma once

#include <optional>
#include <string>

#include "meta/metadata.h"

namespace surrogate::meta {

std::string apertureText(double fNumber);
std::string exposureText(double seconds);
std::string focalLengthText(double mm);
// "31 mm, f/5.6, 1/125 s, ISO 100": the exposure as a photographer notes it, the known parts
// only (the exposure time as the file writes it when it gives no number); empty when none is.
std::string exposureSettingsText(const CameraMetadata& m);
// "16-35 mm", or "50 mm" when both ends are equal.
std::string focalRangeText(double minMm, double maxMm);
// The model alone when it already names the maker ("Canon EOS D30", "NIKON D70" for make
// "NIKON CORPORATION"), else both ("Sony D5803"); empty when neither is known.
std::string cameraText(const CameraMetadata& m);
// EXIF's "YYYY:MM:DD HH:MM:SS" as ISO 8601, with the zone when `offset` is one ("+02:00");
// text in another form is returned as it is.
std::string dateTimeText(const std::string& exifDateTime, const std::optional<std::string>& offset);

// What EXIF orientation 1..8 asks of a viewer: "as stored", "rotate 90° clockwise", ...
std::string orientationText(long orientation);
// "pixels per inch" (EXIF resolution unit 2), "pixels per cm" (3), "pixels per mm" (4).
std::string resolutionUnitText(long unit);

// The lens as a photographer should read it; empty when nothing is known.
//   - the lens the file names (LensModel, XMP): that name;
//   - a maker-note lens code whose reading (a guess among lenses sharing the code) does not
//     match the focal range the camera recorded: the range, with the guess labelled
//     ("16-35 mm (recorded focal range; the lens code reads as Canon EF 70-200mm ..., which
//     does not match it)");
//   - no name, a recorded range: the range ("7.1-21.3 mm").
std::string lensText(const CameraMetadata& m);
// False when the lens is a maker-note reading that contradicts the recorded focal range.
bool lensAgreesWithRange(const CameraMetadata& m);

}  // namespace surrogate::meta
