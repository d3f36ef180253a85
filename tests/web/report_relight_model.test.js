// The report's relighting arithmetic (src/report/web/relight_model.js) in Node: the decoding of
// relight-data, the rounding to bytes, the light's vector, the HSH basis (orthonormal on the
// hemisphere, as src/fit/basis.cpp's is), a learned model's light weights and each model's
// rendering of one or two pixels worked out by hand.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const model = require(path.join(__dirname, "../../src/report/web/relight_model.js"));

const base64 = (bytes) => Buffer.from(bytes).toString("base64");
const close = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual} is not ${expected} (within ${tolerance})`);

test("decodeBase64 gives the bytes the page was given", () => {
  assert.deepStrictEqual(Array.from(model.decodeBase64(base64([0, 1, 2, 127, 128, 255]))), [0, 1, 2, 127, 128, 255]);
  assert.strictEqual(model.decodeBase64("").length, 0);
});

test("sample clamps to 0..255 and rounds half away from zero as the C++ renderer", () => {
  assert.deepStrictEqual([-3, 0, 2.49, 2.5, 254.5, 255, 300].map(model.sample), [0, 0, 2, 3, 255, 255, 255]);
});

test("lightVector puts azimuth 0 to the right, 90 up and elevation 90 on the camera axis", () => {
  const cases = [[{ azimuth: 0, elevation: 0 }, [1, 0, 0]], [{ azimuth: 90, elevation: 0 }, [0, 1, 0]],
                 [{ azimuth: 180, elevation: 0 }, [-1, 0, 0]], [{ azimuth: 30, elevation: 90 }, [0, 0, 1]],
                 [{ azimuth: -90, elevation: 30 }, [0, -Math.sqrt(3) / 2, 0.5]]];
  for (const [light, expected] of cases) {
    const l = model.lightVector(light);
    expected.forEach((value, i) => close(l[i], value, 1e-12, `${JSON.stringify(light)}[${i}]`));
  }
});

test("hshBasis has the requested number of terms and its known values on the camera axis", () => {
  assert.strictEqual(model.hshBasis([0, 0, 1], 4).length, 4);
  assert.strictEqual(model.hshBasis([0, 0, 1], 16).length, 16);
  const h = model.hshBasis([0, 0, 2], 9);  // not normalised: the direction counts, not the length
  close(h[0], 1 / Math.sqrt(2 * Math.PI), 1e-12, "H0");
  close(h[2], Math.sqrt(3 / (2 * Math.PI)), 1e-12, "H2");
  close(h[6], Math.sqrt(5 / (2 * Math.PI)), 1e-12, "H6");
  [1, 3, 4, 5, 7, 8].forEach((k) => close(h[k], 0, 1e-12, `H${k}`));
});

test("the 16 HSH terms are orthonormal on the hemisphere", () => {
  // Midpoint rule in theta and phi with the measure sin(theta); the basis is clamped within
  // 0.01 rad of the horizon (as the C++), which the tolerance allows for.
  const steps = 180, gram = Array.from({ length: 16 }, () => new Array(16).fill(0));
  const dt = Math.PI / 2 / steps, dp = 2 * Math.PI / (2 * steps);
  for (let i = 0; i < steps; ++i) {
    const theta = (i + 0.5) * dt;
    for (let j = 0; j < 2 * steps; ++j) {
      const phi = (j + 0.5) * dp, w = Math.sin(theta) * dt * dp;
      const h = model.hshBasis([Math.sin(theta) * Math.cos(phi), Math.sin(theta) * Math.sin(phi), Math.cos(theta)], 16);
      for (let a = 0; a < 16; ++a) for (let b = 0; b < 16; ++b) gram[a][b] += w * h[a] * h[b];
    }
  }
  for (let a = 0; a < 16; ++a) for (let b = 0; b < 16; ++b) close(gram[a][b], a === b ? 1 : 0, 0.02, `<H${a}, H${b}>`);
});

// A learned model of `planes` planes on a bilinear map of 3 x 3 nodes, or on rbf `nodes`.
function learned(extra) {
  return Object.assign({ model: "learned", width: 1, height: 1, planes: 1, range: [2], scale: [1], bias: [0] }, extra);
}

test("learnedWeights on the bilinear map take the centre node straight up and plane 1 as (byte - 127) / range", () => {
  const m = learned({ basis: "bln", resolution: 3 });
  const bytes = new Uint8Array(2 * 9 * 3);
  bytes.set([255, 51, 0], 4 * 3);                 // plane 0, the centre node (index 4)
  bytes.set([127, 131, 27], (9 + 4) * 3);         // plane 1, the centre node
  bytes.set([255, 255, 255], 0);                  // plane 0, a corner node: no weight straight up
  const W = model.learnedWeights(m, bytes, [0, 0, 5]);
  assert.strictEqual(W.length, 6);
  [1, 0.2, 0, 0, 2, -50].forEach((value, i) => close(W[i], value, 1e-6, `W[${i}]`));
});

test("learnedWeights on the bilinear map share a light between the neighbouring nodes", () => {
  const m = learned({ basis: "bln", resolution: 3, planes: 0, range: [] });
  const bytes = new Uint8Array(9 * 3);
  // Towards +x, (1, 0, 1): u = ((x + y) / s + 1) / 2 * 2 = 1.5 and v = ((y - x) / s + 1) / 2 * 2 =
  // 0.5, a quarter to each of nodes 1, 2, 4 and 5 (none to node 0).
  bytes.set([255, 0, 0], 1 * 3);
  bytes.set([0, 255, 0], 4 * 3);
  bytes.set([0, 0, 255], 5 * 3);
  bytes.set([255, 255, 255], 0);
  const W = model.learnedWeights(m, bytes, [1, 0, 1]);
  [0.25, 0.25, 0.25].forEach((value, i) => close(W[i], value, 1e-6, `W[${i}]`));
});

test("learnedWeights with radial nodes are normalised and favour the node at the light", () => {
  const nodes = [0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0];
  const all = new Uint8Array(4 * 3).fill(255);
  const W = model.learnedWeights(learned({ basis: "rbf", nodes: nodes, planes: 0, range: [] }), all, [0, 0, 1]);
  close(W[0], 1, 1e-6, "the weights sum to 1");
  const first = new Uint8Array(4 * 3);
  first.set([255, 255, 255], 0);
  const near = model.learnedWeights(learned({ basis: "rbf", nodes: nodes, planes: 0, range: [] }), first, [0.1, 0, 1]);
  assert.ok(near[0] > 0.9, `the node at the light weighs ${near[0]}`);
  // Nodes 1 and 2 are as near to (1, 1, 0): together they weigh twice what node 1 does.
  const both = model.learnedWeights(learned({ basis: "rbf", nodes: nodes, planes: 0, range: [] }),
                                    new Uint8Array(12).fill(255, 3, 9), [1, 1, 0]);
  const one = model.learnedWeights(learned({ basis: "rbf", nodes: nodes, planes: 0, range: [] }),
                                   new Uint8Array(12).fill(255, 3, 6), [1, 1, 0]);
  assert.ok(one[0] > 0.4, `node 1 weighs ${one[0]}`);
  // Between nodes 0 and 1, far from node 3 (distances 0.765, 0.765, 1.848 and 1.414 to node 2):
  // eps = 8 / the exp(-2 d)-weighted mean distance, weight exp(-eps d^2), normalised.
  const bytes = new Uint8Array(12);
  bytes.set([255, 0, 0], 0);
  bytes.set([0, 255, 0], 9);
  const weights = model.learnedWeights(learned({ basis: "rbf", nodes: nodes, planes: 0, range: [] }), bytes, [1, 0, 1]);
  const d = [Math.sqrt(2 - Math.SQRT2), Math.sqrt(2 - Math.SQRT2), Math.SQRT2, Math.sqrt(2 + Math.SQRT2)];
  const eps = 8 / (d.reduce((s, x) => s + x * Math.exp(-2 * x), 0) / d.reduce((s, x) => s + Math.exp(-2 * x), 0));
  const w = d.map((x) => Math.exp(-eps * x * x)), total = w.reduce((s, x) => s + x, 0);
  close(weights[0], w[0] / total, 1e-6, "node 0");
  close(weights[1], w[3] / total, 1e-9, "node 3");
  close(one[0] * 2, both[0], 1e-6, "two nodes as near the light weigh the same");
});

test("a PTM LRGB model scales the pixel colour by the luminance polynomial at the light", () => {
  const coefficients = [0, 0, 0, 200, 0, 0];     // L = a3 lx
  const m = model.makeModel({ model: "ptm", format: "lrgb", basis: "ptm", width: 1, height: 1,
                              coefficients: base64(coefficients), rgb: base64([10, 100, 255]),
                              scale: [1, 1, 1, 1, 1, 1], bias: [0, 0, 0, 0, 0, 0] });
  const px = new Uint8ClampedArray(4);
  m.render([0.9, 0, 0.3], px);
  assert.deepStrictEqual(Array.from(px), [7, 71, 180, 255]);   // 10, 100, 255 times 180 / 255
  m.render([-0.5, 0, 0.8], px);
  assert.deepStrictEqual(Array.from(px), [0, 0, 0, 255]);
});

test("a PTM RGB model evaluates one polynomial per channel with its bias and scale", () => {
  // Two pixels; channel d of pixel t at (d * 2 + t) * 6. Only a5 (the constant) is set.
  const coefficients = new Array(36).fill(0);
  [[0, 0, 40], [1, 0, 90], [2, 0, 250], [0, 1, 7], [1, 1, 8], [2, 1, 9]].forEach(([d, t, v]) => {
    coefficients[(d * 2 + t) * 6 + 5] = v;
  });
  const m = model.makeModel({ model: "ptm", format: "rgb", basis: "ptm", width: 2, height: 1,
                              coefficients: base64(coefficients), rgb: "",
                              scale: [1, 1, 1, 1, 1, 2], bias: [0, 0, 0, 0, 0, 10] });
  const px = new Uint8ClampedArray(8);
  m.render([0.3, 0.3, 0.9], px);
  assert.deepStrictEqual(Array.from(px), [60, 160, 255, 255, 0, 0, 0, 255]);   // (v - 10) * 2
});

test("an HSH model sums the bytes times scale and the bias, each times the basis, in 0..255", () => {
  const m = model.makeModel({ model: "hsh", basis: "hsh", width: 1, height: 1, terms: 1,
                              coefficients: base64([200, 0, 255]), scale: [1], bias: [0.1] });
  const px = new Uint8ClampedArray(4), h0 = 1 / Math.sqrt(2 * Math.PI);
  m.render([0, 0, 1], px);
  assert.deepStrictEqual(Array.from(px), [200, 0, 255].map((b) => Math.round((b + 25.5) * h0)).concat([255]));
});

test("a learned model adds each plane's weighted bytes to the first plane and clamps to 0..1", () => {
  const bytes = new Uint8Array(2 * 9 * 3);
  bytes.set([51, 51, 255], 4 * 3);               // plane 0 at the centre node: 0.2, 0.2, 1
  bytes.set([227, 27, 227], (9 + 4) * 3);        // plane 1: 0.5, -0.5, 0.5 with range 200
  const m = model.makeModel(learned({ basis: "bln", resolution: 3, range: [200], scale: [2], bias: [0.25],
                                      coefficients: base64([204]), basisBytes: base64(bytes) }));
  const px = new Uint8ClampedArray(4);
  m.render([0, 0, 1], px);
  // byte 204: (0.8 - 0.25) * 2 = 1.1; 0.2 + 0.55, 0.2 - 0.55 (clamped), 1 + 0.55 (clamped).
  assert.deepStrictEqual(Array.from(px), [191, 0, 255, 255]);
});

test("an HSH model of 4 terms weighs each term by its basis value at the light", () => {
  // Pixel 0 then 1, each R, G, B, each 4 terms.
  const bytes = [100, 20, 50, 0, 0, 0, 0, 200, 0, 255, 0, 0, 9, 9, 9, 9, 0, 0, 0, 0, 255, 255, 255, 255];
  const m = model.makeModel({ model: "hsh", basis: "hsh", width: 2, height: 1, terms: 4, coefficients: base64(bytes),
                              scale: [1, 0.5, 2, 1], bias: [0, 0.2, 0, -0.1] });
  const px = new Uint8ClampedArray(8), l = [1, -0.5, 1], H = model.hshBasis(l, 4);
  m.render(l, px);
  const expected = [];
  for (let t = 0; t < 2; ++t) {
    for (let c = 0; c < 3; ++c) {
      let v = 0;
      for (let k = 0; k < 4; ++k) v += (bytes[(t * 3 + c) * 4 + k] / 255 * [1, 0.5, 2, 1][k] + [0, 0.2, 0, -0.1][k]) * H[k];
      expected.push(model.sample(255 * v));
    }
    expected.push(255);
  }
  assert.deepStrictEqual(Array.from(px), expected);
  assert.ok(new Set(expected).size > 4, `the pixels differ: ${expected}`);
});

test("relighting data of the wrong size is refused", () => {
  assert.throws(() => model.makeModel({ model: "hsh", width: 2, height: 1, terms: 4, coefficients: base64([1, 2, 3]) }),
                /HSH relighting data has the wrong size/);
  assert.throws(() => model.makeModel({ model: "ptm", format: "lrgb", width: 1, height: 1,
                                        coefficients: base64([1, 2, 3, 4, 5, 6]), rgb: base64([1, 2]) }),
                /PTM relighting data has the wrong size/);
  assert.throws(() => model.makeModel(learned({ basis: "bln", resolution: 3, coefficients: base64([1, 2]),
                                                basisBytes: base64([]) })),
                /learned relighting data has the wrong size/);
});
