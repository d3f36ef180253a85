// Private to src/cli: how `surrogate info` prints each kind of file it describes, as text or
// as one JSON object, from the summaries each concern offers (carrier/summary.h,
// archive/package_summary.h, capture/capture_summary.h, meta/image_summary.h,
// meta/metadata.h's XMP sidecar summary, publish/web_layout.h).
#pragma once

#include <filesystem>

#include "carrier/carrier.h"
#include "core/json.h"

namespace surrogate::cli {

// A carrier file (info_carrier.cpp).
void printCarrier(const std::filesystem::path& path, bool json);
// A carrier's lines below the heading (title, steps, decisions, choices, runs) or its JSON
// object, written into `j` (alone, or nested in a capture's or a package's object).
void printCarrierText(const carrier::Carrier& c);
void carrierJson(JsonWriter& j, const carrier::Carrier& c);
// The colour step's record (carrier/colour_summary.h) in the carrier's lines ("  colour: ...")
// and as its "colour" key (info_colour.cpp); nothing at all for a carrier without the step.
void printColour(const carrier::Carrier& c);
void colourJson(JsonWriter& j, const carrier::Carrier& c);

// A package: a bag folder, .tar or .zip, or the bag an OCFL object or E-ARK SIP holds
// (info_folders.cpp).
void printPackage(const std::filesystem::path& path, bool json);
// A capture folder; with --json, a processed capture's carrier is nested under "carrier".
void printCapture(const std::filesystem::path& path, bool json);

// An image, an .xmp sidecar, a web layout's info.json (info_images.cpp).
void printImage(const std::filesystem::path& path, bool json);
void printXmpSidecar(const std::filesystem::path& path, bool json);
void printWebLayout(const std::filesystem::path& infoJson, bool json);

}  // namespace surrogate::cli
