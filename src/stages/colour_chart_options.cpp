#include "stages/colour_chart_options.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "colour/chart_reference.h"
#include "colour/correction_model.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::stages {

namespace {

// Eight finite numbers separated by commas, as corners; Error(Usage) naming `origin`.
std::array<std::array<double, 2>, 4> parseCorners(const std::string& text, const std::string& origin) {
  std::array<std::array<double, 2>, 4> out{};
  std::stringstream in(text);
  std::string item;
  int n = 0;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v) || n >= 8) {
      n = -1;
      break;
    }
    out[n / 2][n % 2] = v;
    ++n;
  }
  if (n != 8)
    throw Error(ErrorKind::Usage, origin + " " + text, "colour chart",
                "needs the chart's four corners as eight numbers X1,Y1,X2,Y2,X3,Y3,X4,Y4 (pixels of the "
                "full frame): the outer corners of the dark skin, bluish green, black and white patches, "
                "in that order");
  return out;
}

}  // namespace

std::string ColourChartOptions::cornersText() const {
  if (!cornersGiven) return "";
  std::string s;
  for (const auto& c : corners) s += (s.empty() ? "" : ",") + formatNumber(c[0]) + "," + formatNumber(c[1]);
  return s;
}

pipeline::Parameters ColourChartOptions::toParameters() const {
  // corners is always written (empty: found automatically), so that a later --colour-chart
  // without corners replaces corners given earlier.
  pipeline::Parameters p{{"chart", chart}, {"corners", cornersText()}};
  p.push_back({"reference", reference});
  p.push_back({"model", model});
  return p;
}

void ColourChartOptions::parseChartText(const std::string& text, const std::string& origin, ColourChartOptions& o) {
  const std::size_t colon = text.rfind(':');
  // A colon followed by numbers gives corners; an image name may hold colons of its own only
  // when no corners follow.
  if (colon != std::string::npos && colon + 1 < text.size() &&
      text.find_first_not_of("0123456789.,-+eE ", colon + 1) == std::string::npos) {
    o.chart = text.substr(0, colon);
    o.corners = parseCorners(text.substr(colon + 1), origin);
    o.cornersGiven = true;
  } else {
    o.chart = text;
    o.cornersGiven = false;
  }
  if (o.chart.empty())
    throw Error(ErrorKind::Usage, origin + " " + text, "colour chart",
                "give auto, none, or the image the chart is in (e.g. IMG_0003), optionally with its corners "
                "IMG_0003:X1,Y1,X2,Y2,X3,Y3,X4,Y4");
  if (o.cornersGiven && !o.named())
    throw Error(ErrorKind::Usage, origin + " " + text, "colour chart",
                "corners belong to one image: name it, e.g. IMG_0003:X1,Y1,...,X4,Y4");
}

ColourChartOptions ColourChartOptions::fromParameters(const pipeline::Parameters& p, const std::string& origin) {
  ColourChartOptions o;
  for (const auto& [name, value] : p) {
    if (name == "chart") {
      parseChartText(value, origin == "carrier" ? "chart=" : origin, o);
    } else if (name == "corners") {
      if (value.empty()) {
        o.cornersGiven = false;
        continue;
      }
      o.corners = parseCorners(value, origin == "carrier" ? "corners=" : origin);
      o.cornersGiven = true;
    } else if (name == "reference") {
      colour::chartReference(value);  // Error(Usage) listing the known ones
      o.reference = value;
    } else if (name == "model") {
      o.model = colour::modelName(colour::parseModelName(value, origin == "carrier" ? "model=" : origin));
    } else {
      throw Error(ErrorKind::Input, name + "=" + value, "colour chart",
                  "is not a parameter of ColourCorrection (chart, corners, reference, model)");
    }
  }
  if (o.cornersGiven && !o.named())
    throw Error(ErrorKind::Input, "corners=" + o.cornersText(), "colour chart",
                "corners are given for one named image, but chart=" + o.chart);
  return o;
}

}  // namespace surrogate::stages
