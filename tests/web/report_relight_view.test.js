// The report's relighting view without the DOM (src/report/web/relight_view.js) in Node: the
// light an address or a pointer chooses, the light disc's geometry and marks, the texts shown
// and the figures recorded on <body> for the browser tests.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const view = require(path.join(__dirname, "../../src/report/web/relight_view.js"));

const close = (actual, expected, what) =>
  assert.ok(Math.abs(actual - expected) <= 1e-9, `${what}: ${actual} is not ${expected}`);
const closeLight = (actual, expected, what) => {
  close(actual.azimuth, expected.azimuth, `${what}, azimuth`);
  close(actual.elevation, expected.elevation, `${what}, elevation`);
};

test("parseHash reads name=value pairs, decoded, with or without the #", () => {
  assert.deepStrictEqual(view.parseHash("#model=1&light=0.5%2C0.5%2C0.7"), { model: "1", light: "0.5,0.5,0.7" });
  assert.deepStrictEqual(view.parseHash("azimuth=-30&elevation=20"), { azimuth: "-30", elevation: "20" });
  assert.deepStrictEqual(view.parseHash("#stray&a=b=c&model=2"), { model: "2" });
  assert.deepStrictEqual(view.parseHash(""), {});
});

test("anglesFromDirection turns x,y,z into azimuth and elevation, and refuses no direction", () => {
  closeLight(view.anglesFromDirection("1,0,0"), { azimuth: 0, elevation: 0 }, "right");
  closeLight(view.anglesFromDirection("0,2,2"), { azimuth: 90, elevation: 45 }, "up, half raised");
  closeLight(view.anglesFromDirection("-1,0,0"), { azimuth: 180, elevation: 0 }, "left");
  closeLight(view.anglesFromDirection("0,0,3"), { azimuth: 0, elevation: 90 }, "on the axis");
  assert.strictEqual(view.anglesFromDirection("0,0,0"), null);
});

test("startLight is 45, 45, else the captured lights mean, else what the address names", () => {
  assert.deepStrictEqual(view.startLight(null, {}), { azimuth: 45, elevation: 45 });
  closeLight(view.startLight("0,1,0", {}), { azimuth: 90, elevation: 0 }, "the mean direction");
  closeLight(view.startLight("0,1,0", { light: "-1,0,1" }), { azimuth: 180, elevation: 45 }, "the address's light");
  closeLight(view.startLight("0,1,0", { light: "0,0,0" }), { azimuth: 90, elevation: 0 }, "no direction is ignored");
  closeLight(view.startLight("0,0,0", {}), { azimuth: 45, elevation: 45 }, "no mean direction is ignored");
  closeLight(view.startLight("0,1,0", { light: "1,0,0", azimuth: "-120", elevation: "20" }),
             { azimuth: -120, elevation: 20 }, "the address's angles last");
});

test("firstModel is the address's model within the models there are", () => {
  assert.strictEqual(view.firstModel({}, 3), 0);
  assert.strictEqual(view.firstModel({ model: "1" }, 3), 1);
  assert.strictEqual(view.firstModel({ model: "9" }, 3), 2);
  assert.strictEqual(view.firstModel({ model: "-2" }, 3), 0);
});

test("the disc is centred with 34 px left for its labels", () => {
  assert.deepStrictEqual(view.padGeometry(300, 300), { cx: 150, cy: 150, r: 116 });
  assert.deepStrictEqual(view.padGeometry(240, 260), { cx: 120, cy: 130, r: 86 });
});

test("the disc has rings at elevation 0, 30 and 60 and spokes labelled past the rim", () => {
  const p = { cx: 150, cy: 150, r: 90 }, marks = view.padMarks(p);
  assert.deepStrictEqual(marks.rings.map((ring) => ring.label), ["el 0\u00b0", "el 30\u00b0", "el 60\u00b0"]);
  marks.rings.forEach((ring, i) => close(ring.r, 90 - 30 * i, `ring ${i}`));
  // A ring's label sits on it at 112.5 degrees (up and a little left), 8 px lower.
  const a = 112.5 * Math.PI / 180;
  close(marks.rings[1].x, 150 + 60 * Math.cos(a), "label x");
  close(marks.rings[1].y, 150 - 60 * Math.sin(a) + 8, "label y");
  assert.deepStrictEqual(marks.spokes.map((spoke) => spoke.label), ["0\u00b0", "90\u00b0", "180\u00b0", "\u221290\u00b0"]);
  const ends = [[240, 150], [150, 60], [60, 150], [150, 240]];
  const labels = [[257, 150], [150, 50], [43, 150], [150, 250]];
  marks.spokes.forEach((spoke, i) => {
    close(spoke.endX, ends[i][0], `spoke ${i} end x`);
    close(spoke.endY, ends[i][1], `spoke ${i} end y`);
    close(spoke.x, labels[i][0], `spoke ${i} label x`);
    close(spoke.y, labels[i][1], `spoke ${i} label y`);
  });
});

test("lightSpot is the centre straight on and on the rim at grazing light", () => {
  const p = { cx: 100, cy: 120, r: 80 };
  const centre = view.lightSpot(p, { azimuth: 70, elevation: 90 });
  close(centre.x, 100, "x"); close(centre.y, 120, "y");
  const up = view.lightSpot(p, { azimuth: 90, elevation: 0 });
  close(up.x, 100, "x"); close(up.y, 40, "y");
  const halfLeft = view.lightSpot(p, { azimuth: 180, elevation: 45 });
  close(halfLeft.x, 60, "x"); close(halfLeft.y, 120, "y");
});

test("lightFromPointer is the inverse of lightSpot, past the rim grazing, at the centre keeping its azimuth", () => {
  closeLight(view.lightFromPointer(0, 0, 80, 33), { azimuth: 33, elevation: 90 }, "the centre");
  closeLight(view.lightFromPointer(200, 0, 80, 33), { azimuth: 0, elevation: 0 }, "past the rim");
  closeLight(view.lightFromPointer(0, -40, 80, 33), { azimuth: 90, elevation: 45 }, "halfway up");
  const p = { cx: 100, cy: 120, r: 80 };
  for (const light of [{ azimuth: -135, elevation: 10 }, { azimuth: 20, elevation: 70 }, { azimuth: 170, elevation: 35 }]) {
    const spot = view.lightSpot(p, light);
    closeLight(view.lightFromPointer(spot.x - p.cx, spot.y - p.cy, p.r, 0), light, `back from ${JSON.stringify(light)}`);
  }
});

test("the readout and the caption say the light and the model shown", () => {
  assert.strictEqual(view.readoutText({ azimuth: -120, elevation: 30.25 }), "Light: azimuth -120.0\u00b0, elevation 30.3\u00b0");
  assert.strictEqual(view.captionText({ basis: "hsh", width: 600, height: 400, originalWidth: 1200, originalHeight: 800 }),
                     "HSH model, 600\u00d7400 (a copy of the 1200\u00d7800 model)");
  assert.strictEqual(view.captionText({ basis: "rbf", width: 300, height: 200, originalWidth: 300, originalHeight: 200 }),
                     "RBF model, 300\u00d7200 (the model's own resolution)");
});

test("renderingFigures gives the mean, the light and the pixels at the centres of a 3x3 grid", () => {
  const width = 6, height = 3, d = new Uint8ClampedArray(width * height * 4);
  for (let t = 0; t < width * height; ++t) d.set([t, 2 * t, 3 * t, 255], t * 4);
  const figures = view.renderingFigures(d, width, height, { azimuth: 12.34, elevation: 56.78 });
  // The mean of t, 2t and 3t over t = 0..17 is 2 * 8.5.
  assert.strictEqual(figures.mean, "17.000");
  assert.strictEqual(figures.light, "12.3,56.8");
  // Columns 1, 3 and 5; rows floor(3 / 6) = 0, floor(9 / 6) = 1, floor(15 / 6) = 2.
  const expected = [];
  for (const y of [0, 1, 2]) for (const x of [1, 3, 5]) { const t = y * width + x; expected.push(`${x},${y}:${t},${2 * t},${3 * t}`); }
  assert.strictEqual(figures.probes, expected.join(";"));
});

test("elementName names the tag, the id and the first class, not an SVG element's class object", () => {
  assert.strictEqual(view.elementName("DIV", "relight", "first-row wide"), "div#relight.first-row");
  assert.strictEqual(view.elementName("TABLE", "", ""), "table");
  assert.strictEqual(view.elementName("svg", "hemisphere", { baseVal: "plot" }), "svg#hemisphere");
});
