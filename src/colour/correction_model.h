// Colour correction fitted to a chart: a model mapping a camera's linear RGB to linear sRGB.
//
//   matrix (3x3)          out = M rgb
//   root-polynomial (2)   out = M [r, g, b, sqrt(rg), sqrt(gb), sqrt(rb)]   (3x6; Finlayson,
//                         Mackiewicz and Hurlbert 2015: unlike a plain polynomial it scales
//                         with exposure, so a chart lit brighter or darker gives the same
//                         correction)
//
// Fitted by least squares over the patches, with the exposure fixed by the neutral patches:
// the fit is constrained so that the sum of the chosen neutral patches (white point) maps
// exactly onto the sum of their reference values (Finlayson and Drew's white-point preserving
// least squares), so neither a cast nor the exposure is left for the viewer.
//
//   ColourModel m = fitColourModel(measured, reference, ColourModelKind::Matrix, neutrals);
//   Rgb corrected = m.apply(measured[3]);
#pragma once

#include <string>
#include <vector>

#include "colour/colour_space.h"

namespace surrogate::colour {

enum class ColourModelKind { Matrix, RootPolynomial };
// "matrix", "root-polynomial"; parse throws Error(Usage) naming `origin`.
std::string modelName(ColourModelKind kind);
ColourModelKind parseModelName(const std::string& text, const std::string& origin);

struct ColourModel {
  ColourModelKind kind = ColourModelKind::Matrix;
  std::vector<double> coefficients;  // 3 rows x terms (3 or 6), row-major
  int terms() const;
  Rgb apply(const Rgb& linearRgb) const;  // negatives clamp to 0 before the roots
};

// measured[k], reference[k]: linear RGB of patch k (same length, at least terms + 1 patches);
// `neutrals`: the indices whose sum fixes the white point (must be non-empty). Patches with
// weight 0 in `use` (if given, same length) are left out of the fit (clipped, shadowed).
// Error(Input) when the patches do not determine the model (too few, or collinear).
ColourModel fitColourModel(const std::vector<Rgb>& measured, const std::vector<Rgb>& reference,
                           ColourModelKind kind, const std::vector<int>& neutrals,
                           const std::vector<bool>& use = {});

// Leave-one-out: for each patch k, the model fitted without k applied to k (what the model
// does on colours it was not fitted to). Patches that cannot be left out (a neutral that
// fixes the white point) are fitted with it kept. Same length as measured.
std::vector<Rgb> leaveOneOut(const std::vector<Rgb>& measured, const std::vector<Rgb>& reference,
                             ColourModelKind kind, const std::vector<int>& neutrals);

}  // namespace surrogate::colour
