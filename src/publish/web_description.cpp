// webDescriptionOf(Carrier): the header's description and the range of elevations the capture's
// lights were photographed at, which the viewer's disc shows (publish/web/viewer_disc.js).
#include <algorithm>
#include <cmath>

#include "carrier/carrier.h"
#include "core/error.h"
#include "publish/web_layout.h"

namespace surrogate::publish {

namespace {

// A recorded light's elevation in degrees: its elevationDeg, or from its direction; nullopt for
// a light that is not numbers (the viewer then says nothing of it).
std::optional<double> elevationOf(const carrier::DataItem& light) {
  try {
    if (light.get("elevationDeg")) return light.number("elevationDeg");
    const double x = light.number("x"), y = light.number("y"), z = light.number("z");
    const double n = std::sqrt(x * x + y * y + z * z);
    if (!(n > 0)) return std::nullopt;
    return std::asin(std::clamp(z / n, -1.0, 1.0)) * 180 / 3.14159265358979323846;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace

WebDescription webDescriptionOf(const carrier::Carrier& carrier) {
  WebDescription d = webDescriptionOf(carrier.header);
  const carrier::Result* lights = carrier.lastResultWith("light");
  if (!lights) return d;
  for (const carrier::DataItem* l : lights->itemsOf("light")) {
    const std::optional<double> e = elevationOf(*l);
    if (!e || !std::isfinite(*e)) continue;
    if (!d.lightElevationsDeg) d.lightElevationsDeg = std::make_pair(*e, *e);
    d.lightElevationsDeg->first = std::min(d.lightElevationsDeg->first, *e);
    d.lightElevationsDeg->second = std::max(d.lightElevationsDeg->second, *e);
  }
  return d;
}

}  // namespace surrogate::publish
