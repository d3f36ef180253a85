// The review page's sentences from the record (src/review/web/review_words.js).
"use strict";
const test = require("node:test");
const assert = require("node:assert");
const path = require("node:path");
const w = require(path.join(__dirname, "../../src/review/web/review_words.js"));
const corners = ["dark skin", "bluish green", "black", "white"];

test("numbers shown to a tenth, or as a dash when there is none", () => {
  assert.strictEqual(w.shown(3.14159), "3.1");
  assert.strictEqual(w.shown(3.14159, 2), "3.14");
  assert.strictEqual(w.shown(null), "-");
});

test("doubtful highlights are the flagged ones and those of low confidence", () => {
  const f = { highlights: [{ sphere: 0, flag: "ok", confidence: 0.9 }, { sphere: 1, flag: "ok", confidence: 0.3 },
                           { sphere: 2, flag: "missing", reason: "no peak" }, { sphere: 3, flag: "manual" }] };
  assert.deepStrictEqual(w.frameFlags(f), ["sphere 2: ok", "sphere 3: missing \u2014 no peak"]);
});

test("the chart help follows the corners marked on this frame", () => {
  assert.match(w.chartHelp(null, "img_01", corners), /outer corner of the dark skin patch \(corner 1 of 4\)/);
  const chart = { image: "img_01", points: [{ x: 1, y: 1 }, { x: 2, y: 2 }] };
  assert.match(w.chartHelp(chart, "img_01", corners), /the black patch \(corner 3 of 4\)/);
  assert.match(w.chartHelp(chart, "img_02", corners), /the dark skin patch/);
  assert.match(w.chartHelp({ none: true }, "img_01", corners), /^No colour chart/);
  assert.strictEqual(w.modeHelp("chart", "r", "the chart's"), "the chart's");
  assert.match(w.modeHelp("none", "none", ""), /^Not processed yet/);
  assert.match(w.modeHelp("none", "sha256:1", ""), /^No sphere circle yet/);
});

test("the recorded chart and the capture line", () => {
  assert.match(w.chartRecorded({ outcome: "corrected", method: "given", image: "img_03", deltaE2000MeanBefore: 9.123,
                                 deltaE2000Mean: 1.5, deltaE2000Max: 3 }),
               /took the chart as given in img_03 .*9\.12 before, 1\.50 mean and 3\.00 largest/);
  assert.match(w.chartRecorded(null), /^No colour correction/);
  assert.strictEqual(w.captureLine({ capture: "/c", who: "Ana", revision: "sha256:0123456789abcdef" }),
                     "Capture /c \u2014 decisions recorded as made by Ana \u2014 record 0123456789ab");
  assert.strictEqual(w.lightFact({ elevation: 30, azimuth: 12.34, uncertaintyDegrees: 1, rmse: 0.5 }),
                     "elevation 30.0\u00b0, azimuth 12.3\u00b0 \u00b11.0\u00b0 (95 %), residual 0.50 levels");
});
