// The report's relighting view, what it computes without the DOM: the light chosen by the
// page's address or a pointer, the light disc's geometry and marks, the texts it shows and the
// figures it records on <body> for the tests. report.js draws with them; Node's tests
// (tests/web/report_relight_view.test.js) load this file as a module.
var surrogateRelightView = (function () {
  "use strict";
  var degree = Math.PI / 180;

  // "#model=1&light=x,y,z" (or azimuth=..&elevation=..) chooses the first view: for links and
  // tests. The address's hash (with or without its "#") as name -> value.
  function parseHash(hash) {
    var out = {};
    hash.replace(/^#/, "").split("&").forEach(function (part) {
      var kv = part.split("=");
      if (kv.length === 2) out[kv[0]] = decodeURIComponent(kv[1]);
    });
    return out;
  }

  // A direction "x,y,z" as the view's angles, or null when it has no length.
  function anglesFromDirection(text) {
    var l = text.split(",").map(Number), norm = Math.hypot(l[0], l[1], l[2]);
    return norm > 0 ? { azimuth: Math.atan2(l[1], l[0]) / degree, elevation: Math.asin(l[2] / norm) / degree } : null;
  }

  // The first light: 45, 45, else the captured lights' mean direction (the canvas's
  // data-start-light, report/relight_section.h: inside the range the model was fitted on),
  // else what the page's address names.
  function startLight(startDirection, settings) {
    var light = { azimuth: 45, elevation: 45 };
    function fromDirection(text) { light = anglesFromDirection(text) || light; }
    if (startDirection) fromDirection(startDirection);
    if (settings.light) fromDirection(settings.light);
    if (settings.azimuth) light.azimuth = Number(settings.azimuth);
    if (settings.elevation) light.elevation = Number(settings.elevation);
    return light;
  }

  // The model shown first: the address's, within the models there are.
  function firstModel(settings, count) {
    return Math.min(count - 1, Math.max(0, Number(settings.model || 0)));
  }

  // The disc: the hemisphere plot's projection, radius = R (90 - elevation) / 90.
  function padGeometry(width, height) { return { cx: width / 2, cy: height / 2, r: width / 2 - 34 }; }

  // The disc's marks in its geometry p: rings at elevation 0, 30 and 60 labelled at 112.5
  // degrees round, spokes at azimuth 0, 90, 180 and -90 labelled past the rim.
  function padMarks(p) {
    var rings = [0, 30, 60].map(function (e) {
      var r = p.r * (90 - e) / 90, a = 112.5 * degree;
      return { r: r, label: "el " + e + "\u00b0", x: p.cx + r * Math.cos(a), y: p.cy - r * Math.sin(a) + 8 };
    });
    var spokes = [0, 90, 180, -90].map(function (a) {
      return { x: p.cx + (p.r + 17) * Math.cos(a * degree), y: p.cy - (p.r + 10) * Math.sin(a * degree),
               endX: p.cx + p.r * Math.cos(a * degree), endY: p.cy - p.r * Math.sin(a * degree),
               label: (a === 90 ? "" : a === -90 ? "\u2212" : "") + Math.abs(a) + "\u00b0" };
    });
    return { rings: rings, spokes: spokes };
  }

  // Where the light's spot sits on the disc.
  function lightSpot(p, light) {
    var r = p.r * (90 - light.elevation) / 90, a = light.azimuth * degree;
    return { x: p.cx + r * Math.cos(a), y: p.cy - r * Math.sin(a) };
  }

  // A pointer at (dx, dy) from the disc's centre (y down) on a disc of that radius: the
  // elevation from the distance (90 at the centre, 0 at the rim and past it), the azimuth from
  // the direction (kept at the centre, where it has none).
  function lightFromPointer(dx, dy, radius, azimuth) {
    var f = Math.min(1, Math.sqrt(dx * dx + dy * dy) / radius);
    return { azimuth: f > 0 ? Math.atan2(-dy, dx) / degree : azimuth, elevation: 90 * (1 - f) };
  }

  function readoutText(light) {
    return "Light: azimuth " + light.azimuth.toFixed(1) + "\u00b0, elevation " +
           light.elevation.toFixed(1) + "\u00b0";
  }

  function captionText(m) {
    return m.basis.toUpperCase() + " model, " + m.width + "\u00d7" + m.height +
        (m.width !== m.originalWidth ? " (a copy of the " + m.originalWidth + "\u00d7" + m.originalHeight + " model)"
                                     : " (the model's own resolution)");
  }

  // For tests and for people checking the page: the mean (0..255) of a rendering's RGBA pixels
  // d (width x height), its light ("azimuth,elevation" in degrees) and its pixels at the
  // centres of a 3x3 grid ("x,y:r,g,b;...").
  function renderingFigures(d, width, height, light) {
    var sum = 0;
    for (var i = 0; i < d.length; i += 4) sum += d[i] + d[i + 1] + d[i + 2];
    var probes = [];
    for (var j = 0; j < 3; ++j) {
      for (var k = 0; k < 3; ++k) {
        var x = Math.floor(width * (2 * k + 1) / 6), y = Math.floor(height * (2 * j + 1) / 6), t = (y * width + x) * 4;
        probes.push(x + "," + y + ":" + d[t] + "," + d[t + 1] + "," + d[t + 2]);
      }
    }
    return { mean: (sum / (3 * width * height)).toFixed(3),
             light: light.azimuth.toFixed(1) + "," + light.elevation.toFixed(1),
             probes: probes.join(";") };
  }

  // An element named for the layout test: tag, #id and its first class.
  function elementName(tagName, id, className) {
    return tagName.toLowerCase() + (id ? "#" + id : "") +
           (className && typeof className === "string" ? "." + className.split(" ")[0] : "");
  }

  return { parseHash: parseHash, anglesFromDirection: anglesFromDirection, startLight: startLight,
           firstModel: firstModel, padGeometry: padGeometry, padMarks: padMarks, lightSpot: lightSpot,
           lightFromPointer: lightFromPointer, readoutText: readoutText, captionText: captionText,
           renderingFigures: renderingFigures, elementName: elementName };
})();
if (typeof module === "object") module.exports = surrogateRelightView;
