// What the review page's browser tests share (review_page.test.js, review_chart.test.js): the
// programs under test from ctest's environment, Debian's chromium and puppeteer-core (a test
// exits 77, skipped, when either is absent: scripts/install-deps installs both), running a
// program, a work folder, `surrogate review` started on a capture with the address it prints,
// and the headless browser.
//
//   const { surrogateExe, run, workDir, startReview, launchBrowser } = require("./harness");
//   const review = await startReview(capture);   // { child, address, port, key, output() }
//   const browser = await launchBrowser(work);
"use strict";

const childProcess = require("node:child_process");
const fs = require("node:fs");
const os = require("node:os");
const path = require("node:path");

function skip(why) {
  console.error("SKIPPED: " + why);
  process.exit(77);
}

const surrogateExe = process.env.SURROGATE_EXE, generatorExe = process.env.GENERATOR_EXE;
if (!surrogateExe || !generatorExe) {
  console.error("set SURROGATE_EXE and GENERATOR_EXE (ctest does)");
  process.exit(2);
}
function chromiumPath() {
  const candidates = process.env.SURROGATE_CHROMIUM ? [process.env.SURROGATE_CHROMIUM] : ["chromium", "chromium-browser"];
  for (const name of candidates) {
    const found = childProcess.spawnSync("sh", ["-c", "command -v \"$0\"", name], { encoding: "utf8" });
    if (found.status === 0 && found.stdout.trim()) return found.stdout.trim();
  }
  return null;
}
const chromium = chromiumPath();
if (!chromium) skip("chromium is not installed (apt-get install chromium, or scripts/install-deps)");
let puppeteer;
try {
  puppeteer = require("puppeteer-core");
} catch (e) {
  skip("puppeteer-core is not installed: run scripts/install-deps (npm ci in tests/review/browser)");
}

// Runs a program to its end; its standard output, or an Error with both outputs.
function run(program, args) {
  const r = childProcess.spawnSync(program, args, { encoding: "utf8" });
  if (r.status !== 0) throw new Error(program + " " + args.join(" ") + " failed: " + r.stdout + r.stderr);
  return r.stdout;
}

const workDir = prefix => fs.mkdtempSync(path.join(os.tmpdir(), prefix));

// `surrogate review CAPTURE` on a free port, as "Ana Silva", resolved once it prints its address.
function startReview(capture) {
  return new Promise((resolve, reject) => {
    const child = childProcess.spawn(surrogateExe, ["review", capture, "--no-browser", "--port", "0", "--operator", "Ana Silva"],
                                     { stdio: ["ignore", "pipe", "pipe"] });
    let output = "";
    const timer = setTimeout(() => reject(new Error("surrogate review printed no address: " + output)), 20000);
    const seen = chunk => {
      output += chunk;
      const m = /(http:\/\/127\.0\.0\.1:(\d+)\/\?key=([0-9a-f]{64}))\n/.exec(output);
      if (m) { clearTimeout(timer); resolve({ child, address: m[1], port: Number(m[2]), key: m[3], output: () => output }); }
    };
    child.stdout.on("data", seen);
    child.stderr.on("data", seen);
    child.on("exit", code => reject(new Error("surrogate review ended (" + code + "): " + output)));
  });
}

// Headless chromium with its profile in `work`; `extraArgs` for a test that needs more (WebGL).
function launchBrowser(work, extraArgs = []) {
  return puppeteer.launch({
    executablePath: chromium,
    headless: true,
    protocolTimeout: 60000,
    args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--user-data-dir=" + path.join(work, "profile"), ...extraArgs],
  });
}

// A new page of the review at `address`, 1400x1000, every console error or warning and script
// error pushed onto `problems` (with the response statuses of 400 and above when `responses`),
// ready once the page says it is.
async function openReview(browser, address, problems, responses = false) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1400, height: 1000 });
  page.on("console", m => { if (m.type() === "error" || m.type() === "warn") problems.push("console " + m.type() + ": " + m.text()); });
  page.on("pageerror", e => problems.push("page error: " + e.message));
  if (responses) page.on("response", r => { if (r.status() >= 400) problems.push(r.status() + ": " + r.url()); });
  await page.goto(address, { waitUntil: "networkidle0" });
  await page.waitForSelector("body[data-ready=true]");
  return page;
}

module.exports = { surrogateExe, generatorExe, run, workDir, startReview, launchBrowser, openReview };
