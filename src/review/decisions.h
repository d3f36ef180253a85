// The decisions the review page sends with "Apply", as the options of `surrogate run` that make
// the same decisions.
//
// The page sends one JSON object (every member optional):
//   {"revision": "sha256:...",                     the carrier the page shows (review.h)
//    "title": "Stela 12", "rights": "...", "license": "https://...",
//    "creators": ["Ana Silva:photographer"],        as --creator takes them
//    "meta": [{"key": "site", "value": "Abydos"}],
//    "spheres": [{"cx": 120.5, "cy": 88, "r": 40.2, "reason": "..."}],   every sphere, in order
//    "forgetSpheres": [{"sphere": 0, "reason": "..."}],
//    "highlights": [{"image": "IMG_0003", "sphere": 0, "x": 131.2, "y": 70.4, "reason": "..."}],
//    "forgetHighlights": [{"image": "IMG_0003", "sphere": 0, "reason": "..."}],
//    "chart": {"image": "IMG_0003", "corners": [x1, y1, x2, y2, x3, y3, x4, y4], "reason": "..."}
//          or {"none": true, "reason": "..."},      the colour chart: its corners (dark skin,
//                                                   bluish green, black, white) or none
//    "exclude": [{"image": "IMG_0007", "reason": "..."}],
//    "forgetExclusions": [{"image": "IMG_0007", "reason": "..."}],
//    "accept": [{"check": "lights-clustered", "reason": "..."}],
//    "forgetAccept": [{"check": "lights-clustered", "reason": "..."}]}
// and gets back, in this order:
//   --title --creator... --rights --license --meta KEY=VALUE...
//   (--sphere CX,CY,R --reason R)... (--forget-sphere N --reason R)...
//   (--highlight IMAGE:SPHERE=X,Y --reason R)... (--forget-highlight IMAGE:SPHERE --reason R)...
//   (--colour-chart IMAGE:X1,Y1,...,X4,Y4 | none  --reason R)
//   (--exclude IMAGE --reason R)... (--forget-exclusion IMAGE --reason R)...
//   (--accept CHECK --reason R)... (--forget-accept CHECK --reason R)...
// Coordinates are the frame's pixels, written to 0.1 pixel ("120.5", "88"): what a person places
// by eye, and what they would type. A sphere or highlight without a reason gets none (the run
// records that none was stated, as for the option), nor does a chart (its reason, when given,
// goes in the run's note, as that of --light-distance does); the others need one, as their
// options do.
// The values themselves are judged by the run's own parse of the options, not here.
#pragma once

#include <string>
#include <vector>

namespace surrogate::review {

// Throws Error(Usage) naming the member for a body that is not such an object (not JSON, a
// member of the wrong type, a missing field).
std::vector<std::string> argumentsFor(const std::string& applyJson);

// The revision the body names ("" when it names none).
std::string revisionOf(const std::string& applyJson);

// A coordinate as the options carry it: rounded to 0.1, without a trailing ".0".
std::string coordinateText(double value);

}  // namespace surrogate::review
