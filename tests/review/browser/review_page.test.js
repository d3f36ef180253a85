// surrogate review's page driven in Debian's headless Chromium by puppeteer-core, as a person
// uses it: load, drag the sphere's circle and resize it, click a frame's highlight, leave a frame out with a
// reason, apply. Then the capture's carrier is compared with that of a copy run with
// `surrogate run` and the options the page's Apply recorded: the same bytes apart from times
// (and the command's name in the history). No console error or CSP violation may occur; a stale
// page is told so and writes nothing, and a page open while another command changes the record
// shows it; requests with another Host or Origin are refused (403).
//
// Run by ctest (tests/review/CMakeLists.txt) with SURROGATE_EXE and GENERATOR_EXE set; exits 77
// (skipped) when chromium or the npm packages (scripts/install-deps: npm ci) are absent.
"use strict";

const assert = require("node:assert/strict");
const fs = require("node:fs");
const http = require("node:http");
const path = require("node:path");

const { surrogateExe, generatorExe, run, workDir, startReview, launchBrowser } = require("./harness");

const work = workDir("surrogate-review-browser-");

// A generated capture (DNG originals and JPEG exports, 8 frames of 400 x 300), processed once.
const capture = path.join(work, "capture");
run(generatorExe, ["--out", capture, "--images", "8", "--width", "400", "--height", "300", "--sphere-radius", "45", "--seed", "7"]);
fs.rmSync(path.join(capture, "truth"), { recursive: true });
run(surrogateExe, ["run", capture, "--quiet", "--no-report"]);
const copy = path.join(work, "copy");
fs.cpSync(capture, copy, { recursive: true });
const carrierOf = dir => fs.readFileSync(path.join(dir, "assembly-files", "carrier.xml"), "utf8");
// What differs between two runs of the same decisions: times and durations.
const masked = xml => xml
  .replace(/(time|started|ended|seconds)="[^"]*"/g, '$1="T"')
  .replace(/<(modified|created)>[^<]*</g, "<$1>T<")
  .replace(/completed in [0-9.]+ s/g, "completed in T s");


// A request from outside the page (node's http), with the headers given.
function request(port, method, urlPath, headers, body) {
  return new Promise((resolve, reject) => {
    const req = http.request({ host: "127.0.0.1", port, method, path: urlPath, headers }, res => {
      let text = "";
      res.on("data", c => { text += c; });
      res.on("end", () => resolve({ status: res.statusCode, body: text }));
    });
    req.on("error", reject);
    if (body) req.write(body);
    req.end();
  });
}

async function main() {
  const review = await startReview(capture);
  // The address review printed, with its key: the browser keeps the key as a cookie and is sent
  // on to the address without it.
  const base = review.address;
  const browser = await launchBrowser(work);
  const problems = [];
  function watch(page, name) {
    page.on("console", m => { if (m.type() === "error" || m.type() === "warn") problems.push(name + " console " + m.type() + ": " + m.text()); });
    page.on("pageerror", e => problems.push(name + " page error: " + e.message));
    page.on("requestfailed", r => problems.push(name + " request failed: " + r.url() + " " + (r.failure() && r.failure().errorText)));
    page.on("response", r => { if (r.status() >= 400 && !r.url().endsWith("/api/apply")) problems.push(name + " " + r.status() + ": " + r.url()); });
  }
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1400, height: 1000 });
    watch(page, "page");
    // A second page opened now: it will be stale once the first applies.
    const stalePage = await browser.newPage();
    await stalePage.setViewport({ width: 1400, height: 1000 });
    watch(stalePage, "stale page");
    // This page never learns of the new record by itself (its look at the revision every few
    // seconds is cut off here), so that its Apply meets the server's refusal.
    await stalePage.setRequestInterception(true);
    stalePage.on("request", r => (r.url().endsWith("/api/revision") ? r.abort() : r.continue()));

    await page.goto(base, { waitUntil: "networkidle0" });
    await page.waitForSelector("body[data-ready=true]");
    // The key left the address bar, and the page's script cannot read the cookie (HttpOnly).
    assert.equal(page.url(), "http://127.0.0.1:" + review.port + "/");
    assert.equal(await page.evaluate(key => document.cookie.includes(key), review.key), false);
    await stalePage.goto(base, { waitUntil: "networkidle0" });
    await stalePage.waitForSelector("body[data-ready=true]");
    await page.bringToFront();
    const state = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    assert.equal(state.frames.length, 8);
    assert.equal(state.spheres.length, 1);
    assert.equal(await page.$$eval(".thumb", t => t.length), 8);
    assert.equal(await page.$$eval("#hemisphere-box circle.light", c => c.length), 8);
    // The frame's preview loaded, at the frame's size (thumbnails load as they come into view).
    await page.waitForFunction(() => { const i = document.getElementById("frame-image"); return i.complete && i.naturalWidth === 400; });

    // Drag the sphere's circle by (+5, -3) frame pixels, measured through the overlay's scale.
    const sphere = state.spheres[0];
    // Frame pixels to the screen's, through the overlay where it is now (the page's layout may
    // move as messages come and go).
    const toScreen = async (x, y) => {
      const o = await page.$eval("#overlay", e => { const r = e.getBoundingClientRect(); return { x: r.x, y: r.y, w: r.width }; });
      const scale = o.w / state.frameWidth;
      return { x: o.x + x * scale, y: o.y + y * scale };
    };
    const from = await toScreen(sphere.cx, sphere.cy), to = await toScreen(sphere.cx + 5, sphere.cy - 3);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(to.x, to.y, { steps: 8 });
    await page.mouse.up();
    // Then its orange square (on the rim at 45 degrees, below right) 3 px further out in x and y.
    const corner = sphere.r * Math.SQRT1_2;
    const grip = await toScreen(sphere.cx + 5 + corner, sphere.cy - 3 + corner);
    const pulled = await toScreen(sphere.cx + 5 + corner + 3, sphere.cy - 3 + corner + 3);
    await page.mouse.move(grip.x, grip.y);
    await page.mouse.down();
    await page.mouse.move(pulled.x, pulled.y, { steps: 6 });
    await page.mouse.up();
    const moved = { cx: sphere.cx + 5, cy: sphere.cy - 3, r: (corner + 3) * Math.SQRT2 };

    // Click the highlight of IMG_0003 where the detection put it, in highlight mode.
    const frame3 = state.frames.find(f => f.name === "IMG_0003");
    await page.click('.thumb[data-frame="IMG_0003"]');
    await page.click("#mode-highlight");
    const h = frame3.highlights[0];
    const click = await toScreen(h.x + 0.5, h.y - 0.5);
    await page.mouse.click(click.x, click.y);

    // The reasons for the circle and the highlight, typed (none is written for the user).
    await page.type("#sphere-reason", "the rim was cut by the frame");
    await page.type("#highlight-reason", "a reflection was taken for the highlight");

    // Leave IMG_0007 out, with a reason.
    await page.click('.thumb[data-frame="IMG_0007"]');
    await page.click("#exclude-frame");
    await page.type("#exclude-reason", "the flash did not fire");
    // And the title, typed over the folder's name (selected whole first: a triple click can
    // land as two clicks on a busy machine and leave the name in front of the typing).
    await page.focus("#field-title");
    await page.$eval("#field-title", el => el.select());
    await page.type("#field-title", "Stela 12");
    assert.equal(await page.$eval("body", b => b.getAttribute("data-pending")), "4");
    await page.waitForFunction(() => document.getElementById("equivalent").textContent.includes("--exclude IMG_0007"));

    await page.screenshot({ path: path.join(work, "before-apply.png") });
    await page.click("#apply");
    await page.waitForSelector("body[data-applied='1']", { timeout: 120000 });
    const status = await page.$eval("#status", s => s.textContent);
    assert.match(status, /^Applied: run r2 completed/);

    // What the Apply recorded, option by option.
    const after = await page.evaluate(() => fetch("/api/state").then(r => r.json()));
    const recorded = after.runs[after.runs.length - 1];
    assert.equal(recorded.command, "run");
    assert.equal(recorded.outcome, "completed");
    const args = recorded.arguments;
    assert.deepEqual(args.filter((a, i) => i % 2 === 0),
                     ["--operator", "--title", "--sphere", "--reason", "--highlight", "--reason", "--exclude", "--reason"]);
    assert.equal(args[1], "Ana Silva");
    assert.equal(args[3], "Stela 12");
    assert.equal(after.header.title, "Stela 12");
    const circle = args[5].split(",").map(Number);
    // Within the 0.1-pixel rounding of the options and a pixel of the mouse's own rounding.
    assert.ok(Math.abs(circle[0] - moved.cx) < 1 && Math.abs(circle[1] - moved.cy) < 1 && Math.abs(circle[2] - moved.r) < 1,
              "the circle " + args[5] + " is where the drag put it: " + JSON.stringify(moved));
    const hl = /^IMG_0003:sphere1=([-0-9.]+),([-0-9.]+)$/.exec(args[9]);
    assert.ok(hl, args[9]);
    assert.ok(Math.abs(Number(hl[1]) - (h.x + 0.5)) < 1 && Math.abs(Number(hl[2]) - (h.y - 0.5)) < 1, "the highlight " + args[9]);
    assert.deepEqual([args[7], args[11]], ["the rim was cut by the frame", "a reflection was taken for the highlight"]);
    assert.deepEqual(args.slice(12), ["--exclude", "IMG_0007", "--reason", "the flash did not fire"]);
    assert.equal(after.frames.find(f => f.name === "IMG_0007").excluded.reason, "the flash did not fire");
    assert.equal(after.spheres[0].source, "manual");

    // The same options typed for surrogate run on the copy: the same carrier.
    run(surrogateExe, ["run", copy].concat(args));
    const fromPage = carrierOf(capture), fromOptions = carrierOf(copy);
    assert.ok(fromPage.includes('command="run"'));
    assert.equal(masked(fromPage), masked(fromOptions), "the page and the options record the same carrier");

    // The page opened before the Apply is stale: its Apply is refused, said, and writes nothing.
    await stalePage.bringToFront();
    await stalePage.click('.thumb[data-frame="IMG_0002"]');
    await stalePage.click("#exclude-frame");
    await stalePage.type("#exclude-reason", "out of focus");
    await stalePage.click("#apply");
    await stalePage.waitForSelector("body[data-stale=true]", { timeout: 30000 });
    assert.match(await stalePage.$eval("#status", s => s.textContent), /out of date/);
    assert.equal(await stalePage.$eval("body", b => b.getAttribute("data-revision")), after.revision);
    assert.equal(carrierOf(capture), fromPage);

    // Requests from elsewhere: another Host (DNS rebinding), another Origin.
    const json = { "Content-Type": "application/json" };
    const decisions = JSON.stringify({ revision: after.revision, title: "Hijacked" });
    // Without the key (another account of the computer knows the port, not the key).
    assert.equal((await request(review.port, "GET", "/api/state", {})).status, 403);
    assert.equal((await request(review.port, "POST", "/api/apply", Object.assign({ Origin: "http://127.0.0.1:" + review.port }, json), decisions)).status, 403);
    assert.equal((await request(review.port, "GET", "/api/state", { Host: "evil.example:" + review.port })).status, 403);
    assert.equal((await request(review.port, "POST", "/api/apply", Object.assign({ Origin: "http://evil.example" }, json), decisions)).status, 403);
    assert.equal((await request(review.port, "POST", "/api/apply", Object.assign({ Host: "rebound.example:" + review.port }, json), decisions)).status, 403);
    assert.equal(carrierOf(capture), fromPage);

    // Another command changes the record while the first page is open: the page shows it
    // within seconds, and says so.
    await page.bringToFront();
    run(surrogateExe, ["run", capture, "--title", "Stela 12, second title"]);
    await page.waitForSelector("body[data-stale=true]", { timeout: 20000 });
    assert.match(await page.$eval("#status", s => s.textContent), /record changed while this page was open/);
    assert.equal(await page.$eval("#title-shown", t => t.textContent), "Stela 12, second title");
    assert.equal(await page.$eval("body", b => b.getAttribute("data-revision")), "sha256:" +
                 require("node:crypto").createHash("sha256").update(fs.readFileSync(path.join(capture, "assembly-files", "carrier.xml"))).digest("hex"));

    const errorsInPage = await page.$eval("body", b => b.getAttribute("data-errors"));
    assert.equal(errorsInPage, null, "script errors: " + errorsInPage);
    // Expected: the stale page's 409 answer (Chromium logs it) and its looks at the revision cut
    // off above. Nothing else may go wrong.
    const expected = [/^stale page console error: .*status of 409 \(Conflict\)$/,
                      /^stale page request failed: http:\/\/127\.0\.0\.1:\d+\/api\/revision net::ERR_FAILED$/,
                      /^stale page console error: Failed to load resource: net::ERR_FAILED$/];
    assert.deepEqual(problems.filter(p => !expected.some(e => e.test(p))), []);
  } finally {
    await browser.close();
    review.child.kill("SIGTERM");
  }
  const code = await new Promise(resolve => review.child.on("exit", resolve));
  assert.equal(code, 0, "surrogate review stops cleanly on SIGTERM");
  fs.rmSync(work, { recursive: true, force: true });
  console.log("review page: load, drag, resize, highlight, exclude, title, apply, stale pages, refusals: all as expected");
}

main().catch(e => {
  console.error(e && e.stack || e);
  console.error("work folder kept: " + work);
  process.exit(1);
});
