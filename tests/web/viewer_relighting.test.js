// The published viewer's relighting weights (src/publish/web/viewer_relighting.js) against closed
// forms written here: PTM's six terms, and the HSH functions of orders 2 and 3 built as
// docs/hrti-math.md constructs them (Legendre functions of cos(theta') = 2 cos(theta) - 1,
// RTIViewer's signs), and their orthonormality over the hemisphere.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const relighting = require(path.join(__dirname, "../../src/publish/web/viewer_relighting.js"));

const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual}, expected ${expected}`);
const unit = (x, y, z) => { const n = Math.hypot(x, y, z); return [x / n, y / n, z / n]; };
const directions = [[0, 0, 1], unit(1, 0, 1), unit(0, 1, 2), unit(-1, -2, 1.5), unit(3, -1, 0.4), unit(-0.2, 0.1, 1), unit(1, 1, 0.05)];

test("PTM weights are 1, u, v, u^2, uv, v^2 with (u, v) the light's x and y", () => {
  for (const type of [{ type: "ptm", colorspace: "lrgb", nplanes: 9 }, { type: "ptm", colorspace: "rgb", nplanes: 18 }]) {
    for (const l of directions) {
      const w = relighting.weights(type, l);
      assert.strictEqual(w.length, 6);
      const [u, v] = l;
      [1, u, v, u * u, u * v, v * v].forEach((e, i) => near(w[i], e, 1e-15, `${type.colorspace} term ${i} at ${l}`));
    }
  }
  const horizon = relighting.weights({ type: "ptm", nplanes: 9 }, [0.6, -0.8, 0]);
  [1, 0.6, -0.8, 0.36, -0.48, 0.64].forEach((e, i) => near(horizon[i], e, 1e-15, `term ${i} at (0.6, -0.8, 0)`));
});

// H_l^m of docs/hrti-math.md: K_l^m P_l^|m|(cos theta'), times sqrt(2) cos(|m| phi) for m < 0 and
// sqrt(2) sin(m phi) for m > 0, P without the Condon-Shortley sign; RTIViewer reverses k = 4 and 8.
function factorial(n) { return n <= 1 ? 1 : n * factorial(n - 1); }
function legendre(l, m, x) {  // associated Legendre P_l^m(x), m >= 0, l <= 2, no (-1)^m
  const s = Math.sqrt(1 - x * x);
  const table = { "0,0": 1, "1,0": x, "1,1": s, "2,0": (3 * x * x - 1) / 2, "2,1": 3 * x * s, "2,2": 3 * (1 - x * x) };
  return table[`${l},${m}`];
}
function hsh(k, l3) {
  const theta = Math.min(Math.acos(l3[2]), Math.PI / 2 - 0.01), phi = Math.atan2(l3[1], l3[0]);
  const l = Math.floor(Math.sqrt(k)), m = k - l * (l + 1), a = Math.abs(m);
  const K = Math.sqrt((2 * l + 1) * factorial(l - a) / (2 * Math.PI * factorial(l + a)));
  const P = legendre(l, a, 2 * Math.cos(theta) - 1);
  const angular = m < 0 ? Math.SQRT2 * Math.cos(a * phi) : m > 0 ? Math.SQRT2 * Math.sin(m * phi) : 1;
  return (k === 4 || k === 8 ? -1 : 1) * K * angular * P;
}

test("HSH order 2 and 3 weights are the hemispherical harmonics of docs/hrti-math.md", () => {
  for (const [nplanes, terms] of [[12, 4], [27, 9]]) {
    for (const l of directions) {
      const w = relighting.weights({ type: "hsh", nplanes }, l);
      assert.strictEqual(w.length, terms, `${terms} terms for ${nplanes} planes`);
      w.forEach((value, k) => near(value, hsh(k, l), 1e-12, `H${k} at ${l}`));
    }
  }
});

test("HSH values at given directions: overhead, and on the horizon where theta is clamped", () => {
  const pi = Math.PI, up = relighting.hshBasis([0, 0, 1], 9);
  const expected = [1 / Math.sqrt(2 * pi), 0, Math.sqrt(3 / (2 * pi)), 0, 0, 0, Math.sqrt(5 / (2 * pi)), 0, 0];
  expected.forEach((e, k) => near(up[k], e, 1e-15, `H${k} overhead`));
  // On the horizon towards +y: theta = pi/2 - 0.01, so c = sin(0.01), phi = pi/2.
  const c = Math.sin(0.01), s = Math.sqrt(c - c * c), t = 2 * c - 1, h = relighting.hshBasis([0, 1, 0], 9);
  near(h[1], 0, 1e-15, "H1 (cos phi) at phi = 90");
  near(h[3], Math.sqrt(6 / pi) * s, 1e-12, "H3 at the horizon");
  near(h[2], Math.sqrt(3 / (2 * pi)) * t, 1e-12, "H2 at the horizon");
  near(h[4], -Math.sqrt(30 / pi) * (c * c - c), 1e-12, "H4 (cos 2 phi = -1) at the horizon");
  near(h[7], Math.sqrt(30 / pi) * t * s, 1e-12, "H7 at the horizon");
});

test("HSH order 3 is orthonormal over the hemisphere", () => {
  // Midpoint rule in theta and phi; the clamp at pi/2 - 0.01 moves the values of a band 0.01
  // wide at the rim only, worth about 1e-2 at most.
  const nt = 300, np = 240, grams = Array.from({ length: 9 }, () => new Array(9).fill(0));
  for (let i = 0; i < nt; ++i) {
    const theta = (i + 0.5) * (Math.PI / 2) / nt, area = Math.sin(theta) * (Math.PI / 2 / nt) * (2 * Math.PI / np);
    for (let j = 0; j < np; ++j) {
      const phi = (j + 0.5) * 2 * Math.PI / np;
      const h = relighting.hshBasis([Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)], 9);
      for (let a = 0; a < 9; ++a) for (let b = 0; b < 9; ++b) grams[a][b] += h[a] * h[b] * area;
    }
  }
  for (let a = 0; a < 9; ++a)
    for (let b = 0; b < 9; ++b) near(grams[a][b], a === b ? 1 : 0, 0.02, `integral of H${a} H${b}`);
});
