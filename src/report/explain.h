// Private to src/report: the plain sentence beside each figure of the page (what the number
// means, what is good, what is worrying), and the thresholds it judges by, in one place.
#pragma once

#include <string>

namespace surrogate::report {

// A fit's PSNR over the photographs it was fitted on, in dB: 20 log10(255 / RMSE). Fits of
// real captures are mostly 28-38 dB; at 30 dB the mean difference is 8 of 255 levels (3 %),
// hardly visible; below 25 dB (14 levels, 6 %) the model visibly misses parts of the
// photographs (shadows, gloss, a moved object).
inline constexpr double kGoodPsnrDb = 30;
inline constexpr double kPoorPsnrDb = 25;

// A sphere's rim confidence (hrti/sphere_detection.h): the share of its rim that is a clean
// edge on the fitted circle. Detection keeps no circle below 0.5 (minConfidence); from 0.8 the
// rim is whole and the centre and radius are sure; between, part of the rim is hidden or
// blurred and the circle is worth a look on the overlay.
inline constexpr double kGoodRimConfidence = 0.8;
inline constexpr double kMinRimConfidence = 0.5;

// A sphere's moving-highlight evidence: the share of the images with a highlight that moves
// on it. Detection keeps no circle below 0.5; from 0.8 the sphere shows a highlight in nearly
// every image.
inline constexpr double kGoodEvidence = 0.8;
inline constexpr double kMinEvidence = 0.5;

// The share of the normal map's pixels whose normal came from the least-squares Lambertian
// fit because the PTM has no brightest direction there (DerivedMaps logs a warning above it):
// a few per cent are flat, dark or shadowed spots; more is a large part of the map.
inline constexpr double kNormalFallbackWarning = 0.05;

// "<span class=...>sentence</span>": what the figure says, judged by the thresholds above.
std::string explainPsnr(double psnrDb);
// The same judgement in a word for the summary, where a sentence would push the relighting
// view off the first screen: "<span class=... title="the sentence">good</span>" (fair,
// worrying); the results' fit table gives the sentence.
std::string judgePsnr(double psnrDb);
std::string explainRmse(double rmseLevels);
std::string explainRimConfidence(double confidence);
std::string explainEvidence(double evidence);
std::string explainNormalFallback(long long pixels, long long totalPixels);

}  // namespace surrogate::report
