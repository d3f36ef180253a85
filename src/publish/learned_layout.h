// The web layout of a learned model (relight's RBF and bilinear bases, fit/learned.h): what
// OpenLIME's RTI layer and relight's viewer read for "type": "rbf" or "bilinear" with the
// colour space "mrgb" (docs/formats.md, "Learned bases (rbf, bilinear) in the web layout").
//
//   info.json   width, height, format "jpg", type, resolution (bilinear), colorspace "mrgb",
//               sigma (rbf), lights (3 decimals), nplanes, quality, basis ((P + 1) x nodes x 3
//               bytes as numbers), materials [{range, scale, bias}] (P numbers each)
//   plane_j.jpg coefficients 3j, 3j + 1, 3j + 2 of every texel as red, green and blue
//
// The coefficient bytes and the basis bytes are the model's own, never re-quantised: only the
// planes' JPEG compression changes them. range, scale and bias are printed with 9 significant
// digits, so each reads back as the same float. The folder is written as publish() writes one
// (a hidden partial folder renamed into place when complete, web_layout.h).
//
//   PublishOptions options;  options.quality = 95;
//   options.planeQualities = {98, 95, 90};          // one per JPEG, or empty for `quality`
//   WebLayoutFiles files = webLayoutOf(model, options);
//   writeWebLayoutFolder(files, "web/stela-bln");
#pragma once

#include <filesystem>
#include <string>

#include "fit/learned.h"
#include "publish/web_layout.h"

namespace surrogate::publish {

// The qualities the planes are written with: options.planeQualities when given (one per JPEG,
// nplanes / 3 of them), else options.quality to options.lastQuality in equal rounded steps
// (90 to 40 over 15 JPEGs: 90, 86, 83, ... 44, 40), else options.quality for every plane. Throws Error(Usage) naming
// "--quality" for a count that differs or a quality outside 1..100.
std::vector<int> planeQualitiesOf(const PublishOptions& options, int jpegs);

// info.json of `model` (its "quality" is `quality`, the highest the planes use). Throws
// Error(Input) naming "the learned model" when its parts disagree in size, a range is 0 or a
// number is not finite.
std::string learnedInfoJson(const fit::LearnedModel& model, int quality);

// info.json and the planes (whole, or Deep Zoom tiles as options.tiles says); no viewer pages:
// Surrogate's own viewer (viewer.h) draws PTM and HSH only.
WebLayoutFiles webLayoutOf(const fit::LearnedModel& model, const PublishOptions& options);

}  // namespace surrogate::publish
