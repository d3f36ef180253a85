#include "report/page_assets.h"

namespace surrogate::report {

const char* const kReportCss = R"CSS(
:root { --fg:#1d1d1f; --muted:#62636a; --line:#d8d8de; --bg:#fafafa; --card:#fff;
        --bad:#b3261e; --warn:#8a5a00; --good:#1e6b34; --accent:#3446b8; }
* { box-sizing: border-box; }
body { margin:0; font:15px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif; color:var(--fg); background:var(--bg); }
header { padding:12px 24px 8px; border-bottom:1px solid var(--line); background:var(--card); }
header h1 { margin:0 0 2px; font-size:24px; overflow-wrap:anywhere; }
header p { margin:2px 0; }
main { padding:4px 24px 48px; max-width:1680px; margin:0 auto; }
section { margin-top:18px; min-width:0; }
h2 { font-size:20px; border-bottom:1px solid var(--line); padding-bottom:4px; margin:0 0 10px; }
h3 { font-size:16px; margin:14px 0 6px; }
.visually-hidden { position:absolute; width:1px; height:1px; overflow:hidden; clip:rect(0 0 0 0); white-space:nowrap; }
.note { color:var(--muted); font-size:13px; }
.facts { columns:4 250px; column-gap:10px; }
.fact { background:var(--card); border:1px solid var(--line); border-radius:6px; padding:4px 12px 6px; margin:0 0 10px; break-inside:avoid; font-size:14px; line-height:1.35; }
.fact h3 { margin:2px 0 4px; font-size:13px; text-transform:uppercase; letter-spacing:.04em; color:var(--muted); }
.fact h3 code { text-transform:none; letter-spacing:0; }
.fact dl { display:grid; grid-template-columns:max-content 1fr; gap:2px 12px; margin:0; }
.fact dt { color:var(--muted); }
.fact dd { margin:0; overflow-wrap:anywhere; }
.fact p { margin:2px 0; }
.verdict { font-weight:700; }
.gallery { display:grid; grid-template-columns:repeat(auto-fill, minmax(min(100%, 320px), 1fr)); gap:16px; align-items:start; }
.gallery.large { grid-template-columns:repeat(auto-fill, minmax(min(100%, 480px), 1fr)); }
figure { margin:0; background:var(--card); border:1px solid var(--line); border-radius:6px; padding:8px; min-width:0; }
figure img { display:block; max-width:100%; height:auto; margin:0 auto; }
figcaption { font-size:13px; color:var(--muted); margin-top:4px; overflow-wrap:anywhere; }
table { border-collapse:collapse; font-size:13px; margin:6px 0; display:block; max-width:100%; overflow-x:auto; }
th, td { border:1px solid var(--line); padding:3px 8px; text-align:left; vertical-align:top; }
th { background:#f0f0f3; }
td.num { text-align:right; font-variant-numeric:tabular-nums; }
code, .mono { font-family:ui-monospace,Menlo,Consolas,monospace; font-size:12px; overflow-wrap:anywhere; }
.gaps li, .bad { color:var(--bad); }
.ok { color:var(--good); }
.warning { color:var(--warn); }
.plot { display:flex; flex-wrap:wrap; gap:24px; align-items:flex-start; }
.plot > div { flex:1; min-width:260px; }
#hemisphere, .error-plot { background:var(--card); border:1px solid var(--line); border-radius:6px; max-width:100%; height:auto; }
#hemisphere .grid, .error-plot .grid { fill:none; stroke:#c9c9d0; stroke-width:1; }
#hemisphere .raking, .error-plot .raking { stroke:#b3261e; stroke-dasharray:4 3; }
#hemisphere .gap { fill:#b3261e; fill-opacity:.10; stroke:none; }
#hemisphere .axis, .error-plot .axis { font-size:11px; fill:var(--muted); }
#hemisphere .axis.elevation, .error-plot .axis.elevation { fill:var(--accent); font-style:italic; }
#hemisphere .light, .error-plot .error-light { stroke:#222; stroke-width:1; }
.difference-images { display:grid; grid-template-columns:minmax(0, 1fr); gap:16px; margin-top:10px; }
figure.difference img { width:100%; cursor:zoom-in; }
figure.difference.full-size { overflow-x:auto; }
figure.difference.full-size img { width:auto; max-width:none; cursor:zoom-out; }
ol.timeline { list-style:none; padding:0; margin:0; border-left:3px solid var(--line); }
ol.timeline > li { position:relative; margin:0 0 18px 0; padding-left:18px; }
ol.timeline > li::before { content:""; position:absolute; left:-9px; top:6px; width:15px; height:15px; border-radius:50%; background:var(--card); border:3px solid #5b6bd6; }
ol.timeline > li.failed::before { border-color:var(--bad); }
.step-head { font-weight:600; }
.intervention { border-left:3px solid var(--warn); background:#fff8e6; padding:4px 8px; margin:6px 0; }
.relight { display:flex; flex-wrap:wrap; gap:16px 24px; align-items:flex-start; }
.relight-view { min-width:0; max-width:100%; }
.relight-controls { flex:1 1 240px; max-width:300px; }
.first-row { display:flex; flex-wrap:wrap; column-gap:40px; align-items:flex-start; }
.first-row > section { flex:1 1 560px; min-width:0; max-width:100%; }
.first-row > #relight { flex:1 1 auto; }
#relight-canvas { display:block; max-width:100%; height:auto; border:1px solid var(--line); cursor:crosshair; touch-action:none; background:#000; }
#relight-caption { margin:4px 0 0; }
#light-pad { display:block; border:1px solid var(--line); border-radius:50%; cursor:crosshair; touch-action:none; background:var(--card); max-width:100%; }
#light-readout { font-variant-numeric:tabular-nums; margin:6px 0; }
#model-choice { display:flex; flex-wrap:wrap; gap:6px; margin-bottom:10px; }
#model-choice button { font:inherit; padding:4px 10px; border:1px solid var(--line); border-radius:4px; background:var(--card); cursor:pointer; }
#model-choice button[aria-pressed="true"] { background:var(--accent); color:#fff; border-color:var(--accent); }
details { margin:6px 0; }
footer { padding:8px 24px 24px; max-width:1680px; margin:0 auto; }
summary { cursor:pointer; color:var(--accent); }
.columns { display:grid; grid-template-columns:repeat(auto-fit, minmax(360px, 1fr)); gap:0 32px; }
.colour-chart { display:grid; grid-template-columns:repeat(6, minmax(0, 1fr)); gap:6px; list-style:none; padding:8px; margin:8px 0; max-width:780px; background:#2b2b2e; border-radius:6px; }
.colour-chart .patch { background:var(--card); border-radius:4px; padding:4px; font-size:12px; line-height:1.3; min-width:0; }
.patch-swatches { display:flex; gap:2px; height:44px; border-radius:3px; overflow:hidden; }
.patch-swatches > span { flex:2; }
.patch-swatches > .as-shot { flex:1; }
.patch-swatches > .unmeasured { display:flex; align-items:center; justify-content:center; color:var(--muted); background:repeating-linear-gradient(45deg, #eee 0 4px, #fff 4px 8px); font-size:11px; text-align:center; }
.patch-name, .patch-de { display:block; overflow-wrap:anywhere; }
.patch-de { font-variant-numeric:tabular-nums; color:var(--muted); }
)CSS";

const char* const kPageErrorsJs = R"JS(
(function () {
  "use strict";
  var errors = [];
  function record(message) {
    errors.push(String(message));
    document.body.setAttribute("data-errors", errors.join(" | "));
  }
  window.addEventListener("error", function (e) { record(e.message || "script error"); });
  window.addEventListener("unhandledrejection", function (e) {
    record(e.reason && e.reason.message || String(e.reason));
  });
  var originalConsoleError = console.error;
  console.error = function () {
    record(Array.prototype.join.call(arguments, " "));
    return originalConsoleError.apply(console, arguments);
  };
  window.surrogateRecordError = record;
})();
)JS";

const char* const kReportJs = R"JS(
(function () {
  "use strict";
  var body = document.body;
  var record = window.surrogateRecordError;

  function decodeBase64(text) {
    var bin = atob(text), out = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  }
  // As the C++ renderer's toSample: clamp to 0..255, then round half away from zero.
  function sample(v) { return v <= 0 ? 0 : v >= 255 ? 255 : Math.round(v); }
  var degree = Math.PI / 180;

  // A light in the hemisphere plot's angles (azimuth -180..180, 0 right, 90 up; elevation 0 at
  // grazing, 90 on the camera's axis) as a unit vector x right, y up, z towards the camera.
  function lightVector(light) {
    var a = light.azimuth * degree, e = light.elevation * degree;
    return [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  }

  // The HSH basis of src/fit/basis.cpp (hshBasis), term for term, theta clamped the same way.
  function hshBasis(l, terms) {
    var n = Math.sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    var z = n > 0 ? Math.min(1, Math.max(-1, l[2] / n)) : 1;
    var theta = Math.min(Math.acos(z), 1.5607963267948966), phi = Math.atan2(l[1], l[0]);
    var pi = Math.PI, c = Math.cos(theta), s = Math.sqrt(c - c * c), t = 2 * c - 1;
    var cp = Math.cos(phi), sp = Math.sin(phi), c2p = Math.cos(2 * phi), s2p = Math.sin(2 * phi);
    var s3 = Math.pow(c - c * c, 1.5);
    var h = [1 / Math.sqrt(2 * pi), Math.sqrt(6 / pi) * cp * s, Math.sqrt(3 / (2 * pi)) * t,
             Math.sqrt(6 / pi) * sp * s, Math.sqrt(30 / pi) * c2p * (c * c - c),
             Math.sqrt(30 / pi) * cp * t * s, Math.sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1),
             Math.sqrt(30 / pi) * sp * t * s, Math.sqrt(30 / pi) * s2p * (c * c - c),
             2 * Math.sqrt(35 / pi) * Math.cos(3 * phi) * s3,
             Math.sqrt(210 / pi) * c2p * t * (c * c - c),
             2 * Math.sqrt(21 / pi) * cp * s * (5 * c * c - 5 * c + 1),
             Math.sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1),
             2 * Math.sqrt(21 / pi) * sp * s * (5 * c * c - 5 * c + 1),
             Math.sqrt(210 / pi) * s2p * t * (c * c - c),
             2 * Math.sqrt(35 / pi) * Math.sin(3 * phi) * s3];
    return h.slice(0, terms);
  }

  // A model of the page's relight-data (report/embed.h) with render(light, rgba pixels), the
  // same formulas as src/fit/render.cpp:
  //   PTM LRGB: out_c = C_c * L(lx, ly) / 255; RGB: out_c = L_c(lx, ly);
  //   L = a0 lx^2 + a1 ly^2 + a2 lx ly + a3 lx + a4 ly + a5, a_k = (byte - bias_k) * scale_k;
  //   HSH: out_c = 255 * sum_k (byte / 255 * scale_k + bias_k) H_k(theta, phi).
  // A learned model's weights at light l as src/fit/learned_render.cpp (learnedLightWeights)
  // and OpenLIME compute them: the nodes' weights (rbf: exp(-eps d^2) normalised, eps = 8 / the
  // exp(-2 d)-weighted mean distance; bln: bilinear on the rotated octahedral map), then per
  // plane and channel the weighted basis values, summed in float as a Float32Array does.
  function learnedWeights(m, basisBytes, l) {
    var norm = Math.hypot(l[0], l[1], l[2]), x = l[0] / norm, y = l[1] / norm, z = l[2] / norm, nodes = [];
    if (m.basis === "rbf") {
      var count = m.nodes.length / 3, d = [], num = 0, den = 0, total = 0;
      for (var i = 0; i < count; ++i) {
        var dx = m.nodes[3 * i] - x, dy = m.nodes[3 * i + 1] - y, dz = m.nodes[3 * i + 2] - z;
        d.push(Math.sqrt(dx * dx + dy * dy + dz * dz));
        var e = Math.exp(-2 * d[i]); num += d[i] * e; den += e;
      }
      var eps = 8 / (num / den);
      for (var j = 0; j < count; ++j) { nodes.push([j, Math.exp(-eps * d[j] * d[j])]); total += nodes[j][1]; }
      nodes.forEach(function (nw) { nw[1] /= total; });
    } else {
      var R = m.resolution, s = Math.abs(x) + Math.abs(y) + Math.abs(z);
      var u = ((x + y) / s + 1) / 2 * (R - 1), v = ((y - x) / s + 1) / 2 * (R - 1);
      var sx = Math.min(R - 2, Math.max(0, Math.floor(u))), sy = Math.min(R - 2, Math.max(0, Math.floor(v)));
      var fx = u - sx, fy = v - sy;
      nodes = [[sx + sy * R, (1 - fx) * (1 - fy)], [sx + 1 + sy * R, fx * (1 - fy)],
               [sx + (sy + 1) * R, (1 - fx) * fy], [sx + 1 + (sy + 1) * R, fx * fy]];
    }
    var count = m.basis === "rbf" ? m.nodes.length / 3 : m.resolution * m.resolution;
    var W = new Float32Array((m.planes + 1) * 3), f = Math.fround;
    for (var p = 0; p <= m.planes; ++p)
      for (var k = 0; k < 3; ++k) {
        var sum = 0;
        nodes.forEach(function (nw) {
          var b = basisBytes[(p * count + nw[0]) * 3 + k];
          var value = p === 0 ? f(b / 255) : f(f(b - 127) / m.range[p - 1]);
          sum = f(sum + f(f(nw[1]) * value));
        });
        W[p * 3 + k] = sum;
      }
    return W;
  }

  function makeModel(m) {
    var w = m.width, h = m.height, n = w * h, coef = decodeBase64(m.coefficients);
    if (m.model === "learned") {
      var basisBytes = decodeBase64(m.basisBytes), P = m.planes;
      if (coef.length !== n * P) throw new Error("learned relighting data has the wrong size");
      return { m: m, render: function (l, px) {
        // out_k = W_0k + sum_p W_(p+1)k (byte_p / 255 - bias_p) scale_p, clamped to 0..1.
        var W = learnedWeights(m, basisBytes, l), a = new Float32Array(P * 3), base = [W[0], W[1], W[2]];
        for (var k = 0; k < 3; ++k)
          for (var p = 0; p < P; ++p) {
            a[p * 3 + k] = W[(p + 1) * 3 + k] * m.scale[p] / 255;
            base[k] -= W[(p + 1) * 3 + k] * m.bias[p] * m.scale[p];
          }
        for (var t = 0; t < n; ++t) {
          for (var c = 0; c < 3; ++c) {
            var v = base[c], o = t * P;
            for (var q = 0; q < P; ++q) v += a[q * 3 + c] * coef[o + q];
            px[t * 4 + c] = sample(Math.min(1, Math.max(0, v)) * 255);
          }
          px[t * 4 + 3] = 255;
        }
      } };
    }
    if (m.model === "hsh") {
      if (coef.length !== n * 3 * m.terms) throw new Error("HSH relighting data has the wrong size");
      return { m: m, render: function (l, px) {
        var H = hshBasis(l, m.terms), terms = m.terms, weight = [], offset = 0;
        for (var k = 0; k < terms; ++k) { weight.push(m.scale[k] * H[k]); offset += m.bias[k] * H[k]; }
        for (var t = 0; t < n; ++t) {
          for (var c = 0; c < 3; ++c) {
            var base = (t * 3 + c) * terms, v = offset * 255;
            for (var q = 0; q < terms; ++q) v += coef[base + q] * weight[q];
            px[t * 4 + c] = sample(v);
          }
          px[t * 4 + 3] = 255;
        }
      } };
    }
    var channels = m.format === "rgb" ? 3 : 1, rgb = decodeBase64(m.rgb);
    if (coef.length !== n * 6 * channels || (channels === 1 && rgb.length !== n * 3))
      throw new Error("PTM relighting data has the wrong size");
    return { m: m, render: function (l, px) {
      var u = l[0], v = l[1], s = m.scale, b = m.bias;
      var wk = [s[0] * u * u, s[1] * v * v, s[2] * u * v, s[3] * u, s[4] * v, s[5]];
      var bk = 0;
      for (var k = 0; k < 6; ++k) bk += b[k] * wk[k];
      function evaluate(i) {
        return coef[i] * wk[0] + coef[i + 1] * wk[1] + coef[i + 2] * wk[2] + coef[i + 3] * wk[3] +
               coef[i + 4] * wk[4] + coef[i + 5] * wk[5] - bk;
      }
      for (var t = 0; t < n; ++t) {
        if (channels === 1) {
          var lum = evaluate(t * 6);
          for (var c = 0; c < 3; ++c) px[t * 4 + c] = sample(rgb[t * 3 + c] * lum / 255);
        } else {
          for (var d = 0; d < 3; ++d) px[t * 4 + d] = sample(evaluate((d * n + t) * 6));
        }
        px[t * 4 + 3] = 255;
      }
    } };
  }

  // "#model=1&light=x,y,z" (or azimuth=..&elevation=..) chooses the first view: for links and tests.
  function hashSettings() {
    var out = {};
    location.hash.replace(/^#/, "").split("&").forEach(function (part) {
      var kv = part.split("=");
      if (kv.length === 2) out[kv[0]] = decodeURIComponent(kv[1]);
    });
    return out;
  }

  function setUpRelight() {
    var dataElement = document.getElementById("relight-data");
    var canvas = document.getElementById("relight-canvas");
    var pad = document.getElementById("light-pad");
    if (!dataElement || !canvas || !pad) { body.setAttribute("data-relight", "absent"); return; }
    var models = JSON.parse(dataElement.textContent).map(makeModel);
    var readout = document.getElementById("light-readout");
    var caption = document.getElementById("relight-caption");
    var context = canvas.getContext("2d");
    var light = { azimuth: 45, elevation: 45 }, current = null, picture = null, pending = false;
    // A direction "x,y,z" as the view's angles (unchanged when it has no length).
    function fromDirection(text) {
      var l = text.split(",").map(Number), norm = Math.hypot(l[0], l[1], l[2]);
      if (norm > 0) light = { azimuth: Math.atan2(l[1], l[0]) / degree, elevation: Math.asin(l[2] / norm) / degree };
    }
    // First the captured lights' mean direction (report/relight_section.h), inside the range
    // the model was fitted on; the page's address may name another.
    if (canvas.getAttribute("data-start-light")) fromDirection(canvas.getAttribute("data-start-light"));
    var settings = hashSettings();
    if (settings.light) fromDirection(settings.light);
    if (settings.azimuth) light.azimuth = Number(settings.azimuth);
    if (settings.elevation) light.elevation = Number(settings.elevation);

    function draw() {
      pending = false;
      current.render(lightVector(light), picture.data);
      context.putImageData(picture, 0, 0);
      drawPad();
      readout.textContent = "Light: azimuth " + light.azimuth.toFixed(1) + "\u00b0, elevation " +
                            light.elevation.toFixed(1) + "\u00b0";
    }
    function redraw() {
      if (!pending) { pending = true; requestAnimationFrame(draw); }
    }
    function choose(index) {
      current = models[index];
      var m = current.m;
      canvas.width = m.width; canvas.height = m.height;
      picture = context.createImageData(m.width, m.height);
      caption.textContent = m.basis.toUpperCase() + " model, " + m.width + "\u00d7" + m.height +
          (m.width !== m.originalWidth ? " (a copy of the " + m.originalWidth + "\u00d7" + m.originalHeight + " model)"
                                       : " (the model's own resolution)");
      body.setAttribute("data-relight-model", m.basis);
      Array.prototype.forEach.call(document.querySelectorAll("#model-choice button"), function (b) {
        b.setAttribute("aria-pressed", String(Number(b.getAttribute("data-model")) === index));
      });
      draw();
    }
    // The disc: the hemisphere plot's projection, radius = R (90 - elevation) / 90.
    function padGeometry() { return { cx: pad.width / 2, cy: pad.height / 2, r: pad.width / 2 - 34 }; }
    function drawPad() {
      var g = pad.getContext("2d"), p = padGeometry();
      g.clearRect(0, 0, pad.width, pad.height);
      g.lineWidth = 1; g.strokeStyle = "#c9c9d0"; g.font = "11px system-ui, sans-serif";
      g.textAlign = "center"; g.textBaseline = "middle";
      [0, 30, 60].forEach(function (e) {
        var r = p.r * (90 - e) / 90;
        g.beginPath(); g.arc(p.cx, p.cy, r, 0, 2 * Math.PI); g.stroke();
        var a = 112.5 * degree;
        g.fillStyle = "#3446b8";
        g.fillText("el " + e + "\u00b0", p.cx + r * Math.cos(a), p.cy - r * Math.sin(a) + 8);
      });
      [0, 90, 180, -90].forEach(function (a) {
        var x = p.cx + (p.r + 17) * Math.cos(a * degree), y = p.cy - (p.r + 10) * Math.sin(a * degree);
        g.beginPath(); g.moveTo(p.cx, p.cy);
        g.lineTo(p.cx + p.r * Math.cos(a * degree), p.cy - p.r * Math.sin(a * degree)); g.stroke();
        g.fillStyle = "#62636a";
        g.fillText((a === 90 ? "" : a === -90 ? "\u2212" : "") + Math.abs(a) + "\u00b0", x, y);
      });
      var r = p.r * (90 - light.elevation) / 90, a = light.azimuth * degree;
      g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
      g.beginPath(); g.arc(p.cx + r * Math.cos(a), p.cy - r * Math.sin(a), 7, 0, 2 * Math.PI); g.fill(); g.stroke();
    }
    // A pointer on the disc, or on the picture taken as the same disc round its centre.
    function setFrom(element, event) {
      var box = element.getBoundingClientRect(), p = padGeometry();
      var scale = element === pad ? pad.width / box.width : 1;
      var radius = element === pad ? p.r / scale : Math.min(box.width, box.height) / 2;
      var dx = event.clientX - (box.left + box.width / 2), dy = event.clientY - (box.top + box.height / 2);
      var f = Math.min(1, Math.sqrt(dx * dx + dy * dy) / radius);
      light.elevation = 90 * (1 - f);
      light.azimuth = f > 0 ? Math.atan2(-dy, dx) / degree : light.azimuth;
      redraw();
    }
    [canvas, pad].forEach(function (element) {
      var dragging = false;
      element.addEventListener("pointerdown", function (e) {
        dragging = true; element.setPointerCapture(e.pointerId); setFrom(element, e);
      });
      element.addEventListener("pointermove", function (e) { if (dragging) setFrom(element, e); });
      element.addEventListener("pointerup", function () { dragging = false; });
    });
    Array.prototype.forEach.call(document.querySelectorAll("#model-choice button"), function (b) {
      b.addEventListener("click", function () { choose(Number(b.getAttribute("data-model"))); });
    });
    var first = Math.min(models.length - 1, Math.max(0, Number(settings.model || 0)));
    choose(first);
    recordRendering(picture, current.m, light);
    body.setAttribute("data-relight-models", models.map(function (m) { return m.m.basis; }).join(" "));
    body.setAttribute("data-relight", "rendered");
  }

  // For tests and for people checking the page: the mean (0..255) of the first rendering, its
  // light ("azimuth,elevation" in degrees) and its pixels at the centres of a 3x3 grid
  // ("x,y:r,g,b;...").
  function recordRendering(picture, m, light) {
    var d = picture.data, sum = 0;
    for (var i = 0; i < d.length; i += 4) sum += d[i] + d[i + 1] + d[i + 2];
    body.setAttribute("data-relight-mean", (sum / (3 * m.width * m.height)).toFixed(3));
    body.setAttribute("data-relight-light", light.azimuth.toFixed(1) + "," + light.elevation.toFixed(1));
    var probes = [];
    for (var j = 0; j < 3; ++j) {
      for (var k = 0; k < 3; ++k) {
        var x = Math.floor(m.width * (2 * k + 1) / 6), y = Math.floor(m.height * (2 * j + 1) / 6), t = (y * m.width + x) * 4;
        probes.push(x + "," + y + ":" + d[t] + "," + d[t + 1] + "," + d[t + 2]);
      }
    }
    body.setAttribute("data-relight-probes", probes.join(";"));
  }

  // Where the page lays things out, for the layout test: the viewport, the viewer's place and
  // any element reaching past the viewport's edges (scrolling boxes count, not their content).
  function recordLayout() {
    var width = document.documentElement.clientWidth, outside = [];
    (function check(element) {
      var box = element.getBoundingClientRect();
      if (box.width > 0 && (box.right > width + 0.5 || box.left < -0.5) && outside.length < 5)
        outside.push(element.tagName.toLowerCase() + (element.id ? "#" + element.id : "") +
                     (element.className && typeof element.className === "string" ? "." + element.className.split(" ")[0] : ""));
      if (getComputedStyle(element).overflowX !== "visible") return;
      for (var i = 0; i < element.children.length; ++i) check(element.children[i]);
    })(body);
    body.setAttribute("data-viewport", window.innerWidth + "x" + window.innerHeight);
    body.setAttribute("data-page-width", String(document.documentElement.scrollWidth));
    body.setAttribute("data-outside", outside.join(" "));
    var viewer = document.getElementById("relight-canvas");
    if (viewer) {
      var v = viewer.getBoundingClientRect();
      body.setAttribute("data-viewer-top", String(Math.round(v.top + window.scrollY)));
      body.setAttribute("data-viewer-bottom", String(Math.round(v.bottom + window.scrollY)));
      body.setAttribute("data-viewer-width", String(Math.round(v.width)));
    }
  }

  try {
    setUpRelight();
  } catch (e) {
    record("relighting: " + e.message);
  }
  // The audit's difference pictures: a click shows one at its own size (scrolled within its
  // frame), another click at the column's width again.
  Array.prototype.forEach.call(document.querySelectorAll("figure.difference img"), function (img) {
    img.addEventListener("click", function () { img.parentNode.classList.toggle("full-size"); });
  });
  var plotted = document.querySelectorAll("#hemisphere circle.light").length;
  body.setAttribute("data-lights-plotted", String(plotted));
  recordLayout();
  window.addEventListener("resize", recordLayout);
  body.setAttribute("data-ready", "yes");
})();
)JS";

}  // namespace surrogate::report
