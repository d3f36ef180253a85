// The review page's changes as the decisions it sends (src/review/web/review_decisions.js): the
// request body /api/apply takes, what Apply still asks for, and the command line shown.
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const d = require(path.join(__dirname, "../../src/review/web/review_decisions.js"));

test("no change makes a request with the revision alone", () => {
  const p = d.emptyPending();
  assert.strictEqual(d.changeCount(p), 0);
  assert.deepStrictEqual(d.decisions(p, "sha256:abc"), { revision: "sha256:abc" });
});

test("moved circles and placed highlights are sent to a tenth of a pixel with their reasons", () => {
  const p = d.emptyPending();
  p.spheres = [{ cx: 100.04, cy: 50.06, r: 30.25 }];
  p.sphereReason = "the glare";
  p.highlights[d.highlightKey("img_01", 0)] = { image: "img_01", sphere: 0, x: 10.449, y: 20.51 };
  p.highlightReason = "by eye";
  p.exclude.img_02 = "blurred";
  p.accept.residual = "fine";
  p.title = "Stone";
  assert.strictEqual(d.changeCount(p), 5);
  assert.deepStrictEqual(d.decisions(p, "r1"), {
    revision: "r1", title: "Stone",
    spheres: [{ cx: 100, cy: 50.1, r: 30.3, reason: "the glare" }],
    highlights: [{ image: "img_01", sphere: 0, x: 10.4, y: 20.5, reason: "by eye" }],
    exclude: [{ image: "img_02", reason: "blurred" }],
    accept: [{ check: "residual", reason: "fine" }],
  });
});

test("a chart is sent once its four corners are marked, or as none", () => {
  const p = d.emptyPending();
  p.chart = { image: "img_03", points: [{ x: 1, y: 2 }, { x: 3, y: 4 }, { x: 5, y: 6 }] };
  p.chartReason = "low light";
  assert.strictEqual(d.decisions(p, "r").chart, undefined);
  assert.match(d.missingReason(p), /3 of 4 so far, next the white patch/);
  p.chart.points.push({ x: 7.06, y: 8 });
  assert.deepStrictEqual(d.decisions(p, "r").chart, { image: "img_03", reason: "low light", corners: [1, 2, 3, 4, 5, 6, 7.1, 8] });
  assert.strictEqual(d.missingReason(p), "");
  p.chart = { none: true };
  assert.deepStrictEqual(d.decisions(p, "r").chart, { none: true, reason: "low light" });
});

test("Apply asks for the reason each change by hand needs", () => {
  const p = d.emptyPending();
  p.exclude.img_04 = "  ";
  assert.match(d.missingReason(p), /^Say why img_04 is left out/);
  p.exclude.img_04 = "dark";
  p.spheres = [{ cx: 1, cy: 1, r: 5 }];
  assert.match(d.missingReason(p), /circles are placed by hand/);
  p.sphereReason = "moved";
  assert.strictEqual(d.missingReason(p), "");
});

test("withdrawn decisions name their frame and highlight", () => {
  assert.strictEqual(d.excludedFrameName("/data/cap/images/img_05.tif"), "img_05");
  assert.deepStrictEqual(d.highlightTarget("a:b:2"), { image: "a:b", sphere: 2 });
  const p = d.emptyPending();
  p.forgetHighlights["a:b:2"] = { image: "a:b", sphere: 2, reason: "wrong" };
  p.forgetSpheres["1"] = "gone";
  assert.deepStrictEqual(d.decisions(p, "r").forgetHighlights, [{ image: "a:b", sphere: 2, reason: "wrong" }]);
  assert.deepStrictEqual(d.decisions(p, "r").forgetSpheres, [{ sphere: 1, reason: "gone" }]);
  assert.strictEqual(d.pendingFor(p, "a:b"), 0);
});

test("the command line quotes only the words that need it", () => {
  assert.strictEqual(d.quoted("--exclude=img_01"), "--exclude=img_01");
  assert.strictEqual(d.quoted("/a/b+c,d"), "/a/b+c,d");
  assert.strictEqual(d.quoted("it's here"), "'it'\\''s here'");
  assert.strictEqual(d.commandLine("/data/my capture", ["--title", "A B"]), "surrogate run '/data/my capture' --title 'A B'");
});
