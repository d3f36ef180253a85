#include "publish/viewer_parts.h"

#include <cstdio>

namespace surrogate::publish {

namespace {
std::string degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v + 0.0);
  return buf;
}
}  // namespace

std::string discHtml(const WebDescription& d) {
  std::string range;
  if (d.lightElevationsDeg)
    range = " data-photographed=\"" + degrees(d.lightElevationsDeg->first) + "," +
            degrees(d.lightElevationsDeg->second) + "\"";
  return "<div id=\"disc\"" + range +
         "><canvas id=\"pad\" width=\"260\" height=\"260\" aria-label=\"light direction: drag the light\"></canvas></div>\n"
         "    <p id=\"readout\"></p>\n"
         "    <p id=\"light-note\" role=\"status\"></p>\n"
         "    <p id=\"photographed\"></p>\n";
}

const char* const kDiscStyle = R"CSS(
#disc { position:relative; width:260px; height:260px; }
#pad { display:block; cursor:crosshair; touch-action:none; }
.disc-label { position:absolute; transform:translate(-50%, -50%); font-size:11px; line-height:1.2; color:var(--muted);
              background:rgba(255,255,255,.85); padding:0 2px; border-radius:3px; white-space:nowrap; pointer-events:none; }
.disc-label.elevation { color:var(--accent); font-style:italic; }
#light-note { color:#a01010; margin:6px 0; }
#photographed { color:var(--muted); margin:6px 0; }
)CSS";

const char* const kDiscScript = R"JS(
  // A number as the page shows it: a negative one that rounds to zero prints as zero ("-0.000"
  // reads as if the sign meant something).
  function fixed(value, digits) {
    var text = value.toFixed(digits);
    return /^-0(\.0*)?$/.test(text) ? text.slice(1) : text;
  }

  // The disc: the centre is the camera's axis, the rim the horizon, at r (90 - elevation) / 90
  // from the centre; azimuth 0 right, 90 up. The margin holds the azimuths' labels.
  var kDiscMargin = 26;
  function discRadius(pad) { return pad.width / 2 - kDiscMargin; }

  // [lowest, highest] elevation photographed (the holder's data-photographed); null when unknown.
  function photographed(pad) {
    var v = (pad.parentNode.getAttribute("data-photographed") || "").split(",").map(Number);
    return v.length === 2 && isFinite(v[0]) && isFinite(v[1]) ? v : null;
  }

  // The labels as text over the canvas, on a background: above the rings, the band and the light.
  function labelDisc(pad) {
    var c = pad.width / 2, r = discRadius(pad), range = photographed(pad);
    function put(text, angle, radius, kind) {
      var s = document.createElement("span");
      s.className = "disc-label " + kind;
      s.textContent = text;
      s.style.left = (c + radius * Math.cos(angle * degree)).toFixed(1) + "px";
      s.style.top = (c - radius * Math.sin(angle * degree)).toFixed(1) + "px";
      pad.parentNode.appendChild(s);
    }
    [0, 90, 180, -90].forEach(function (a) { put((a < 0 ? "\u2212" : "") + Math.abs(a) + "\u00b0", a, r + 13, "azimuth"); });
    [0, 30, 60].forEach(function (e) { put("el " + e + "\u00b0", -135, r * (90 - e) / 90, "elevation"); });
    document.getElementById("photographed").textContent = range
        ? "Shaded band: the elevations the lights were photographed at, " + fixed(range[0], 1) + "\u00b0 to " +
          fixed(range[1], 1) + "\u00b0. Outside it the relighting is extrapolated."
        : "The elevations of the photographed lights are not known for this model.";
  }

  function drawDisc(pad, a) {
    var g = pad.getContext("2d"), c = pad.width / 2, r = discRadius(pad), range = photographed(pad);
    g.clearRect(0, 0, pad.width, pad.height);
    g.fillStyle = "#fafafb";
    g.beginPath(); g.arc(c, c, r, 0, 2 * Math.PI); g.fill();
    if (range) {  // the band photographed, at least 2 px wide to be seen
      var outer = r * (90 - range[0]) / 90 + 1, inner = Math.max(0, r * (90 - range[1]) / 90 - 1);
      g.fillStyle = "rgba(52, 70, 184, 0.2)";
      g.beginPath(); g.arc(c, c, outer, 0, 2 * Math.PI); g.arc(c, c, inner, 0, 2 * Math.PI, true);
      g.fill("evenodd");
    }
    g.strokeStyle = "#c9c9d0";
    [0, 30, 60].forEach(function (e) { g.beginPath(); g.arc(c, c, r * (90 - e) / 90, 0, 2 * Math.PI); g.stroke(); });
    [0, 90, 180, 270].forEach(function (az) {
      g.beginPath(); g.moveTo(c, c); g.lineTo(c + r * Math.cos(az * degree), c - r * Math.sin(az * degree)); g.stroke();
    });
    var d = r * (90 - a.elevation) / 90;
    g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
    g.beginPath(); g.arc(c + d * Math.cos(a.azimuth * degree), c - d * Math.sin(a.azimuth * degree), 7, 0, 2 * Math.PI);
    g.fill(); g.stroke();
  }

  // The readout, and in words when the light is outside the elevations photographed.
  function describeLight(pad, a, light) {
    var range = photographed(pad), e = a.elevation, note = "";
    document.getElementById("readout").textContent = "Light: azimuth " + fixed(a.azimuth, 1) + "\u00b0, elevation " +
        fixed(e, 1) + "\u00b0 (x " + fixed(light[0], 3) + ", y " + fixed(light[1], 3) + ", z " + fixed(light[2], 3) + ")";
    if (range && e < range[0] - 0.05)
      note = "below the lowest photographed light (" + fixed(range[0], 1) + "\u00b0)";
    else if (range && e > range[1] + 0.05)
      note = "above the highest photographed light (" + fixed(range[1], 1) + "\u00b0)";
    document.getElementById("light-note").textContent = note && "Light at " + fixed(e, 1) + "\u00b0 elevation: " + note +
        "; the relighting is extrapolated, so it may show what is not on the object.";
  }
)JS";

}  // namespace surrogate::publish
