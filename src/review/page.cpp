#include "review/page.h"

#include "core/version.h"
#include "report/html.h"
#include "report/page_assets.h"

namespace surrogate::review {

std::string pageHtml() {
  return std::string("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                     "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
                     "<meta name=\"generator\" content=\"Surrogate ") +
         escapeHtml(surrogateVersion()) + R"HTML(">
<title>Surrogate review</title><link rel="icon" href="data:,"><link rel="stylesheet" href="/review.css"></head>
<body>
<header><h1 id="title-shown">Surrogate review</h1>
<p class="note" id="capture-line">Loading the capture&hellip;</p></header>
<div id="status" role="status" aria-live="polite"></div>
<main class="review">
<section id="viewer-section">
  <h2>Frames</h2>
  <div class="toolbar" role="toolbar" aria-label="What a click on the frame does">
    <button type="button" id="mode-sphere" aria-pressed="true">Move or resize a sphere</button>
    <button type="button" id="mode-highlight" aria-pressed="false">Place this frame&rsquo;s highlight</button>
    <button type="button" id="mode-chart" aria-pressed="false">Mark the colour chart</button>
    <button type="button" id="add-sphere">Add a sphere</button>
    <span class="spacer"></span>
    <button type="button" id="previous-frame" aria-label="Previous frame">&larr;</button>
    <strong id="frame-name"></strong>
    <button type="button" id="next-frame" aria-label="Next frame">&rarr;</button>
  </div>
  <p class="note" id="mode-help"></p>
  <div id="viewer"><img id="frame-image" alt=""><svg id="overlay" xmlns="http://www.w3.org/2000/svg"></svg></div>
  <div id="frame-facts"></div>
  <div id="exclusion" class="decision-box"></div>
  <div id="chart-box" class="decision-box" hidden></div>
  <div id="thumbnails" aria-label="Every frame"></div>
</section>
<aside id="side">
  <section id="pending-section"><h2>Changes to apply</h2><div id="pending"></div>
    <p><button type="button" id="apply" class="primary" disabled>Apply</button>
       <button type="button" id="discard" disabled>Discard the changes</button></p>
    <p class="note">Apply records each change as a decision of the capture (who, when, why) and runs
      what it needs again, exactly as this command would:</p>
    <pre id="equivalent" class="mono"></pre>
    <div id="progress" hidden><progress id="progress-bar" max="1" value="0"></progress> <span id="progress-label"></span></div>
  </section>
  <section id="lights-section"><h2>Light directions</h2><div id="hemisphere-box"></div>
    <p class="note">Click a light to show its frame. Colours: the fit&rsquo;s residual on each frame, dark low, yellow high.</p></section>
  <section id="checks-section"><h2>Checks</h2><div id="checks"></div></section>
  <section id="decisions-section"><h2>Standing decisions</h2><div id="decisions"></div></section>
  <section id="description-section"><h2>Description</h2>
    <div class="form">
      <label for="field-title">Title</label><input id="field-title" type="text">
      <label for="field-rights">Rights</label><input id="field-rights" type="text" placeholder="who may do what with the capture">
      <label for="field-license">Licence (URI)</label><input id="field-license" type="text" placeholder="https://creativecommons.org/licenses/by/4.0/">
      <label for="field-creator">Add a creator</label><span><input id="field-creator" type="text" placeholder="Ana Silva:photographer"> <button type="button" id="add-creator">Add</button></span>
      <label for="field-meta-key">Add metadata</label><span><input id="field-meta-key" type="text" placeholder="key"> = <input id="field-meta-value" type="text" placeholder="value"> <button type="button" id="add-meta">Add</button></span>
    </div>
    <div id="description-shown"></div>
  </section>
  <section id="history-section"><h2>Runs</h2><div id="runs"></div>
    <p class="note">Each run&rsquo;s notes as the record keeps them (records made before December 2026 count spheres from 0).</p></section>
</aside>
</main>
<script src="/review.js"></script>
</body></html>
)HTML";
}

std::string pageCss() {
  return std::string(report::kReportCss) + R"CSS(
main.review { display:grid; grid-template-columns:minmax(0, 3fr) minmax(320px, 2fr); gap:0 32px; max-width:1800px; }
@media (max-width: 1000px) { main.review { grid-template-columns:minmax(0, 1fr); } }
#status { margin:0; padding:8px 24px; min-height:1.4em; }
#status.bad { background:#fdecea; } #status.ok { background:#e8f5ec; } #status.warning { background:#fff8e6; }
.toolbar { display:flex; flex-wrap:wrap; gap:6px; align-items:center; margin-bottom:4px; }
.toolbar .spacer { flex:1; }
button { font:inherit; padding:4px 10px; border:1px solid var(--line); border-radius:4px; background:var(--card); cursor:pointer; }
button[aria-pressed="true"], button.primary { background:var(--accent); color:#fff; border-color:var(--accent); }
button:disabled { opacity:.5; cursor:default; }
input[type=text] { font:inherit; padding:3px 6px; border:1px solid var(--line); border-radius:4px; min-width:0; }
#viewer { position:relative; display:block; line-height:0; border:1px solid var(--line); background:#000; }
#frame-image { display:block; width:100%; height:auto; }
#overlay { position:absolute; left:0; top:0; width:100%; height:100%; touch-action:none; cursor:crosshair; }
#overlay .sphere { fill:rgba(52,70,184,.08); stroke:#4cc3ff; stroke-width:2; vector-effect:non-scaling-stroke; cursor:move; }
#overlay .sphere.changed { stroke:#ffb000; stroke-dasharray:6 3; }
#overlay .handle { fill:#ffb000; stroke:#000; stroke-width:1; vector-effect:non-scaling-stroke; cursor:nwse-resize; }
#overlay .sphere-label { fill:#4cc3ff; font:bold 14px system-ui, sans-serif; }
#overlay .highlight { fill:none; stroke-width:2; vector-effect:non-scaling-stroke; }
#overlay .highlight.ok, #overlay .highlight.multiple { stroke:#37d67a; }
#overlay .highlight.manual { stroke:#4cc3ff; }
#overlay .highlight.flagged { stroke:#ff4d4f; }
#overlay .highlight.pending { stroke:#ffb000; stroke-width:3; }
#overlay .chart, #overlay .chart-corner, #overlay .chart-label { pointer-events:none; vector-effect:non-scaling-stroke; }
#overlay .chart { fill:none; stroke-width:2; }
#overlay .chart.found { stroke:#37d67a; }
#overlay .chart.pending { stroke:#ffb000; stroke-dasharray:6 3; fill:rgba(255,176,0,.08); }
#overlay .chart-corner { fill:#ffb000; stroke:#000; stroke-width:1; }
#overlay .chart-label { fill:#ffb000; font:bold 14px system-ui, sans-serif; }
#overlay .chart-label.found { fill:#37d67a; }
#thumbnails { display:grid; grid-template-columns:repeat(auto-fill, minmax(110px, 1fr)); gap:8px; margin-top:12px; }
.thumb { position:relative; padding:3px; text-align:center; font-size:12px; line-height:1.2; }
.thumb img { display:block; width:100%; height:auto; }
.thumb[aria-current="true"] { outline:3px solid var(--accent); }
.thumb.excluded img { opacity:.3; }
.thumb .badge { position:absolute; top:4px; right:4px; border-radius:8px; padding:0 5px; color:#fff; background:var(--bad); font-weight:700; }
.thumb .badge.pending { background:#b77900; right:auto; left:4px; }
.decision-box { border-left:3px solid var(--warn); background:#fff8e6; padding:6px 10px; margin:8px 0; }
.decision-box.excluded { border-color:var(--bad); background:#fdecea; }
.decision-box label { margin-right:8px; }
.form { display:grid; grid-template-columns:max-content 1fr; gap:6px 10px; align-items:center; }
#pending ul, #decisions ul { padding-left:18px; margin:4px 0; }
#pending li, #decisions li { margin:4px 0; }
#equivalent, #runs pre { white-space:pre-wrap; overflow-wrap:anywhere; }
#runs li { overflow-wrap:anywhere; }
#equivalent { background:#f0f0f3; padding:6px 8px; border-radius:4px; min-height:1.5em; }
#hemisphere-box svg { width:100%; max-width:420px; }
#hemisphere-box .light { cursor:pointer; }
#hemisphere-box .light.selected { stroke:#ff4d4f; stroke-width:3; }
.status-failed { color:var(--bad); font-weight:700; } .status-accepted { color:var(--warn); font-weight:700; } .status-passed { color:var(--good); }
.inline-reason { display:flex; gap:6px; margin-top:4px; }
.inline-reason input { flex:1; }
)CSS";
}

const char* const kReviewJs = R"JS(
(function () {
  "use strict";
  var body = document.body;
  var record = window.surrogateRecordError;  // report/page_assets.h, kPageErrorsJs: served first

  var SVG = "http://www.w3.org/2000/svg";
  // The chart's corners, in the order --colour-chart takes them (stages/colour_chart_options.h).
  var CHART_CORNERS = ["dark skin", "bluish green", "black", "white"];
  var state = null, current = 0, mode = "sphere", applied = 0, busy = false;
  var pending = emptyPending();

  function emptyPending() {
    return { spheres: null, sphereReason: "", highlightReason: "", highlights: {},
             forgetHighlights: {}, forgetSpheres: {}, exclude: {}, forgetExclusions: {}, accept: {}, forgetAccept: {},
             chart: null, chartReason: "",  // chart: {image, points: [{x, y}...]} or {none: true}
             title: "", rights: "", license: "", creators: [], meta: [] };
  }
  function $(id) { return document.getElementById(id); }
  function el(tag, attrs) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) {
      if (k === "text") e.textContent = attrs[k];
      else if (k === "onclick") e.addEventListener("click", attrs[k]);
      else e.setAttribute(k, attrs[k]);
    }
    for (var i = 2; i < arguments.length; ++i) {
      var c = arguments[i];
      if (c == null) continue;
      e.appendChild(typeof c === "string" ? document.createTextNode(c) : c);
    }
    return e;
  }
  function svg(tag, attrs) {
    var e = document.createElementNS(SVG, tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    return e;
  }
  function round1(v) { return Math.round(v * 10) / 10; }
  function shown(v, digits) { return v == null ? "-" : Number(v).toFixed(digits == null ? 1 : digits); }
  function frame() { return state.frames[current]; }
  function say(text, kind) {
    var s = $("status");
    s.textContent = text;
    s.className = kind || "";
  }

  // --- what the page holds: the spheres as they are or as moved, and the pending changes ---
  function spheres() { return pending.spheres || state.spheres; }
  function highlightKey(image, sphere) { return image + ":" + sphere; }
  function changeCount() {
    var n = (pending.spheres ? 1 : 0) + (pending.chart ? 1 : 0) + pending.creators.length + pending.meta.length;
    ["highlights", "forgetHighlights", "forgetSpheres", "exclude", "forgetExclusions", "accept", "forgetAccept"].forEach(function (k) {
      n += Object.keys(pending[k]).length;
    });
    ["title", "rights", "license"].forEach(function (k) { if (pending[k]) ++n; });
    return n;
  }

  // The decisions as the server takes them (src/review/decisions.h).
  function decisions() {
    var d = { revision: state.revision };
    ["title", "rights", "license"].forEach(function (k) { if (pending[k]) d[k] = pending[k]; });
    if (pending.creators.length) d.creators = pending.creators.slice();
    if (pending.meta.length) d.meta = pending.meta.slice();
    if (pending.spheres) d.spheres = pending.spheres.map(function (s) {
      return { cx: round1(s.cx), cy: round1(s.cy), r: round1(s.r), reason: pending.sphereReason };
    });
    function list(key, make) {
      var keys = Object.keys(pending[key]);
      if (keys.length) d[key] = keys.map(function (k) { return make(k, pending[key][k]); });
    }
    list("forgetSpheres", function (k, reason) { return { sphere: Number(k), reason: reason }; });
    list("highlights", function (k, h) { return { image: h.image, sphere: h.sphere, x: round1(h.x), y: round1(h.y), reason: pending.highlightReason }; });
    list("forgetHighlights", function (k, h) { return { image: h.image, sphere: h.sphere, reason: h.reason }; });
    // A chart still being marked (fewer than four corners) is not sent: Apply asks for the rest.
    if (pending.chart && pending.chart.none) d.chart = { none: true, reason: pending.chartReason };
    else if (chartMarked()) d.chart = { image: pending.chart.image, reason: pending.chartReason,
      corners: pending.chart.points.reduce(function (a, p) { return a.concat([round1(p.x), round1(p.y)]); }, []) };
    list("exclude", function (k, reason) { return { image: k, reason: reason }; });
    list("forgetExclusions", function (k, reason) { return { image: k, reason: reason }; });
    list("accept", function (k, reason) { return { check: k, reason: reason }; });
    list("forgetAccept", function (k, reason) { return { check: k, reason: reason }; });
    return d;
  }

  // --- drawing ---
  function renderAll() {
    $("title-shown").textContent = state.header.title || "Surrogate review";
    document.title = (state.header.title || "capture") + " \u2014 Surrogate review";
    $("capture-line").textContent = "Capture " + state.capture + " \u2014 decisions recorded as made by " + state.who +
      (state.revision === "none" ? " \u2014 not processed yet" : " \u2014 record " + state.revision.slice(7, 19));
    if (current >= state.frames.length) current = 0;
    renderThumbnails();
    renderFrame();
    renderHemisphere();
    renderChecks();
    renderDecisions();
    renderDescription();
    renderRuns();
    renderPending();
    body.setAttribute("data-revision", state.revision);
  }

  function frameFlags(f) {
    var flags = [];
    f.highlights.forEach(function (h) {
      var doubtful = h.confidence != null && h.confidence < 0.5;
      if ((h.flag !== "ok" && h.flag !== "manual") || doubtful)
        flags.push("sphere " + (h.sphere + 1) + ": " + h.flag + (h.reason ? " \u2014 " + h.reason : ""));
    });
    return flags;
  }
  function pendingFor(name) {
    var n = (pending.exclude[name] != null) + (pending.forgetExclusions[name] != null);
    for (var k in pending.highlights) if (pending.highlights[k].image === name) ++n;
    if (pending.chart && pending.chart.image === name) ++n;
    return n;
  }

  function renderThumbnails() {
    var box = $("thumbnails");
    box.textContent = "";
    state.frames.forEach(function (f, i) {
      var flags = frameFlags(f);
      var b = el("button", { type: "button", class: "thumb" + (f.excluded ? " excluded" : ""), "data-frame": f.name,
                             "aria-current": i === current ? "true" : "false",
                             title: f.path + (f.excluded ? " \u2014 left out: " + f.excluded.reason : "") + (flags.length ? " \u2014 " + flags.join("; ") : "") },
                 el("img", { src: f.preview, alt: "", loading: "lazy" }), f.name);
      if (flags.length) b.appendChild(el("span", { class: "badge", text: "!" }));
      if (pendingFor(f.name)) b.appendChild(el("span", { class: "badge pending", text: "\u25cf" }));
      b.addEventListener("click", function () { select(i); });
      box.appendChild(b);
    });
  }

  function select(i) {
    current = (i + state.frames.length) % state.frames.length;
    renderThumbnails();
    renderFrame();
    renderHemisphereSelection();
  }

  function renderFrame() {
    var f = frame();
    $("frame-name").textContent = f ? f.name : "";
    if (!f) return;
    var img = $("frame-image");
    if (img.getAttribute("src") !== f.preview) img.setAttribute("src", f.preview);
    img.setAttribute("alt", "frame " + f.name);
    img.setAttribute("width", state.frameWidth);
    img.setAttribute("height", state.frameHeight);
    var o = $("overlay");
    o.setAttribute("viewBox", "0 0 " + state.frameWidth + " " + state.frameHeight);
    o.setAttribute("preserveAspectRatio", "none");
    drawOverlay();
    renderFrameFacts();
    renderExclusion();
    renderChartBox();
    showMode();
    $("mode-help").textContent = mode === "none" ? (state.revision === "none"
        ? "Not processed yet: first press \u201cRun the capture\u201d (under Changes to apply); Surrogate finds the spheres and their highlights, which you can then check and correct here."
        : "No sphere circle yet: press \u201cAdd a sphere\u201d, drag the circle onto the sphere and resize it with its orange square.")
      : mode === "sphere"
      ? "Drag a circle to move it, its orange square to resize it. The circles are the same in every frame."
      : mode === "chart" ? chartHelp()
      : "Click the centre of the highlight inside a sphere's circle: it becomes this frame's highlight on that sphere.";
  }

  function drawOverlay() {
    var o = $("overlay"), f = frame();
    o.textContent = "";
    var scale = state.frameWidth / Math.max(1, o.getBoundingClientRect().width || state.frameWidth);
    spheres().forEach(function (s, k) {
      o.appendChild(svg("circle", { class: "sphere" + (pending.spheres ? " changed" : ""), cx: s.cx, cy: s.cy, r: s.r, "data-sphere": k }));
      var t = svg("text", { class: "sphere-label", x: s.cx - s.r, y: s.cy - s.r - 4 * scale });
      t.textContent = "sphere " + (k + 1);
      o.appendChild(t);
      var h = 7 * scale;
      o.appendChild(svg("rect", { class: "handle", x: s.cx + s.r * Math.SQRT1_2 - h, y: s.cy + s.r * Math.SQRT1_2 - h, width: 2 * h, height: 2 * h, "data-sphere": k }));
    });
    var marks = [];
    f.highlights.forEach(function (h) {
      if (h.x == null || pending.highlights[highlightKey(f.name, h.sphere)]) return;
      var flagged = (h.flag !== "ok" && h.flag !== "manual" && h.flag !== "multiple") || (h.confidence != null && h.confidence < 0.5);
      marks.push({ x: h.x, y: h.y, cls: flagged ? "flagged" : h.flag, sphere: h.sphere });
    });
    for (var key in pending.highlights) {
      var p = pending.highlights[key];
      if (p.image === f.name) marks.push({ x: p.x, y: p.y, cls: "pending", sphere: p.sphere });
    }
    marks.forEach(function (m) {
      var r = 6 * scale;
      o.appendChild(svg("circle", { class: "highlight " + m.cls, cx: m.x, cy: m.y, r: r, "data-sphere": m.sphere }));
      o.appendChild(svg("path", { class: "highlight " + m.cls, d: "M" + (m.x - 2 * r) + " " + m.y + "h" + r + "m" + 2 * r + " 0h" + r +
                                 "M" + m.x + " " + (m.y - 2 * r) + "v" + r + "m0 " + 2 * r + "v" + r }));
    });
    drawChart(o, f, scale);
  }

  // --- the colour chart: the outline the last run recorded, and the corners marked here ---
  function chartMarked() { return !!(pending.chart && !pending.chart.none && pending.chart.points.length === 4); }
  function chartPointsText(points) { return points.map(function (p) { return shown(p.x) + "," + shown(p.y); }).join(" "); }
  function drawChart(o, f, scale) {
    var c = state.chart;
    if (c && c.corners && c.image === f.name) {
      var pts = [0, 1, 2, 3].map(function (i) { return c.corners[2 * i] + "," + c.corners[2 * i + 1]; }).join(" ");
      o.appendChild(svg("polygon", { class: "chart found", points: pts }));
      var t = svg("text", { class: "chart-label found", x: c.corners[0], y: c.corners[1] - 6 * scale });
      t.textContent = "colour chart (" + (c.method === "given" ? "given" : "found") + ")";
      o.appendChild(t);
    }
    var p = pending.chart;
    if (!p || p.none || p.image !== f.name || !p.points.length) return;
    var marked = p.points.map(function (q) { return q.x + "," + q.y; }).join(" ");
    o.appendChild(svg(p.points.length === 4 ? "polygon" : "polyline", { class: "chart pending", points: marked }));
    p.points.forEach(function (q, i) {
      o.appendChild(svg("circle", { class: "chart-corner", cx: q.x, cy: q.y, r: 5 * scale, "data-corner": i }));
      var t = svg("text", { class: "chart-label", x: q.x + 8 * scale, y: q.y - 8 * scale });
      t.textContent = (i + 1) + " " + CHART_CORNERS[i];
      o.appendChild(t);
    });
  }
  function chartHelp() {
    if (pending.chart && pending.chart.none) return "No colour chart: the images keep their colours. Press \u201cNo colour chart\u201d again to mark one instead.";
    var n = pending.chart && pending.chart.image === frame().name ? pending.chart.points.length : 0;
    if (n === 4) return "The chart is marked on this frame: Reset the corners to mark it again.";
    return "Click the outer corner of the " + CHART_CORNERS[n] + " patch (corner " + (n + 1) + " of 4). The corners go in this order: " +
      "dark skin, bluish green, black, white; the grid they span is measured in every frame.";
  }
  function chartClick(p) {
    var f = frame(), c = pending.chart;
    if (c && !c.none && c.image === f.name && c.points.length === 4) { say("All four corners are marked: Reset the corners to mark them again.", "warning"); return; }
    if (!c || c.none || c.image !== f.name) {
      if (c && !c.none) say("The corners marked on " + c.image + " are dropped: the chart is marked on one frame.", "warning");
      if (!c || c.none) pending.chartReason = "";
      c = pending.chart = { image: f.name, points: [] };
    }
    c.points.push({ x: Math.min(state.frameWidth, Math.max(0, p.x)), y: Math.min(state.frameHeight, Math.max(0, p.y)) });
    var n = c.points.length;
    say("Corner " + n + " (" + CHART_CORNERS[n - 1] + ") at " + shown(p.x) + ", " + shown(p.y) +
        (n < 4 ? "; next: the " + CHART_CORNERS[n] + " patch." : ": the chart is marked (apply to record it)."), n < 4 ? "" : "ok");
    renderFrame(); renderThumbnails(); renderPending();
  }
  function renderChartBox() {
    var box = $("chart-box"), c = state.chart, f = frame();
    box.hidden = mode !== "chart";
    box.textContent = "";
    if (box.hidden) return;
    var text;
    if (!c) text = "No colour correction is recorded yet: a run with a fit looks for a chart.";
    else if (c.outcome === "corrected")
      text = "The last run " + (c.method === "given" ? "took the chart as given" : "found the chart") + " in " + c.image +
        " (green outline): CIEDE2000 " + shown(c.deltaE2000MeanBefore, 2) + " before, " + shown(c.deltaE2000Mean, 2) +
        " mean and " + shown(c.deltaE2000Max, 2) + " largest after correction.";
    else if (c.chart === "none") text = "The last run used no colour chart (--colour-chart none): the images keep their colours.";
    else text = "The last run: " + (c.outcome || "no chart recorded") + ".";
    box.appendChild(el("p", { id: "chart-recorded", text: text }));
    var where = c && (c.image || c.searched);  // the frame it was found in, or searched
    if (where && where !== f.name)
      box.appendChild(el("button", { type: "button", id: "chart-show", text: "Show " + where,
        onclick: function () { for (var i = 0; i < state.frames.length; ++i) if (state.frames[i].name === where) select(i); } }));
    var none = !!(pending.chart && pending.chart.none);
    box.appendChild(el("button", { type: "button", id: "chart-reset", text: "Reset the corners",
      onclick: function () { if (pending.chart && !pending.chart.none) pending.chart = null; renderFrame(); renderThumbnails(); renderPending(); } }));
    if (!pending.chart || pending.chart.none || !pending.chart.points.length) box.lastChild.disabled = true;
    box.appendChild(el("button", { type: "button", id: "chart-none", "aria-pressed": String(none), text: "No colour chart",
      onclick: function () {
        pending.chart = none ? null : { none: true };
        pending.chartReason = "";
        renderFrame(); renderThumbnails(); renderPending();
        if (!none) { say("Say why there is no colour chart (under Changes to apply): it is recorded with the decision.", ""); $("chart-reason").focus(); }
      } }));
  }

  function renderFrameFacts() {
    var f = frame(), box = $("frame-facts");
    box.textContent = "";
    var dl = el("dl", { class: "facts-list" });
    function row(k, v) { dl.appendChild(el("dt", { text: k })); dl.appendChild(el("dd", { text: v })); }
    row("file", f.path);
    if (f.light) row("light", "elevation " + shown(f.light.elevation) + "\u00b0, azimuth " + shown(f.light.azimuth) + "\u00b0" +
                     (f.light.uncertaintyDegrees != null ? " \u00b1" + shown(f.light.uncertaintyDegrees) + "\u00b0 (95 %)" : "") +
                     (f.light.rmse != null ? ", residual " + shown(f.light.rmse, 2) + " levels" : ""));
    f.highlights.forEach(function (h) {
      row("sphere " + (h.sphere + 1), h.flag + (h.x != null ? " at " + shown(h.x) + ", " + shown(h.y) : "") +
          (h.confidence != null ? ", confidence " + shown(h.confidence, 2) : "") + (h.reason ? " \u2014 " + h.reason : ""));
    });
    var c = state.chart;
    if (c && c.corners && c.image === f.name)
      row("colour chart", (c.method === "given" ? "given" : "found") + ", CIEDE2000 " + shown(c.deltaE2000Mean, 2) + " mean after correction");
    var p = 0;
    for (var k in pending.highlights) if (pending.highlights[k].image === f.name) {
      var h = pending.highlights[k];
      row("sphere " + (h.sphere + 1) + " (to apply)", "highlight at " + shown(h.x) + ", " + shown(h.y));
      ++p;
    }
    box.appendChild(el("div", { class: "fact" }, dl));
  }

  function renderExclusion() {
    var f = frame(), box = $("exclusion");
    box.textContent = "";
    var excluded = !!f.excluded, leaving = pending.exclude[f.name] != null, returning = pending.forgetExclusions[f.name] != null;
    box.className = "decision-box" + ((excluded && !returning) || leaving ? " excluded" : "");
    var check = el("input", { type: "checkbox", id: "exclude-frame" });
    check.checked = (excluded && !returning) || leaving;
    var reason = el("input", { type: "text", id: "exclude-reason", placeholder: excluded ? "why it comes back" : "why it is left out (needed)" });
    reason.value = leaving ? pending.exclude[f.name] : returning ? pending.forgetExclusions[f.name] : "";
    function update() {
      delete pending.exclude[f.name];
      delete pending.forgetExclusions[f.name];
      if (check.checked && !excluded) pending.exclude[f.name] = reason.value;
      if (!check.checked && excluded) pending.forgetExclusions[f.name] = reason.value;
      box.className = "decision-box" + (check.checked ? " excluded" : "");
      renderPending();
      renderThumbnails();
    }
    check.addEventListener("change", update);
    reason.addEventListener("input", update);
    box.appendChild(el("label", { for: "exclude-frame" }, check, " Leave this frame out"));
    box.appendChild(reason);
    if (excluded) box.appendChild(el("p", { class: "note", text: "Left out: \u201c" + f.excluded.reason + "\u201d, by " + f.excluded.who + ", " + f.excluded.time + "." }));
  }

  function renderHemisphere() {
    var box = $("hemisphere-box");
    // The plot is the report's own (src/report/hemisphere.cpp), every text in it escaped there.
    box.innerHTML = state.hemisphere || "";
    if (!state.hemisphere) box.appendChild(el("p", { class: "note", text: "No light directions are recorded yet." }));
    Array.prototype.forEach.call(box.querySelectorAll(".light"), function (c) {
      c.addEventListener("click", function () {
        var path = c.getAttribute("data-image");
        for (var i = 0; i < state.frames.length; ++i) if (state.frames[i].path === path) { select(i); return; }
      });
    });
    renderHemisphereSelection();
  }
  function renderHemisphereSelection() {
    var f = frame();
    Array.prototype.forEach.call($("hemisphere-box").querySelectorAll(".light"), function (c) {
      c.classList.toggle("selected", !!f && c.getAttribute("data-image") === f.path);
    });
  }

  // A button that asks for a reason before it records a change.
  function withReason(label, placeholder, done) {
    var wrap = el("span");
    var b = el("button", { type: "button", text: label });
    b.addEventListener("click", function () {
      wrap.textContent = "";
      var input = el("input", { type: "text", placeholder: placeholder });
      var ok = el("button", { type: "button", text: "OK" });
      ok.addEventListener("click", function () {
        if (!input.value.trim()) { say("Give a reason: it is recorded with the decision.", "warning"); input.focus(); return; }
        done(input.value.trim());
      });
      wrap.appendChild(el("span", { class: "inline-reason" }, input, ok));
      input.focus();
    });
    wrap.appendChild(b);
    return wrap;
  }

  function renderChecks() {
    var box = $("checks");
    box.textContent = "";
    var rows = state.checks.slice();
    state.stoppedBy.forEach(function (name) {
      if (!rows.some(function (c) { return c.name === name && c.status === "failed"; }))
        rows.push({ name: name, status: "failed", detail: "stopped the last run (see Runs)", component: "" });
    });
    if (!rows.length) { box.appendChild(el("p", { class: "note", text: "No check is recorded yet." })); return; }
    var table = el("table", {}, el("tr", {}, el("th", { text: "check" }), el("th", { text: "status" }), el("th", { text: "what it found" }), el("th", { text: "decision" })));
    rows.forEach(function (c) {
      var cell = el("td");
      if (pending.accept[c.name] != null) cell.appendChild(el("span", { text: "to accept: \u201c" + pending.accept[c.name] + "\u201d" }));
      else if (c.status === "failed")
        cell.appendChild(withReason("Accept\u2026", "why the result is right", function (reason) { pending.accept[c.name] = reason; renderChecks(); renderPending(); }));
      var named = el("td", {}, el("code", { text: c.name }));
      if (c.on) named.appendChild(el("div", { class: "note", text: c.on }));
      table.appendChild(el("tr", { "data-check": c.name }, named,
                           el("td", { class: "status-" + c.status, text: c.status }), el("td", { text: c.detail }), cell));
    });
    box.appendChild(table);
  }

  function renderDecisions() {
    var box = $("decisions");
    box.textContent = "";
    if (!state.decisions.length) { box.appendChild(el("p", { class: "note", text: "None: every step works from its defaults." })); return; }
    var ul = el("ul");
    state.decisions.forEach(function (d) {
      var li = el("li", { "data-kind": d.kind, "data-target": d.target }, d.what, el("br"),
                  el("span", { class: "note", text: "by " + d.who + ", " + d.time + ": \u201c" + d.reason + "\u201d " }));
      var forget = null;
      if (d.kind === "exclude-image") forget = function (reason) { pending.forgetExclusions[d.target.replace(/^.*\//, "").replace(/\.[^.]*$/, "")] = reason; };
      // Circles moved here would give the withdrawn circle again: dropped with it.
      if (d.kind === "manual-sphere") forget = function (reason) { pending.forgetSpheres[d.target] = reason; pending.spheres = null; };
      if (d.kind === "manual-highlight") forget = function (reason) {
        var colon = d.target.lastIndexOf(":");
        pending.forgetHighlights[d.target] = { image: d.target.slice(0, colon), sphere: Number(d.target.slice(colon + 1)), reason: reason };
      };
      if (d.kind === "accept-check") forget = function (reason) { pending.forgetAccept[d.target] = reason; };
      if (forget) li.appendChild(withReason("Withdraw\u2026", "why it no longer holds", function (reason) { forget(reason); renderAll(); }));
      ul.appendChild(li);
    });
    box.appendChild(ul);
  }

  function renderDescription() {
    ["title", "rights", "license"].forEach(function (k) {
      var input = $("field-" + k);
      if (document.activeElement !== input) input.value = pending[k] || state.header[k] || "";
    });
    var box = $("description-shown");
    box.textContent = "";
    var dl = el("dl");
    function row(k, v) { dl.appendChild(el("dt", { text: k })); dl.appendChild(el("dd", { text: v })); }
    state.header.creators.forEach(function (c) { row("creator", c.name + " (" + c.role + ")"); });
    state.header.meta.forEach(function (m) { row(m.key, m.value); });
    if (dl.childNodes.length) box.appendChild(el("div", { class: "fact" }, dl));
  }

  function renderRuns() {
    var box = $("runs");
    box.textContent = "";
    var runs = state.runs.slice(-5).reverse();
    if (!runs.length) { box.appendChild(el("p", { class: "note", text: "No run yet: Apply runs the capture for the first time." })); return; }
    var ul = el("ul");
    runs.forEach(function (r) {
      var li = el("li", { class: r.outcome === "failed" ? "bad" : "" }, r.id + " " + r.command + " by " + r.who + ", " + r.started + ": " + r.outcome);
      if (r.notes.length) li.appendChild(el("pre", { class: "mono", text: r.notes.join("\n") }));
      ul.appendChild(li);
    });
    box.appendChild(ul);
  }

  var equivalentTimer = null;
  function renderPending() {
    var box = $("pending");
    box.textContent = "";
    var ul = el("ul");
    function item(text, undo) {
      var li = el("li", {}, text + " ");
      li.appendChild(el("button", { type: "button", text: "undo", onclick: function () { undo(); renderAll(); } }));
      ul.appendChild(li);
    }
    if (pending.spheres) item("sphere circles: " + pending.spheres.map(function (s, k) {
      return (k + 1) + " at " + shown(s.cx) + ", " + shown(s.cy) + " radius " + shown(s.r);
    }).join("; "), function () { pending.spheres = null; });
    Object.keys(pending.highlights).forEach(function (k) {
      var h = pending.highlights[k];
      item("highlight of " + h.image + " on sphere " + (h.sphere + 1) + " at " + shown(h.x) + ", " + shown(h.y), function () { delete pending.highlights[k]; });
    });
    if (pending.chart && pending.chart.none) item("no colour chart (--colour-chart none)", function () { pending.chart = null; });
    else if (pending.chart) item("colour chart in " + pending.chart.image + ": " + (chartMarked()
      ? "corners at " + chartPointsText(pending.chart.points)
      : pending.chart.points.length + " of 4 corners marked, next the " + CHART_CORNERS[pending.chart.points.length] + " patch"),
      function () { pending.chart = null; });
    Object.keys(pending.exclude).forEach(function (k) { item("leave " + k + " out: \u201c" + pending.exclude[k] + "\u201d", function () { delete pending.exclude[k]; }); });
    Object.keys(pending.forgetExclusions).forEach(function (k) { item("take " + k + " back: \u201c" + pending.forgetExclusions[k] + "\u201d", function () { delete pending.forgetExclusions[k]; }); });
    Object.keys(pending.forgetSpheres).forEach(function (k) { item("withdraw the circle of sphere " + (Number(k) + 1), function () { delete pending.forgetSpheres[k]; }); });
    Object.keys(pending.forgetHighlights).forEach(function (k) { item("withdraw the highlight of " + pending.forgetHighlights[k].image + " on sphere " + (pending.forgetHighlights[k].sphere + 1), function () { delete pending.forgetHighlights[k]; }); });
    Object.keys(pending.accept).forEach(function (k) { item("accept the check " + k, function () { delete pending.accept[k]; }); });
    Object.keys(pending.forgetAccept).forEach(function (k) { item("withdraw the acceptance of " + k, function () { delete pending.forgetAccept[k]; }); });
    ["title", "rights", "license"].forEach(function (k) { if (pending[k]) item(k + ": \u201c" + pending[k] + "\u201d", function () { pending[k] = ""; }); });
    pending.creators.forEach(function (c, i) { item("creator " + c, function () { pending.creators.splice(i, 1); }); });
    pending.meta.forEach(function (m, i) { item("metadata " + m.key + " = " + m.value, function () { pending.meta.splice(i, 1); }); });
    var n = changeCount();
    if (!n) box.appendChild(el("p", { class: "note", text: "None yet." }));
    else box.appendChild(ul);
    if (pending.spheres) box.appendChild(reasonField("sphere-reason", "Why the circles are placed by hand", "sphereReason"));
    if (Object.keys(pending.highlights).length) box.appendChild(reasonField("highlight-reason", "Why the highlights are placed by hand", "highlightReason"));
    if (pending.chart) box.appendChild(reasonField("chart-reason", pending.chart.none ? "Why there is no colour chart (needed)" : "Why the chart is marked by hand", "chartReason"));
    // A capture never run can be run as it is (its first run); otherwise Apply needs a change.
    var first = state.revision === "none";
    $("apply").textContent = first && !n ? "Run the capture" : "Apply";
    $("apply").disabled = busy || (!n && !first);
    $("discard").disabled = busy || !n;
    body.setAttribute("data-pending", n);
    clearTimeout(equivalentTimer);
    equivalentTimer = setTimeout(showEquivalent, 150);
  }
  function reasonField(id, label, key) {
    var input = el("input", { type: "text", id: id, placeholder: "needed: recorded with the decision" });
    input.value = pending[key];
    input.addEventListener("input", function () { pending[key] = input.value; clearTimeout(equivalentTimer); equivalentTimer = setTimeout(showEquivalent, 300); });
    return el("p", { class: "inline-reason" }, el("label", { for: id, text: label }), input);
  }
  function quoted(a) { return /^[A-Za-z0-9_.,:=\/+-]+$/.test(a) ? a : "'" + a.replace(/'/g, "'\\''") + "'"; }
  function showEquivalent() {
    if (!changeCount()) { $("equivalent").textContent = ""; return; }
    post("/api/options", decisions()).then(function (r) {
      $("equivalent").textContent = r.ok ? "surrogate run " + quoted(state.capture) + " " + r.body.options.map(quoted).join(" ") : r.body.message;
    });
  }

  // --- the frame's pointer: spheres moved and resized, highlights placed ---
  var drag = null;
  function framePoint(e) {
    var o = $("overlay"), m = o.getScreenCTM();
    var p = new DOMPoint(e.clientX, e.clientY).matrixTransform(m.inverse());
    return { x: p.x, y: p.y };
  }
  function overlayDown(e) {
    if (busy || !state) return;
    var p = framePoint(e), list = spheres();
    if (mode === "none") return;
    if (mode === "chart") { chartClick(p); return; }
    if (mode === "highlight") {
      var k = -1;
      list.forEach(function (s, i) { if (k < 0 && Math.hypot(p.x - s.cx, p.y - s.cy) <= s.r) k = i; });
      if (k < 0) { say("Click inside a sphere's circle: the highlight is on a sphere.", "warning"); return; }
      var f = frame();
      pending.highlights[highlightKey(f.name, k)] = { image: f.name, sphere: k, x: p.x, y: p.y };
      say("Highlight of " + f.name + " on sphere " + (k + 1) + " placed at " + shown(p.x) + ", " + shown(p.y) + " (apply to record it).", "");
      drawOverlay(); renderFrameFacts(); renderThumbnails(); renderPending();
      return;
    }
    var target = e.target, index = target.getAttribute && target.getAttribute("data-sphere");
    if (index == null) {
      list.forEach(function (s, i) { if (index == null && Math.hypot(p.x - s.cx, p.y - s.cy) <= s.r) index = String(i); });
      if (index == null) return;
    }
    if (!pending.spheres) pending.spheres = state.spheres.map(function (s) { return { cx: s.cx, cy: s.cy, r: s.r }; });
    var s = pending.spheres[Number(index)];
    drag = { sphere: s, resize: target.classList.contains("handle"), start: p, cx: s.cx, cy: s.cy, r: s.r };
    $("overlay").setPointerCapture(e.pointerId);
    e.preventDefault();
  }
  function overlayMove(e) {
    if (!drag) return;
    var p = framePoint(e);
    if (drag.resize) {
      drag.sphere.r = Math.max(3, Math.hypot(p.x - drag.cx, p.y - drag.cy));
    } else {
      drag.sphere.cx = Math.min(state.frameWidth, Math.max(0, drag.cx + p.x - drag.start.x));
      drag.sphere.cy = Math.min(state.frameHeight, Math.max(0, drag.cy + p.y - drag.start.y));
    }
    drawOverlay();
  }
  function overlayUp() {
    if (!drag) return;
    drag = null;
    drawOverlay();
    renderPending();
  }

  function setMode(m) { mode = m; renderFrame(); }
  // With no circle yet (a capture never run, or no sphere found) there is nothing to drag nor to
  // click a highlight in: no mode is on, and the help says what to do first.
  function showMode() {
    var none = !spheres().length;
    if (none && mode !== "chart") mode = "none";
    else if (mode === "none") mode = "sphere";
    ["sphere", "highlight", "chart"].forEach(function (m) { $("mode-" + m).setAttribute("aria-pressed", String(mode === m)); });
    $("mode-sphere").disabled = $("mode-highlight").disabled = none;
  }

  // --- the server ---
  function post(url, data) {
    return fetch(url, { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(data) })
      .then(function (res) { return res.json().then(function (b) { return { ok: res.ok, status: res.status, body: b }; }); });
  }
  function loadState() {
    return fetch("/api/state").then(function (res) {
      return res.json().then(function (b) {
        if (!res.ok) throw new Error(b.message || "the state could not be read");
        state = b;
        renderAll();
        body.setAttribute("data-ready", "true");
      });
    });
  }

  var progressTimer = null;
  function watchProgress(on) {
    $("progress").hidden = !on;
    clearInterval(progressTimer);
    if (!on) return;
    progressTimer = setInterval(function () {
      fetch("/api/progress").then(function (r) { return r.json(); }).then(function (p) {
        if (!p.running) return;
        $("progress-bar").value = p.fraction;
        $("progress-label").textContent = p.label + " " + Math.round(p.fraction * 100) + " %";
      });
    }, 400);
  }

  function missingReason() {
    for (var k in pending.exclude) if (!pending.exclude[k].trim()) return "Say why " + k + " is left out: the reason is recorded with the decision.";
    for (var j in pending.forgetExclusions) if (!pending.forgetExclusions[j].trim()) return "Say why " + j + " comes back: the reason is recorded with the decision.";
    if (pending.chart && pending.chart.none && !pending.chartReason.trim()) return "Say why there is no colour chart: the reason is recorded with the decision.";
    // A reason is the person's: none is written for them, and a change made by hand needs one.
    if (pending.spheres && !pending.sphereReason.trim()) return "Say why the circles are placed by hand (under Changes to apply): the reason is recorded with the decision.";
    if (Object.keys(pending.highlights).length && !pending.highlightReason.trim()) return "Say why the highlights are placed by hand (under Changes to apply): the reason is recorded with the decision.";
    if (chartMarked() && !pending.chartReason.trim()) return "Say why the colour chart is marked by hand (under Changes to apply): the reason is recorded with the decision.";
    if (pending.chart && !pending.chart.none && !chartMarked())
      return "Mark the colour chart's four corners (" + pending.chart.points.length + " of 4 so far, next the " +
        CHART_CORNERS[pending.chart.points.length] + " patch), or undo it.";
    return "";
  }

  function apply() {
    var missing = missingReason();
    if (missing) { say(missing, "warning"); return; }
    busy = true;
    renderPending();
    say("Running\u2026 the page will show the new record when the run ends.", "");
    watchProgress(true);
    post("/api/apply", decisions()).then(function (r) {
      watchProgress(false);
      if (r.ok) {
        pending = emptyPending();
        // Busy until the new record is shown: the look at the revision every few seconds would
        // otherwise take this page's own Apply for another command's change.
        return loadState().then(function () {
          busy = false;
          renderPending();
          var run = state.runs[state.runs.length - 1];
          say("Applied: " + (run ? "run " + run.id + " " + run.outcome + ". " : "") + "The same as: surrogate run " + quoted(state.capture) + " " + r.body.options.map(quoted).join(" "), "ok");
          body.setAttribute("data-applied", ++applied);
        });
      }
      busy = false;
      if (r.status === 409) {
        return loadState().then(function () { say("This page was out of date: " + r.body.message + ".", "warning"); body.setAttribute("data-stale", "true"); });
      }
      if (r.status === 423) { renderPending(); say(r.body.message, "warning"); return; }
      return loadState().then(function () { say((r.status === 422 ? "The run stopped: " : "Not applied: ") + r.body.message, "bad"); });
    }).catch(function (e) {
      busy = false;
      watchProgress(false);
      renderPending();
      say("The review server did not answer (" + e.message + "); is surrogate review still running?", "bad");
    });
  }

  $("mode-sphere").addEventListener("click", function () { setMode("sphere"); });
  $("mode-highlight").addEventListener("click", function () { setMode("highlight"); });
  $("mode-chart").addEventListener("click", function () { setMode("chart"); });
  $("add-sphere").addEventListener("click", function () {
    if (!pending.spheres) pending.spheres = state.spheres.map(function (s) { return { cx: s.cx, cy: s.cy, r: s.r }; });
    pending.spheres.push({ cx: state.frameWidth / 2, cy: state.frameHeight / 2, r: Math.min(state.frameWidth, state.frameHeight) / 8 });
    setMode("sphere");
    renderPending();
    say("A new circle is in the middle of the frame: drag it onto the sphere and resize it with its orange square.", "");
  });
  $("previous-frame").addEventListener("click", function () { select(current - 1); });
  $("next-frame").addEventListener("click", function () { select(current + 1); });
  $("apply").addEventListener("click", apply);
  $("discard").addEventListener("click", function () { pending = emptyPending(); renderAll(); say("Changes discarded.", ""); });
  ["title", "rights", "license"].forEach(function (k) {
    $("field-" + k).addEventListener("input", function (e) {
      var v = e.target.value.trim();
      pending[k] = v !== (state.header[k] || "") ? v : "";
      renderPending();
    });
  });
  $("add-creator").addEventListener("click", function () {
    var v = $("field-creator").value.trim();
    if (v) { pending.creators.push(v); $("field-creator").value = ""; renderPending(); }
  });
  $("add-meta").addEventListener("click", function () {
    var k = $("field-meta-key").value.trim(), v = $("field-meta-value").value.trim();
    if (k) { pending.meta.push({ key: k, value: v }); $("field-meta-key").value = ""; $("field-meta-value").value = ""; renderPending(); }
  });
  var o = $("overlay");
  o.addEventListener("pointerdown", overlayDown);
  o.addEventListener("pointermove", overlayMove);
  o.addEventListener("pointerup", overlayUp);
  o.addEventListener("pointercancel", overlayUp);
  window.addEventListener("resize", function () { if (state) drawOverlay(); });
  document.addEventListener("keydown", function (e) {
    if (e.target.tagName === "INPUT") return;
    if (e.key === "ArrowRight") select(current + 1);
    if (e.key === "ArrowLeft") select(current - 1);
  });
  $("frame-image").addEventListener("load", function () { drawOverlay(); });

  // Another command (or page) may change the record while this page is open: it is shown as
  // soon as that is seen, the changes waiting here kept.
  setInterval(function () {
    if (busy || !state) return;
    fetch("/api/revision").then(function (r) { return r.json(); }).then(function (r) {
      if (busy || !state || r.revision === state.revision) return;
      return loadState().then(function () {
        say("The capture's record changed while this page was open (another command ran): the page shows it now." +
            (changeCount() ? " Your changes are kept: look at them, then apply." : ""), "warning");
        body.setAttribute("data-stale", "true");
      });
    }).catch(function () {});
  }, 3000);
  loadState().catch(function (e) { say("The capture could not be read: " + e.message, "bad"); record(e.message); });
})();
)JS";

}  // namespace surrogate::review
