// The published viewer's light disc, its geometry (src/publish/web/viewer_geometry.js): light
// direction and disc position, both ways; the elevation rings; the test of an elevation against
// the range photographed; the numbers the page prints.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const geometry = require(path.join(__dirname, "../../src/publish/web/viewer_geometry.js"));

const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual}, expected ${expected}`);
const nearVector = (actual, expected, what) => expected.forEach((e, i) => near(actual[i], e, 1e-12, `${what}[${i}]`));

test("fromAngles gives the unit light of an azimuth and elevation, x right y up z towards the camera", () => {
  nearVector(geometry.fromAngles(0, 0), [1, 0, 0], "azimuth 0 on the horizon");
  nearVector(geometry.fromAngles(90, 0), [0, 1, 0], "azimuth 90 on the horizon");
  nearVector(geometry.fromAngles(-90, 0), [0, -1, 0], "azimuth -90 on the horizon");
  nearVector(geometry.fromAngles(123, 90), [0, 0, 1], "overhead");
  const h = Math.SQRT1_2;
  nearVector(geometry.fromAngles(45, 45), [0.5, 0.5, h], "azimuth 45 elevation 45");
  nearVector(geometry.fromAngles(180, 30), [-Math.sqrt(3) / 2, 0, 0.5], "azimuth 180 elevation 30");
});

test("anglesOf undoes fromAngles", () => {
  for (const [azimuth, elevation] of [[0, 0], [45, 45], [135, 10], [-60, 75], [-170, 5], [90, 89]]) {
    const a = geometry.anglesOf(geometry.fromAngles(azimuth, elevation));
    near(a.azimuth, azimuth, 1e-9, `azimuth of (${azimuth}, ${elevation})`);
    near(a.elevation, elevation, 1e-9, `elevation of (${azimuth}, ${elevation})`);
  }
  near(geometry.anglesOf([0, 0, 1.0000001]).elevation, 90, 0, "a z rounded past 1 is overhead, not NaN");
});

test("the elevation rings: the centre is overhead, the rim the horizon, linear between", () => {
  assert.strictEqual(geometry.discRadius(260), 104);
  assert.strictEqual(geometry.ringRadius(90, 104), 0);
  assert.strictEqual(geometry.ringRadius(0, 104), 104);
  assert.strictEqual(geometry.ringRadius(30, 90), 60);
  assert.strictEqual(geometry.ringRadius(60, 90), 30);
  assert.strictEqual(geometry.ringRadius(45, 100), 50);
});

test("the disc draws a light at its azimuth on its elevation ring, y downwards", () => {
  const r = 90;
  nearVector(geometry.discOffset({ azimuth: 0, elevation: 0 }, r), [90, 0], "right on the rim");
  nearVector(geometry.discOffset({ azimuth: 90, elevation: 30 }, r), [0, -60], "up, ring 30");
  nearVector(geometry.discOffset({ azimuth: 180, elevation: 60 }, r), [-30, 0], "left, ring 60");
  nearVector(geometry.discOffset({ azimuth: -90, elevation: 0 }, r), [0, 90], "down on the rim");
  nearVector(geometry.discOffset({ azimuth: 77, elevation: 90 }, r), [0, 0], "overhead at the centre");
  const d = geometry.discOffset({ azimuth: 45, elevation: 45 }, r);
  nearVector(d, [45 * Math.SQRT1_2, -45 * Math.SQRT1_2], "azimuth 45 elevation 45");
});

test("a pointer on the disc chooses the light the disc draws there, the rim and beyond the horizon", () => {
  const r = 104;
  for (const [azimuth, elevation] of [[0, 0], [30, 20], [100, 45], [-135, 70], [179, 5], [-10, 89]]) {
    const at = geometry.discOffset({ azimuth, elevation }, r);
    const light = geometry.lightAt(at[0], at[1], r, 0);
    nearVector(light, geometry.fromAngles(azimuth, elevation), `pointer at the light (${azimuth}, ${elevation})`);
  }
  nearVector(geometry.lightAt(0, -2 * r, r, 0), [0, 1, 0], "past the rim, upwards: the horizon at azimuth 90");
  nearVector(geometry.lightAt(r, 0, r, 0), [1, 0, 0], "on the rim, right");
  nearVector(geometry.lightAt(0, 0, r, 37), [0, 0, 1], "the centre: overhead");
  const a = geometry.anglesOf(geometry.lightAt(0, 0, r, 37));
  near(a.elevation, 90, 1e-12, "the centre's elevation");
  near(a.azimuth, 37, 1e-9, "the centre keeps the azimuth the light had");
});

test("the photographed range is read from data-photographed and an elevation is tested against it", () => {
  assert.deepStrictEqual(geometry.photographedRange("15.5,75.1"), [15.5, 75.1]);
  assert.deepStrictEqual(geometry.photographedRange("-5.0,0.0"), [-5, 0]);
  for (const unknown of [null, "", "15.5", "15.5,75.1,80", "a,b", "15.5,x"])
    assert.strictEqual(geometry.photographedRange(unknown), null, `"${unknown}" is not a range`);
  const range = [15.5, 75.1];
  assert.strictEqual(geometry.outsideRange(15.44, range), "below");
  assert.strictEqual(geometry.outsideRange(15.46, range), "", "within the readout's rounding of the lowest");
  assert.strictEqual(geometry.outsideRange(45, range), "");
  assert.strictEqual(geometry.outsideRange(75.14, range), "", "within the readout's rounding of the highest");
  assert.strictEqual(geometry.outsideRange(75.16, range), "above");
  assert.strictEqual(geometry.outsideRange(0, null), "", "unknown range: nothing said");
  assert.strictEqual(geometry.outsideRange(90, null), "");
});

test("fixed prints no negative zero but keeps real negatives", () => {
  assert.strictEqual(geometry.fixed(-0.0001, 3), "0.000");
  assert.strictEqual(geometry.fixed(-0, 1), "0.0");
  assert.strictEqual(geometry.fixed(-0.04, 1), "0.0");
  assert.strictEqual(geometry.fixed(-0.06, 1), "-0.1");
  assert.strictEqual(geometry.fixed(-12.345, 1), "-12.3");
  assert.strictEqual(geometry.fixed(0.5, 3), "0.500");
});
