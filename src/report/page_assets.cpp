#include "report/page_assets.h"

namespace surrogate::report {

const char* const kReportCss = R"CSS(
:root { --fg:#1d1d1f; --muted:#62636a; --line:#d8d8de; --bg:#fafafa; --card:#fff;
        --bad:#b3261e; --warn:#8a5a00; --good:#1e6b34; }
* { box-sizing: border-box; }
body { margin:0; font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif; color:var(--fg); background:var(--bg); }
header { padding:24px 32px 12px; border-bottom:1px solid var(--line); background:var(--card); }
header h1 { margin:0 0 4px; font-size:26px; }
header p { margin:2px 0; color:var(--muted); }
main { padding:8px 32px 48px; max-width:1200px; }
section { margin-top:28px; }
h2 { font-size:20px; border-bottom:1px solid var(--line); padding-bottom:4px; }
h3 { font-size:16px; margin:18px 0 6px; }
.note { color:var(--muted); font-size:13px; }
.cards { display:flex; flex-wrap:wrap; gap:12px; }
.card { background:var(--card); border:1px solid var(--line); border-radius:6px; padding:10px 14px; min-width:140px; }
.card b { display:block; font-size:20px; }
.gallery { display:flex; flex-wrap:wrap; gap:16px; align-items:flex-start; }
figure { margin:0; background:var(--card); border:1px solid var(--line); border-radius:6px; padding:8px; }
figure img { display:block; max-width:100%; max-height:420px; width:auto; height:auto; }
figcaption { font-size:13px; color:var(--muted); margin-top:4px; width:0; min-width:100%; }
table { border-collapse:collapse; font-size:13px; margin:6px 0; }
th, td { border:1px solid var(--line); padding:3px 8px; text-align:left; vertical-align:top; }
th { background:#f0f0f3; }
td.num { text-align:right; font-variant-numeric:tabular-nums; }
code, .mono { font-family:ui-monospace,Menlo,Consolas,monospace; font-size:12px; word-break:break-all; }
.gaps li, .bad { color:var(--bad); }
.ok { color:var(--good); }
.warning { color:var(--warn); }
.plot { display:flex; flex-wrap:wrap; gap:24px; align-items:flex-start; }
.plot > div { flex:1; min-width:280px; }
#hemisphere { background:var(--card); border:1px solid var(--line); border-radius:6px; }
#hemisphere .grid { fill:none; stroke:#c9c9d0; stroke-width:1; }
#hemisphere .raking { stroke:#b3261e; stroke-dasharray:4 3; }
#hemisphere .gap { fill:#b3261e; fill-opacity:.10; stroke:none; }
#hemisphere .axis { font-size:11px; fill:var(--muted); }
#hemisphere .light { stroke:#222; stroke-width:1; }
ol.timeline { list-style:none; padding:0; margin:0; border-left:3px solid var(--line); }
ol.timeline > li { position:relative; margin:0 0 18px 0; padding-left:18px; }
ol.timeline > li::before { content:""; position:absolute; left:-9px; top:6px; width:15px; height:15px; border-radius:50%; background:var(--card); border:3px solid #5b6bd6; }
ol.timeline > li.failed::before { border-color:var(--bad); }
.step-head { font-weight:600; }
.intervention { border-left:3px solid var(--warn); background:#fff8e6; padding:4px 8px; margin:6px 0; }
.relight { display:flex; flex-wrap:wrap; gap:16px; align-items:flex-start; }
#relight-canvas { image-rendering:auto; width:min(560px, 100%); height:auto; border:1px solid var(--line); cursor:crosshair; touch-action:none; background:#000; }
#light-pad { border:1px solid var(--line); border-radius:50%; cursor:crosshair; touch-action:none; background:var(--card); }
details { margin:6px 0; }
summary { cursor:pointer; color:#3446b8; }
)CSS";

const char* const kReportJs = R"JS(
(function () {
  "use strict";
  var body = document.body;
  var errors = [];
  function record(message) {
    errors.push(String(message));
    body.setAttribute("data-errors", errors.join(" | "));
  }
  window.addEventListener("error", function (e) { record(e.message || "script error"); });
  var originalConsoleError = console.error;
  console.error = function () {
    record(Array.prototype.join.call(arguments, " "));
    return originalConsoleError.apply(console, arguments);
  };

  function decodeBase64(text) {
    var bin = atob(text), out = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  }

  // PTM relighting: L = a0 u^2 + a1 v^2 + a2 u v + a3 u + a4 v + a5, a_k = (byte - bias) * scale.
  function setUpRelight() {
    var dataElement = document.getElementById("relight-data");
    var canvas = document.getElementById("relight-canvas");
    var pad = document.getElementById("light-pad");
    if (!dataElement || !canvas || !pad) { body.setAttribute("data-relight", "absent"); return; }
    var ptm = JSON.parse(dataElement.textContent);
    var w = ptm.width, h = ptm.height, channels = ptm.format === "rgb" ? 3 : 1;
    var coef = decodeBase64(ptm.coefficients), rgb = decodeBase64(ptm.rgb);
    if (coef.length !== w * h * 6 * channels || (channels === 1 && rgb.length !== w * h * 3)) {
      throw new Error("relighting data has the wrong size");
    }
    canvas.width = w; canvas.height = h;
    var context = canvas.getContext("2d");
    var picture = context.createImageData(w, h);
    var readout = document.getElementById("light-readout");
    var light = { u: 0.5, v: 0.5 };

    function evaluate(base, u, v) {
      var s = ptm.scale, b = ptm.bias;
      return (coef[base] - b[0]) * s[0] * u * u + (coef[base + 1] - b[1]) * s[1] * v * v +
             (coef[base + 2] - b[2]) * s[2] * u * v + (coef[base + 3] - b[3]) * s[3] * u +
             (coef[base + 4] - b[4]) * s[4] * v + (coef[base + 5] - b[5]) * s[5];
    }
    function draw() {
      var u = light.u, v = light.v, px = picture.data, n = w * h;
      for (var t = 0; t < n; ++t) {
        if (channels === 1) {
          var lum = evaluate(t * 6, u, v) / 255;
          px[t * 4] = rgb[t * 3] * lum; px[t * 4 + 1] = rgb[t * 3 + 1] * lum; px[t * 4 + 2] = rgb[t * 3 + 2] * lum;
        } else {
          for (var c = 0; c < 3; ++c) px[t * 4 + c] = evaluate((c * n + t) * 6, u, v);
        }
        px[t * 4 + 3] = 255;
      }
      context.putImageData(picture, 0, 0);
      drawPad();
      var z = Math.sqrt(Math.max(0, 1 - u * u - v * v));
      var elevation = Math.asin(Math.min(1, z)) * 180 / Math.PI;
      var azimuth = Math.atan2(v, u) * 180 / Math.PI;
      readout.textContent = "light: elevation " + elevation.toFixed(0) + "\u00b0, azimuth " +
                            azimuth.toFixed(0) + "\u00b0 (x " + u.toFixed(2) + ", y " + v.toFixed(2) + ")";
    }
    function drawPad() {
      var g = pad.getContext("2d"), r = pad.width / 2 - 4, cx = pad.width / 2, cy = pad.height / 2;
      g.clearRect(0, 0, pad.width, pad.height);
      g.strokeStyle = "#c9c9d0"; g.beginPath(); g.arc(cx, cy, r, 0, 2 * Math.PI); g.stroke();
      g.beginPath(); g.arc(cx, cy, r * 2 / 3, 0, 2 * Math.PI); g.stroke();
      g.beginPath(); g.arc(cx, cy, r / 3, 0, 2 * Math.PI); g.stroke();
      g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
      g.beginPath(); g.arc(cx + light.u * r, cy - light.v * r, 7, 0, 2 * Math.PI); g.fill(); g.stroke();
    }
    function setFrom(element, event) {
      var box = element.getBoundingClientRect();
      var u = ((event.clientX - box.left) / box.width) * 2 - 1;
      var v = 1 - ((event.clientY - box.top) / box.height) * 2;
      var length = Math.sqrt(u * u + v * v);
      if (length > 1) { u /= length; v /= length; }
      light.u = u; light.v = v;
      draw();
    }
    [canvas, pad].forEach(function (element) {
      var dragging = false;
      element.addEventListener("pointerdown", function (e) {
        dragging = true; element.setPointerCapture(e.pointerId); setFrom(element, e);
      });
      element.addEventListener("pointermove", function (e) { if (dragging) setFrom(element, e); });
      element.addEventListener("pointerup", function () { dragging = false; });
    });
    draw();
    // Mean brightness of the first rendering (0..255): a blank or black view is a failure.
    var sum = 0;
    for (var i = 0; i < picture.data.length; i += 4) sum += picture.data[i] + picture.data[i + 1] + picture.data[i + 2];
    body.setAttribute("data-relight-mean", (sum / (3 * w * h)).toFixed(1));
    body.setAttribute("data-relight", "rendered");
  }

  try {
    setUpRelight();
  } catch (e) {
    record("relighting: " + e.message);
  }
  var plotted = document.querySelectorAll("#hemisphere circle.light").length;
  body.setAttribute("data-lights-plotted", String(plotted));
  body.setAttribute("data-ready", "yes");
})();
)JS";

}  // namespace surrogate::report
