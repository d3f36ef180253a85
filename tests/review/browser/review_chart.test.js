// The review page's colour chart in Debian's headless Chromium (puppeteer-core), as a person
// uses it: on a generated capture with a ColorChecker (its corners as truth), the chart the run
// found is outlined on its frame; "Mark the colour chart" takes the four corners clicked in
// order (dark skin, bluish green, black, white), saying which comes next, draws them, resets,
// and applies them with their reason as --colour-chart IMAGE:X1,Y1,...; "No colour chart" asks
// for a reason and applies --colour-chart none. No console error may occur.
//
// Run by ctest (tests/review/CMakeLists.txt) with SURROGATE_EXE and GENERATOR_EXE set; exits 77
// (skipped) when chromium or the npm packages (scripts/install-deps: npm ci) are absent.
"use strict";

const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");

const { surrogateExe, generatorExe, run, workDir, startReview, launchBrowser, openReview } = require("./harness");

const work = workDir("surrogate-review-chart-");

// A capture with a chart and a warm cast (JPEG, 16 frames of 900 x 600), processed once: the
// chart is found. The generator's truth gives the corners a person would click.
const capture = path.join(work, "capture");
run(generatorExe, ["--out", capture, "--images", "16", "--width", "900", "--height", "600", "--sphere-radius", "50",
                   "--formats", "jpeg", "--colour-chart", "--colour-cast", "warm"]);
const truthLine = fs.readFileSync(path.join(capture, "truth", "colour-chart.txt"), "utf8").split("\n").find(l => l.startsWith("corners "));
const truth = truthLine.trim().split(/\s+/).slice(1).map(Number);
assert.equal(truth.length, 8);
fs.rmSync(path.join(capture, "truth"), { recursive: true });
run(surrogateExe, ["run", capture, "--quiet", "--no-report"]);


async function main() {
  const review = await startReview(capture);
  const browser = await launchBrowser(work);
  const problems = [];
  try {
    const page = await openReview(browser, review.address, problems, true);
    const state = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    assert.equal(state.chart.outcome, "corrected");
    assert.equal(state.chart.method, "found");
    const pending = () => page.$eval("body", b => b.getAttribute("data-pending"));
    const help = () => page.$eval("#mode-help", e => e.textContent);
    const toScreen = async (x, y) => {
      const o = await page.$eval("#overlay", e => { const r = e.getBoundingClientRect(); return { x: r.x, y: r.y, w: r.width }; });
      const scale = o.w / state.frameWidth;
      return { x: o.x + x * scale, y: o.y + y * scale };
    };

    // The mode: its button pressed, the chart box shown with what the run found, the outline
    // on the frame it was found in.
    await page.click("#mode-chart");
    assert.equal(await page.$eval("#mode-chart", b => b.getAttribute("aria-pressed")), "true");
    assert.equal(await page.$eval("#mode-sphere", b => b.getAttribute("aria-pressed")), "false");
    assert.equal(await page.$eval("#chart-box", b => b.hidden), false);
    assert.match(await page.$eval("#chart-recorded", p => p.textContent), new RegExp("found the chart in " + state.chart.image));
    await page.click('.thumb[data-frame="' + state.chart.image + '"]');
    assert.equal(await page.$$eval("#overlay polygon.chart.found", p => p.length), 1);

    // Marked on IMG_0002 (another frame: no found outline there), corner by corner.
    const names = ["dark skin", "bluish green", "black", "white"];
    const other = state.chart.image === "IMG_0002" ? "IMG_0003" : "IMG_0002";
    await page.click('.thumb[data-frame="' + other + '"]');
    assert.equal(await page.$$eval("#overlay polygon.chart.found", p => p.length), 0);
    async function markCorners() {
      // The frame in view whole (a thumbnail's click may have scrolled it partly away).
      await page.$eval("#viewer", e => e.scrollIntoView({ block: "center" }));
      for (let i = 0; i < 4; ++i) {
        assert.match(await help(), new RegExp("Click the outer corner of the " + names[i] + " patch \\(corner " + (i + 1) + " of 4\\)"));
        const at = await toScreen(truth[2 * i], truth[2 * i + 1]);
        const hit = await page.evaluate((x, y) => { const e = document.elementFromPoint(x, y); return e ? e.tagName + "#" + e.id : "nothing"; }, at.x, at.y);
        await page.mouse.click(at.x, at.y);
        assert.equal(await page.$$eval("#overlay circle.chart-corner", c => c.length), i + 1,
                     "corner " + (i + 1) + " at " + JSON.stringify(at) + " on " + hit + ": " + await page.$eval("#status", s => s.textContent) + " " + problems.join("; "));
      }
      assert.match(await help(), /The chart is marked on this frame/);
      assert.equal(await page.$$eval("#overlay polygon.chart.pending", p => p.length), 1);
    }
    await markCorners();
    assert.equal(await pending(), "1");
    await page.waitForFunction(o => document.getElementById("equivalent").textContent.includes("--colour-chart " + o + ":"), {}, other);
    // Reset: nothing marked, nothing pending; then marked again.
    await page.click("#chart-reset");
    assert.equal(await page.$$eval("#overlay .chart-corner", c => c.length), 0);
    assert.equal(await pending(), "0");
    await markCorners();
    await page.$eval("#chart-reason", el => el.select());
    await page.type("#chart-reason", "the chart was under a reflection");
    await page.screenshot({ path: path.join(work, "chart-marked.png") });
    await page.click("#apply");
    await page.waitForSelector("body[data-applied='1']", { timeout: 180000 });
    let after = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    let args = after.runs[after.runs.length - 1].arguments;
    assert.equal(after.runs[after.runs.length - 1].outcome, "completed");
    assert.deepEqual([args[0], args[2], args[4], args[5]], ["--operator", "--colour-chart", "--reason", "the chart was under a reflection"]);
    const given = /^(IMG_\d+):(.*)$/.exec(args[3]);
    assert.ok(given && given[1] === other, args[3]);
    // Within a pixel of the corners drawn (the mouse's own rounding, and tenths).
    given[2].split(",").map(Number).forEach((v, k) => assert.ok(Math.abs(v - truth[k]) < 1, "corner value " + k + ": " + v + " vs " + truth[k]));
    assert.equal(after.chart.method, "given");
    assert.equal(after.chart.image, other);
    assert.ok(after.runs[after.runs.length - 1].notes.join("\n").includes("the chart was under a reflection"));
    // The page shows the chart given, outlined on its frame, the mode kept.
    assert.equal(await page.$$eval("#overlay polygon.chart.found", p => p.length), 1);
    assert.match(await page.$eval("#chart-recorded", p => p.textContent), new RegExp("took the chart as given in " + other));

    // No colour chart: its reason is asked for before Apply, then recorded.
    await page.click("#chart-none");
    assert.equal(await page.$eval("#chart-none", b => b.getAttribute("aria-pressed")), "true");
    assert.equal(await pending(), "1");
    await page.click("#apply");
    assert.match(await page.$eval("#status", s => s.textContent), /Say why there is no colour chart/);
    await page.type("#chart-reason", "the chart is not the one on the stand");
    await page.waitForFunction(() => document.getElementById("equivalent").textContent.includes("--colour-chart none"));
    await page.click("#apply");
    await page.waitForSelector("body[data-applied='2']", { timeout: 180000 });
    after = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    args = after.runs[after.runs.length - 1].arguments;
    assert.deepEqual(args.slice(2), ["--colour-chart", "none", "--reason", "the chart is not the one on the stand"]);
    assert.equal(after.chart.chart, "none");
    assert.equal(after.chart.corners, null);
    assert.equal(await page.$$eval("#overlay polygon.chart", p => p.length), 0);
    assert.match(await page.$eval("#chart-recorded", p => p.textContent), /no colour chart/);

    const errorsInPage = await page.$eval("body", b => b.getAttribute("data-errors"));
    assert.equal(errorsInPage, null, "script errors: " + errorsInPage);
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    review.child.kill("SIGTERM");
  }
  fs.rmSync(work, { recursive: true, force: true });
  console.log("review page, colour chart: found outline, four corners marked, reset, applied; no chart applied: all as expected");
}

main().catch(e => {
  console.error(e && e.stack || e);
  console.error("work folder kept: " + work);
  process.exit(1);
});
