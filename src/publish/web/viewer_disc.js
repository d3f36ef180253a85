// The published viewer's light disc on its canvas (#pad, in #disc): the azimuths and elevation
// rings labelled, the elevations the lights were photographed at shaded (the holder's
// data-photographed), the light drawn where it is, and the readout, which says in words when
// the light is outside the elevations photographed. The geometry is viewer_geometry.js's.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.disc = (function (geometry) {
  "use strict";
  var fixed = geometry.fixed;

  function discRadius(pad) { return geometry.discRadius(pad.width); }

  // [lowest, highest] elevation photographed; null when unknown.
  function photographed(pad) { return geometry.photographedRange(pad.parentNode.getAttribute("data-photographed")); }

  // The labels as text over the canvas, on a background: above the rings, the band and the light.
  function labelDisc(pad) {
    var c = pad.width / 2, r = discRadius(pad), range = photographed(pad);
    function put(text, angle, radius, kind) {
      var s = document.createElement("span"), at = geometry.polar(angle, radius);
      s.className = "disc-label " + kind;
      s.textContent = text;
      s.style.left = (c + at[0]).toFixed(1) + "px";
      s.style.top = (c + at[1]).toFixed(1) + "px";
      pad.parentNode.appendChild(s);
    }
    [0, 90, 180, -90].forEach(function (a) { put((a < 0 ? "\u2212" : "") + Math.abs(a) + "\u00b0", a, r + 13, "azimuth"); });
    [0, 30, 60].forEach(function (e) { put("el " + e + "\u00b0", -135, geometry.ringRadius(e, r), "elevation"); });
    document.getElementById("photographed").textContent = range
        ? "Shaded band: the elevations the lights were photographed at, " + fixed(range[0], 1) + "\u00b0 to " +
          fixed(range[1], 1) + "\u00b0. Outside it the relighting is extrapolated."
        : "The elevations of the photographed lights are not known for this model.";
  }

  // The disc with the light of angles `a` ({ azimuth, elevation }).
  function drawDisc(pad, a) {
    var g = pad.getContext("2d"), c = pad.width / 2, r = discRadius(pad), range = photographed(pad);
    g.clearRect(0, 0, pad.width, pad.height);
    g.fillStyle = "#fafafb";
    g.beginPath(); g.arc(c, c, r, 0, 2 * Math.PI); g.fill();
    if (range) {  // the band photographed, at least 2 px wide to be seen
      var outer = geometry.ringRadius(range[0], r) + 1, inner = Math.max(0, geometry.ringRadius(range[1], r) - 1);
      g.fillStyle = "rgba(52, 70, 184, 0.2)";
      g.beginPath(); g.arc(c, c, outer, 0, 2 * Math.PI); g.arc(c, c, inner, 0, 2 * Math.PI, true);
      g.fill("evenodd");
    }
    g.strokeStyle = "#c9c9d0";
    [0, 30, 60].forEach(function (e) { g.beginPath(); g.arc(c, c, geometry.ringRadius(e, r), 0, 2 * Math.PI); g.stroke(); });
    [0, 90, 180, 270].forEach(function (az) {
      var end = geometry.polar(az, r);
      g.beginPath(); g.moveTo(c, c); g.lineTo(c + end[0], c + end[1]); g.stroke();
    });
    var at = geometry.discOffset(a, r);
    g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
    g.beginPath(); g.arc(c + at[0], c + at[1], 7, 0, 2 * Math.PI);
    g.fill(); g.stroke();
  }

  // The readout, and in words when the light is outside the elevations photographed.
  function describeLight(pad, a, light) {
    var range = photographed(pad), e = a.elevation, where = geometry.outsideRange(e, range), note = "";
    document.getElementById("readout").textContent = "Light: azimuth " + fixed(a.azimuth, 1) + "\u00b0, elevation " +
        fixed(e, 1) + "\u00b0 (x " + fixed(light[0], 3) + ", y " + fixed(light[1], 3) + ", z " + fixed(light[2], 3) + ")";
    if (where === "below")
      note = "below the lowest photographed light (" + fixed(range[0], 1) + "\u00b0)";
    else if (where === "above")
      note = "above the highest photographed light (" + fixed(range[1], 1) + "\u00b0)";
    document.getElementById("light-note").textContent = note && "Light at " + fixed(e, 1) + "\u00b0 elevation: " + note +
        "; the relighting is extrapolated, so it may show what is not on the object.";
  }

  return { discRadius, labelDisc, drawDisc, describeLight };
})(surrogateViewer.geometry);
