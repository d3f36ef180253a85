// The published viewer's relighting weights (no page needed: tests/web/viewer_relighting.test.js):
// for a light, the weight of each plane's coefficients, which the fragment shader (shader.js)
// sums texel by texel. The light is a unit vector, x right, y up, z towards the camera.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.relighting = (function () {
  "use strict";

  // The HSH functions in the order and normalisation of an .rti (docs/hrti-math.md), the polar
  // angle clamped at pi/2 - 0.01 as surrogate render does; the first `terms` of them.
  function hshBasis(l, terms) {
    var theta = Math.min(Math.acos(Math.min(1, Math.max(-1, l[2]))), Math.PI / 2 - 0.01), phi = Math.atan2(l[1], l[0]);
    var pi = Math.PI, c = Math.cos(theta), s = Math.sqrt(c - c * c), t = 2 * c - 1;
    var cp = Math.cos(phi), sp = Math.sin(phi), c2p = Math.cos(2 * phi), s2p = Math.sin(2 * phi);
    var h = [1 / Math.sqrt(2 * pi), Math.sqrt(6 / pi) * cp * s, Math.sqrt(3 / (2 * pi)) * t,
             Math.sqrt(6 / pi) * sp * s, Math.sqrt(30 / pi) * c2p * (c * c - c),
             Math.sqrt(30 / pi) * cp * t * s, Math.sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1),
             Math.sqrt(30 / pi) * sp * t * s, Math.sqrt(30 / pi) * s2p * (c * c - c)];
    return h.slice(0, terms);
  }

  // Weights of the planes' coefficients for a light, in plane order, for the model info.json
  // describes: PTM 1, u, v, u^2, uv, v^2 with (u, v) = (lx, ly); HSH the functions above.
  function weights(info, l) {
    if (info.type === "ptm") { var u = l[0], v = l[1]; return [1, u, v, u * u, u * v, v * v]; }
    return hshBasis(l, info.nplanes / 3);
  }

  return { hshBasis, weights };
})();
if (typeof module === "object") module.exports = surrogateViewer.relighting;
