// The published viewer's light disc, its geometry (no page needed: tests/web/viewer_geometry.test.js).
// A light is a unit vector, x right, y up, z towards the camera; its azimuth is 0 right and 90
// up, its elevation 90 on the camera's axis. The disc shows it from above: the centre is the
// camera's axis, the rim the horizon, elevation e at radius * (90 - e) / 90 from the centre,
// in canvas pixels whose y grows downwards.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.geometry = (function () {
  "use strict";
  var degree = Math.PI / 180;

  // A number as the page shows it: a negative one that rounds to zero prints as zero ("-0.000"
  // reads as if the sign meant something).
  function fixed(value, digits) {
    var text = value.toFixed(digits);
    return /^-0(\.0*)?$/.test(text) ? text.slice(1) : text;
  }

  // The unit light vector of an azimuth and an elevation, in degrees.
  function fromAngles(azimuth, elevation) {
    var a = azimuth * degree, e = elevation * degree;
    return [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  }

  // A light's { azimuth, elevation } in degrees: fromAngles undone.
  function anglesOf(light) {
    return { azimuth: Math.atan2(light[1], light[0]) / degree, elevation: Math.asin(Math.max(-1, Math.min(1, light[2]))) / degree };
  }

  // The disc's radius on a canvas of `side` pixels: the margin holds the azimuths' labels.
  var kDiscMargin = 26;
  function discRadius(side) { return side / 2 - kDiscMargin; }

  // How far from the centre the disc draws an elevation (its ring), for a disc of `radius`.
  function ringRadius(elevation, radius) { return radius * (90 - elevation) / 90; }

  // The point at `distance` from the centre towards `angle` degrees (0 right, 90 up), as an
  // offset [x, y] in canvas pixels.
  function polar(angle, distance) {
    return [distance * Math.cos(angle * degree), -distance * Math.sin(angle * degree)];
  }

  // Where the disc draws a light of angles `a`: its offset from the centre.
  function discOffset(a, radius) { return polar(a.azimuth, ringRadius(a.elevation, radius)); }

  // The light a pointer at offset (dx, dy) from the centre chooses: its elevation from the
  // distance (the rim and past it, the horizon), its azimuth from the direction, except at the
  // very centre, which has none: there the light keeps `azimuth`.
  function lightAt(dx, dy, radius, azimuth) {
    var f = Math.min(1, Math.hypot(dx, dy) / radius);
    return fromAngles(f > 0 ? Math.atan2(-dy, dx) / degree : azimuth, 90 * (1 - f));
  }

  // The elevations the lights were photographed at, [lowest, highest], from the disc's
  // data-photographed ("LOWEST,HIGHEST"; null or anything else when unknown); null when unknown.
  function photographedRange(text) {
    var v = (text || "").split(",").map(Number);
    return v.length === 2 && isFinite(v[0]) && isFinite(v[1]) ? v : null;
  }

  // "below" or "above" when an elevation is outside the range photographed by more than the
  // readout's rounding (0.05 degree), else "" (also when the range is unknown).
  function outsideRange(elevation, range) {
    if (range && elevation < range[0] - 0.05) return "below";
    if (range && elevation > range[1] + 0.05) return "above";
    return "";
  }

  return { degree, fixed, fromAngles, anglesOf, discRadius, ringRadius, polar, discOffset, lightAt,
           photographedRange, outsideRange };
})();
if (typeof module === "object") module.exports = surrogateViewer.geometry;
