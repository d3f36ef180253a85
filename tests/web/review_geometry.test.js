// The review page's geometry (src/review/web/review_geometry.js): where a click falls, how a
// dragged circle moves and grows, and where the overlay's marks go.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const g = require(path.join(__dirname, "../../src/review/web/review_geometry.js"));

test("a click falls in the first circle that holds it, on its edge included", () => {
  const spheres = [{ cx: 100, cy: 100, r: 20 }, { cx: 110, cy: 100, r: 20 }, { cx: 300, cy: 100, r: 10 }];
  assert.strictEqual(g.sphereAt({ x: 105, y: 100 }, spheres), 0);
  assert.strictEqual(g.sphereAt({ x: 125, y: 100 }, spheres), 1);
  assert.strictEqual(g.sphereAt({ x: 300, y: 110 }, spheres), 2);
  assert.strictEqual(g.sphereAt({ x: 200, y: 100 }, spheres), -1);
  assert.strictEqual(g.sphereAt({ x: 1, y: 1 }, []), -1);
});

test("a dragged circle stays in the frame and keeps a radius of at least 3", () => {
  const drag = { start: { x: 50, y: 50 }, cx: 60, cy: 40, r: 10 };
  assert.deepStrictEqual(g.moved(drag, { x: 70, y: 45 }, 400, 300), { cx: 80, cy: 35 });
  assert.deepStrictEqual(g.moved(drag, { x: -100, y: 400 }, 400, 300), { cx: 0, cy: 300 });
  assert.strictEqual(g.resized(drag, { x: 63, y: 44 }), 5);
  assert.strictEqual(g.resized(drag, { x: 61, y: 40 }), 3);
  assert.deepStrictEqual(g.withinFrame({ x: 500, y: -2 }, 400, 300), { x: 400, y: 0 });
  assert.deepStrictEqual(g.newSphere(400, 300), { cx: 200, cy: 150, r: 37.5 });
});

test("the handle sits on the circle at 45 degrees and the marks keep their screen size", () => {
  const s = { cx: 100, cy: 100, r: 40 };
  const h = g.handleSquare(s, 2);
  assert.ok(Math.abs(h.x + 14 - (100 + 40 * Math.SQRT1_2)) < 1e-9);
  assert.strictEqual(h.width, 28);
  assert.strictEqual(h.height, 28);
  assert.deepStrictEqual(g.sphereLabel(s, 2), { x: 60, y: 52 });
  assert.deepStrictEqual(g.cornerLabel({ x: 10, y: 20 }, 0.5), { x: 14, y: 16 });
});

test("a highlight's cross has four strokes from 2r to r off its centre", () => {
  assert.strictEqual(g.crossPath({ x: 10, y: 20 }, 3), "M4 20h3m6 0h3M10 14v3m0 6v3");
});

test("the highlights drawn: a placed one replaces the recorded one, doubtful ones flagged", () => {
  const key = (image, sphere) => image + ":" + sphere;
  const f = { name: "img_01", highlights: [
    { sphere: 0, x: 5, y: 6, flag: "ok", confidence: 0.9 },
    { sphere: 1, x: 7, y: 8, flag: "ok", confidence: 0.2 },
    { sphere: 2, x: null, y: null, flag: "missing" },
    { sphere: 3, x: 1, y: 2, flag: "multiple" },
  ] };
  const placed = { "img_01:0": { image: "img_01", sphere: 0, x: 50, y: 60 }, "img_02:1": { image: "img_02", sphere: 1, x: 0, y: 0 } };
  assert.deepStrictEqual(g.highlightMarks(f, placed, key), [
    { x: 7, y: 8, cls: "flagged", sphere: 1 },
    { x: 1, y: 2, cls: "multiple", sphere: 3 },
    { x: 50, y: 60, cls: "pending", sphere: 0 },
  ]);
});

test("the chart's outlines as SVG points", () => {
  assert.strictEqual(g.cornersPoints([1, 2, 3, 4, 5, 6, 7, 8]), "1,2 3,4 5,6 7,8");
  assert.strictEqual(g.pointsList([{ x: 1.5, y: 2 }, { x: 3, y: 4 }]), "1.5,2 3,4");
});
