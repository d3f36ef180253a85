// Private to src/publish: the learned members of a web layout's info.json (type "rbf" or
// "bilinear", colour space "mrgb"; learned_layout.h, docs/formats.md "Learned bases (rbf,
// bilinear) in the web layout") read into a fit::LearnedModel, as Surrogate or relight-cli
// writes them (relight wraps the basis every 80 numbers and prints 6 significant digits).
//
//   fit::LearnedModel m = learnedModelOf(info, summary);   // before any plane is decoded
//   setLearnedCoefficients(images, &m);                     // the decoded plane_j.jpg
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "fit/learned.h"
#include "publish/web_layout.h"

namespace surrogate::publish {

// The sides a bilinear grid may have in a layout read: OpenLIME interpolates between two
// nodes, so 2 at least; beyond 256 the basis alone would be hundreds of megabytes of text.
constexpr int kMinLearnedResolution = 2, kMaxLearnedResolution = 256;

// Everything but the coefficients, checked: Error(Input) naming `infoJson` and saying what is
// read for a colour space other than "mrgb", planes not a multiple of 3, a basis of the wrong
// length or with a value outside 0..255, a range of 0, a scale, bias or light that is not a
// finite number, rbf without lights or bilinear without a resolution of 2..256.
fit::LearnedModel learnedModelOf(const std::filesystem::path& infoJson, const WebLayoutSummary& summary);

// model->coefficients from the decoded planes (RGB, rows top-first, one image per three
// coefficients).
void setLearnedCoefficients(const std::vector<std::vector<std::uint8_t>>& images, fit::LearnedModel* model);

}  // namespace surrogate::publish
