// The parameters of the ColourCorrection step (stages/colour_chart_stage.h), as the carrier
// records them and as `surrogate run --colour-chart` gives them.
//
//   --colour-chart auto              (the default) look for a chart, correct if one is found
//   --colour-chart none              no chart: the images keep their colours
//   --colour-chart IMG_0003          the chart is in that image (found there, measured there)
//   --colour-chart IMG_0003:X1,Y1,X2,Y2,X3,Y3,X4,Y4
//                                    its grid's corners by hand: the outer corners of the dark
//                                    skin, bluish green, black and white patches, in that order
//   --chart-reference colorchecker-classic-pre-2014    the chart's edition (its values)
//   --colour-model root-polynomial   the model fitted (default: a 3x3 matrix)
//
//   ColourChartOptions o = ColourChartOptions::fromText("IMG_0003:10,20,...", "--colour-chart");
#pragma once

#include <array>
#include <string>

#include "pipeline/stage.h"

namespace surrogate::stages {

struct ColourChartOptions {
  // "auto": looked for in the frame lit most nearly along the camera's axis; a chart found is
  // measured in every frame and the capture corrected, none found leaves the colours as they
  // are. "none": no chart (a capture without one, or a chart withdrawn on purpose). Otherwise
  // an image of the capture (shot name, file name or path): the chart is found or given in
  // that image and measured there only, so it may be a target shot taken before the others.
  std::string chart = "auto";
  // Given by hand (named image only): the grid's four corners in full-frame pixels, in the
  // order of colour/chart_detection.h. Empty: found automatically.
  bool cornersGiven = false;
  std::array<std::array<double, 2>, 4> corners{};
  // The chart's reference values (colour/chart_reference.h): which edition of the chart.
  std::string reference = "colorchecker-classic-2014";
  // "matrix" (3x3, linear) or "root-polynomial" (degree 2): colour/correction_model.h.
  std::string model = "matrix";

  bool named() const { return chart != "auto" && chart != "none"; }
  std::string cornersText() const;  // "x1,y1,...,x4,y4" (empty when not given)
  pipeline::Parameters toParameters() const;
  static ColourChartOptions fromParameters(const pipeline::Parameters& p, const std::string& origin = "carrier");
  // The --colour-chart forms above, into `o` (the other fields kept).
  static void parseChartText(const std::string& text, const std::string& origin, ColourChartOptions& o);
};

}  // namespace surrogate::stages
