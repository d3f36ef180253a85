// Learned layouts (rbf, bilinear) that Surrogate writes, drawn by OpenLIME itself in Debian's
// headless chromium (software WebGL): an OpenLIME Viewer with an RTI layer (layout "image")
// served from a local server this test starts, lit at a chosen light; the canvas's pixels are
// compared with `surrogate render DIR --light` of the same folder.
//
// OpenLIME is not in the npm registry this project reaches: the test looks for it in
// tests/review/browser/node_modules/openlime, then at $SURROGATE_OPENLIME (a copy of
// openlime.js, e.g. relight's demo/openlime.js), and exits 77 (skipped) when it finds neither,
// as it does without chromium or puppeteer-core (harness.js).
"use strict";

const fs = require("node:fs");
const http = require("node:http");
const path = require("node:path");
const harness = require("../../review/browser/harness");

const sampleExe = process.env.LEARNED_SAMPLE_EXE;
if (!sampleExe) { console.error("set LEARNED_SAMPLE_EXE (ctest does)"); process.exit(2); }

function openlimePath() {
  try { return require.resolve("openlime/dist/js/openlime.js", { paths: [path.join(__dirname, "../../review/browser")] }); } catch (e) { /* next */ }
  if (process.env.SURROGATE_OPENLIME && fs.existsSync(process.env.SURROGATE_OPENLIME)) return process.env.SURROGATE_OPENLIME;
  console.error("SKIPPED: OpenLIME not found (no openlime npm package; set SURROGATE_OPENLIME to an openlime.js)");
  process.exit(77);
}
const openlime = openlimePath();

const W = 64, H = 48;
// OpenLIME's setLight takes (x, y) and puts z = sqrt(1 - x^2 - y^2).
const lights = [[0.3, 0.2], [-0.55, 0.4], [0.1, -0.7]];

const page = `<!doctype html><html><head><style>body{margin:0;background:#000}#lime{width:${W}px;height:${H}px;position:relative;overflow:hidden}#lime canvas{position:absolute;left:0;top:0;width:100%;height:100%}</style></head>
<body><div id="lime"></div><script src="/openlime.js"></script><script>
let lime, layer;
window.open_ = url => new Promise(resolve => {
  lime = new OpenLIME.Viewer('#lime', { background: 'black' });
  layer = new OpenLIME.Layer({ type: 'rti', url, layout: 'image', normals: false });
  lime.canvas.addLayer('rti', layer);
  layer.addEvent('ready', () => resolve());
});
window.pixels_ = src => new Promise(resolve => {
  const draw = source => {
    const c = document.createElement('canvas'); c.width = ${W}; c.height = ${H};
    const g = c.getContext('2d'); g.drawImage(source, 0, 0, ${W}, ${H});
    resolve(Array.from(g.getImageData(0, 0, ${W}, ${H}).data));
  };
  if (!src) return draw(document.querySelector('#lime canvas'));
  const img = new Image(); img.onload = () => draw(img); img.src = src;
});
</script></body></html>`;

function serve(root) {
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(req.url.split("?")[0]);
    let file = null;
    if (url === "/") { res.writeHead(200, { "content-type": "text/html" }); return res.end(page); }
    if (url === "/openlime.js") file = openlime;
    else if (!url.includes("..")) file = path.join(root, url);
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) { res.writeHead(404); return res.end(); }
    const type = file.endsWith(".json") ? "application/json" : file.endsWith(".js") ? "text/javascript"
      : file.endsWith(".png") ? "image/png" : "image/jpeg";
    res.writeHead(200, { "content-type": type });
    res.end(fs.readFileSync(file));
  });
  return new Promise(resolve => server.listen(0, "127.0.0.1", () => resolve(server)));
}

(async () => {
  const work = harness.workDir("openlime-learned-");
  harness.run(sampleExe, [path.join(work, "layouts")]);
  const server = await serve(work);
  const base = "http://127.0.0.1:" + server.address().port;
  const browser = await harness.launchBrowser(work, ["--enable-unsafe-swiftshader", "--use-angle=swiftshader", "--force-color-profile=srgb"]);
  let failed = false;
  try {
    for (const kind of ["rbf", "bln"]) {
      const tab = await browser.newPage();
      await tab.setViewport({ width: 200, height: 200, deviceScaleFactor: 1 });
      const messages = [];
      tab.on("pageerror", e => messages.push(String(e)));
      await tab.goto(base + "/");
      await tab.evaluate(url => window.open_(url), "/layouts/" + kind + "/info.json");
      for (const [x, y] of lights) {
        const z = Math.sqrt(1 - x * x - y * y);
        const png = "relit-" + kind + "-" + x + "-" + y + ".png";
        harness.run(harness.surrogateExe, ["render", path.join(work, "layouts", kind), "--light", [x, y, z].join(","), "-o", path.join(work, png)]);
        await tab.evaluate((x, y) => { layer.setLight([x, y], 0); lime.redraw(); }, x, y);
        // Drawn when two reads 150 ms apart agree and the picture is not black.
        let shown = null;
        for (let i = 0; i < 60; ++i) {
          await new Promise(r => setTimeout(r, 150));
          const now = await tab.evaluate(() => window.pixels_(null));
          if (shown && now.some(v => v > 10) && now.every((v, k) => v === shown[k])) break;
          shown = now;
        }
        const expected = await tab.evaluate(src => window.pixels_(src), "/" + png);
        if (process.env.DEBUG_LIME) {
          const cv = await tab.evaluate(() => { const c = document.querySelector("#lime canvas"); return [c.width, c.height, c.clientWidth, c.clientHeight]; });
          console.log(cv, "row 24:", shown.slice(24 * W * 4, (24 * W + 6) * 4).join(" "), "| expected:", expected.slice(24 * W * 4, (24 * W + 6) * 4).join(" "));
        }
        let worst = 0, sum = 0, n = 0;
        for (let yy = 1; yy < H - 1; ++yy)   // the border texels meet the background when filtered
          for (let xx = 1; xx < W - 1; ++xx)
            for (let c = 0; c < 3; ++c) {
              const k = (yy * W + xx) * 4 + c, d = Math.abs(shown[k] - expected[k]);
              worst = Math.max(worst, d); sum += d; ++n;
            }
        const ok = worst <= 3;
        console.log(`${kind} light ${x},${y},${z.toFixed(4)}: OpenLIME against surrogate render: worst ${worst}, mean ${(sum / n).toFixed(3)} levels ${ok ? "ok" : "FAILED"}`);
        if (!ok) failed = true;
      }
      if (messages.length) { console.log("page errors: " + messages.join("\n")); failed = true; }
      await tab.close();
    }
  } finally {
    await browser.close();
    server.close();
    fs.rmSync(work, { recursive: true, force: true });
  }
  process.exit(failed ? 1 : 0);
})().catch(e => { console.error(e); process.exit(1); });
