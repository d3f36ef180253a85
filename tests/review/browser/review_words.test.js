// The review page in a person's words and within the window, in Debian's headless Chromium
// (puppeteer-core), on a capture not yet run: no mode is on before there is a circle, and the
// page says to run the capture first; after the run, no elevation ring label ("el 30") lies under
// a light in the plot (the report's, src/report/hemisphere.cpp, which places them). A circle dragged off the sphere asks for a reason (none is written for the
// user), shows the command the run then records (--operator included), and its refusal says what
// to do on the page, with spheres numbered from 1 as in the decisions (the options' 0 only in the
// command). The runs' notes wrap: the page is as wide as the window at 800 and 1400 px.
//
// Run by ctest (tests/review/CMakeLists.txt) with SURROGATE_EXE and GENERATOR_EXE set; exits 77
// (skipped) when chromium or the npm packages (scripts/install-deps: npm ci) are absent.
"use strict";

const assert = require("node:assert/strict");
const fs = require("node:fs");
const path = require("node:path");

const { generatorExe, run, workDir, startReview, launchBrowser, openReview } = require("./harness");

const work = workDir("surrogate-review-words-");

// 24 frames of 400 x 300, not run: with this seed a light lies where the plot puts "el 30".
const capture = path.join(work, "capture");
run(generatorExe, ["--out", capture, "--images", "24", "--width", "400", "--height", "300", "--sphere-radius", "45", "--seed", "2"]);
fs.rmSync(path.join(capture, "truth"), { recursive: true });

// The page's own quoting of a command's words (page.cpp, quoted).
const quoted = a => (/^[A-Za-z0-9_.,:=/+-]+$/.test(a) ? a : "'" + a.replace(/'/g, "'\\''") + "'");

async function main() {
  const review = await startReview(capture);
  const browser = await launchBrowser(work);
  const problems = [];
  try {
    const page = await openReview(browser, review.address, problems);
    const text = id => page.$eval("#" + id, e => e.textContent);
    const pressed = id => page.$eval("#" + id, b => b.getAttribute("aria-pressed") + (b.disabled ? " disabled" : ""));
    const status = () => text("status");
    const applied = () => page.$eval("body", b => b.getAttribute("data-applied"));

    // Before any run: no circle, so neither "move a sphere" nor "place a highlight" is on, and the
    // page says what to do first.
    assert.equal(await pressed("mode-sphere"), "false disabled");
    assert.equal(await pressed("mode-highlight"), "false disabled");
    assert.match(await text("mode-help"), /^Not processed yet: first press .Run the capture./);
    assert.equal(await text("apply"), "Run the capture");
    await page.click("#apply");
    await page.waitForSelector("body[data-applied='1']", { timeout: 120000 });
    assert.match(await status(), /^Applied: run r1 completed/);
    assert.equal(await pressed("mode-sphere"), "true");

    // No ring label's box meets a light's, at either width.
    const overlaps = () => page.evaluate(() => {
      const boxes = sel => Array.from(document.querySelectorAll("#hemisphere-box " + sel), e => ({ e, b: e.getBoundingClientRect() }));
      const dots = boxes(".light"), labels = boxes("text");
      const meet = (p, q) => p.left < q.right && q.left < p.right && p.top < q.bottom && q.top < p.bottom;
      return { dots: dots.length, rings: labels.filter(l => /^el /.test(l.e.textContent)).length,
               over: labels.filter(l => dots.some(d => meet(l.b, d.b))).map(l => l.e.textContent) };
    });
    const widths = async () => {
      const out = [];
      for (const width of [800, 1400]) {
        await page.setViewport({ width, height: 1000 });
        out.push(await page.evaluate(() => document.documentElement.scrollWidth + "/" + window.innerWidth));
        const o = await overlaps();
        assert.equal(o.dots, 24);
        assert.equal(o.rings, 3);
        assert.deepEqual(o.over, [], "labels over lights at " + width + " px");
      }
      return out;
    };
    assert.deepEqual(await widths(), ["800/800", "1400/1400"]);

    // The circle dragged off the sphere, to the other half of the frame.
    const state = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    const sphere = state.spheres[0];
    const toScreen = async (x, y) => {
      const o = await page.$eval("#overlay", e => { const r = e.getBoundingClientRect(); return { x: r.x, y: r.y, w: r.width }; });
      return { x: o.x + x * o.w / state.frameWidth, y: o.y + y * o.w / state.frameWidth };
    };
    const from = await toScreen(sphere.cx, sphere.cy);
    const to = await toScreen(sphere.cx > 200 ? 100 : 300, sphere.cy > 150 ? 80 : 220);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(to.x, to.y, { steps: 8 });
    await page.mouse.up();

    // Its reason starts empty, and Apply without one is refused on the page.
    assert.equal(await page.$eval("#sphere-reason", e => e.value), "");
    await page.click("#apply");
    assert.match(await status(), /^Say why the circles are placed by hand/);
    assert.equal(await applied(), "1");
    await page.type("#sphere-reason", "the detection took the rim for the sphere");
    await page.waitForFunction(() => document.getElementById("equivalent").textContent.includes("--reason"));
    const shown = await text("equivalent");
    await page.click("#apply");
    await page.waitForFunction(() => /^The run stopped/.test(document.getElementById("status").textContent), { timeout: 120000 });

    // The refusal in the page's words, sphere 1, no option named.
    const refusal = await status();
    assert.match(refusal, /The circle placed by hand for sphere 1 shows no trustworthy highlight/);
    assert.match(refusal, /Drag the circle onto sphere 1/);
    assert.doesNotMatch(refusal, /--|sphere 0/);
    // The command shown is the one recorded.
    const after = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    const recorded = after.runs[after.runs.length - 1];
    assert.equal(recorded.outcome, "failed");
    assert.equal(recorded.arguments[0], "--operator");
    assert.equal(shown, "surrogate run " + quoted(capture) + " " + recorded.arguments.map(quoted).join(" "));
    // The standing circle, sphere 1 for people; withdrawn as --forget-sphere sphere1 in the command.
    const decision = await page.$eval('#decisions li[data-kind="manual-sphere"]', li => li.textContent);
    assert.match(decision, /circle of sphere 1 given by hand/);
    assert.doesNotMatch(decision, /sphere 0/);
    // The refusal's long note in Runs wraps within the window.
    assert.match(await text("runs"), /failed: /);
    assert.deepEqual(await widths(), ["800/800", "1400/1400"]);

    await page.click('#decisions li[data-kind="manual-sphere"] button');
    await page.type('#decisions li[data-kind="manual-sphere"] input', "it was not on the sphere");
    await page.click('#decisions li[data-kind="manual-sphere"] .inline-reason button');
    assert.match(await text("pending"), /withdraw the circle of sphere 1/);
    await page.waitForFunction(() => document.getElementById("equivalent").textContent.includes("--forget-sphere sphere1 --reason"));
    await page.click("#apply");
    await page.waitForFunction(() => document.body.getAttribute("data-applied") === "2" ||
                               /^(The run stopped|Not applied|Say why)/.test(document.getElementById("status").textContent), { timeout: 120000 });
    assert.match(await status(), /^Applied: run r3 completed/);
    // The residual check of each fit names the fit it ran on: two rows, two models.
    const residual = await page.$$eval('#checks tr[data-check="residual-outlier"] td:first-child', tds => tds.map(td => td.textContent));
    assert.equal(residual.length, 2);
    assert.match(residual[0], /Fit: PTM/);
    assert.match(residual[1], /Fit: HSH/);

    const errorsInPage = await page.$eval("body", b => b.getAttribute("data-errors"));
    assert.equal(errorsInPage, null, "script errors: " + errorsInPage);
    // Expected: the failed run's answer (422), which Chromium logs.
    assert.deepEqual(problems.filter(p => !/status of 422/.test(p)), []);
  } finally {
    await browser.close();
    review.child.kill("SIGTERM");
  }
  await new Promise(resolve => review.child.on("exit", resolve));
  fs.rmSync(work, { recursive: true, force: true });
  console.log("review page words and layout: no mode before a circle, labels clear of lights, reasons asked for, " +
              "the command shown recorded, the refusal in page words, notes wrapped: all as expected");
}

main().catch(e => {
  console.error(e && e.stack || e);
  console.error("work folder kept: " + work);
  process.exit(1);
});
