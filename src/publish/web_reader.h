// A web layout read back (docs/formats.md, "The web layout"): its info.json and JPEG planes
// turned into the model Surrogate renders, a formats::PtmFile or a formats::HshFile, so that
// `surrogate render DIR` relights a published folder as `surrogate render FILE.ptm` relights
// the file it came from, up to the JPEG error of the planes.
//
// Read: "ptm" with "lrgb" (9 planes) or "rgb" (18), "hsh" with "rgb" (12, 27 or 48), and the
// learned "rbf" and "bilinear" with "mrgb" (into a fit::LearnedModel, learned_reader.h), in
// whole planes (plane_N.jpg) or Deep Zoom tiles (plane_N.dzi, publish/deep_zoom_reader.h), as
// Surrogate writes them or as another tool (relight) does; other members of info.json
// ("lights", "pixelSizeInMM", ...) are ignored. Refused, with Error(Input) naming the file:
// other bases and colour spaces (the learned ones in "mycc"), planes in another
// format or tiled only in another form (.tzi), a missing plane or tile, one that is not a JPEG
// or not of the size info.json gives, a file that is a symbolic link, and sizes beyond the
// readers' limits or the memory budget (checked before any plane is decoded).
//
// The planes' bytes go into the model unchanged when info.json's scales and biases are ones a
// .ptm or .rti can hold (the same for red, green and blue; a .ptm's bias a whole number of
// 0..255 and its LRGB colour stored as it is), which is always the case for what Surrogate
// publishes. Otherwise (relight gives each colour its own scale and bias) each term is
// re-quantised to 8 bits over the range of its decoded coefficients: an error of at most half a
// step of that range (`requantised` says so).
//
//   WebLayoutModel web = readWebLayout("web/stela");        // or "web/stela/info.json"
//   auto model = web.isLearned ? fit::makeRelightable(std::move(web.learned))   // fit/learned_relightable.h
//              : web.isPtm ? fit::makeRelightable(std::move(web.ptm)) : fit::makeRelightable(std::move(web.hsh));
#pragma once

#include <filesystem>
#include <string>

#include "fit/learned.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::publish {

struct WebLayoutModel {
  std::filesystem::path infoJson;  // the info.json read
  bool isPtm = false;              // ptm holds the model; else hsh (or learned)
  bool isLearned = false;          // learned holds the model (rbf or bilinear, "mrgb")
  formats::PtmFile ptm;
  formats::HshFile hsh;
  fit::LearnedModel learned;       // coefficients as decoded from the JPEGs
  bool requantised = false;        // the planes' bytes were re-quantised (see above)
};

// Whether `path` names a web layout rather than a .ptm or .rti: a folder, or a file whose name
// ends in ".json".
bool isWebLayoutPath(const std::filesystem::path& path);

// `path`: a web layout's folder (holding info.json) or its info.json. The layout's files are
// read as they are, never through a symbolic link (publish/layout_files.h). What reading it
// takes, from the size and planes info.json declares, with budget.besidePerTexel for what the
// caller holds beside the model, is checked against budget.bytes (--memory) before any plane
// is read: Error(Input) naming the info.json when it does not fit.
WebLayoutModel readWebLayout(const std::filesystem::path& path, const formats::ModelBudget& budget = {});

}  // namespace surrogate::publish
