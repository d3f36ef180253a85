// The review page's script: the record's state (/api/state) and the changes waiting to be
// applied, drawn in the page; the frame's overlay (circles moved and resized, highlights placed,
// the colour chart's corners marked); Apply, and the record watched for other commands' changes.
// Served last in /review.js (server.cpp), after the pure functions it uses (review_decisions.js,
// review_geometry.js, review_words.js), the DOM helpers (review_dom.js) and the side panels
// (review_panels.js).
/* global reviewDecisions, reviewGeometry, reviewWords, reviewDom, reviewPanels */
(function () {
  "use strict";
  var D = reviewDecisions, G = reviewGeometry, W = reviewWords;
  var $ = reviewDom.$, el = reviewDom.el, svg = reviewDom.svg, say = reviewDom.say;
  var CHART_CORNERS = D.CHART_CORNERS, shown = W.shown;
  var body = document.body;
  var record = window.surrogateRecordError;  // report/page_assets.h, kPageErrorsJs: served first

  var state = null, current = 0, mode = "sphere", applied = 0, busy = false;
  var pending = D.emptyPending();
  var panels = reviewPanels({ state: function () { return state; }, pending: function () { return pending; }, frame: frame,
                              select: select, renderAll: renderAll, renderPending: renderPending });

  function frame() { return state.frames[current]; }
  // --- what the page holds: the spheres as they are or as moved, and the pending changes ---
  function spheres() { return pending.spheres || state.spheres; }
  function changeCount() { return D.changeCount(pending); }
  function chartMarked() { return D.chartMarked(pending); }

  // --- drawing ---
  function renderAll() {
    $("title-shown").textContent = state.header.title || "Surrogate review";
    document.title = (state.header.title || "capture") + " \u2014 Surrogate review";
    $("capture-line").textContent = W.captureLine(state);
    if (current >= state.frames.length) current = 0;
    renderThumbnails();
    renderFrame();
    panels.hemisphere();
    panels.checks();
    panels.decisions();
    panels.description();
    panels.runs();
    renderPending();
    body.setAttribute("data-revision", state.revision);
  }

  function renderThumbnails() {
    var box = $("thumbnails");
    box.textContent = "";
    state.frames.forEach(function (f, i) {
      var flags = W.frameFlags(f);
      var b = el("button", { type: "button", class: "thumb" + (f.excluded ? " excluded" : ""), "data-frame": f.name,
                             "aria-current": i === current ? "true" : "false",
                             title: f.path + (f.excluded ? " \u2014 left out: " + f.excluded.reason : "") + (flags.length ? " \u2014 " + flags.join("; ") : "") },
                 el("img", { src: f.preview, alt: "", loading: "lazy" }), f.name);
      if (flags.length) b.appendChild(el("span", { class: "badge", text: "!" }));
      if (D.pendingFor(pending, f.name)) b.appendChild(el("span", { class: "badge pending", text: "\u25cf" }));
      b.addEventListener("click", function () { select(i); });
      box.appendChild(b);
    });
  }

  function select(i) {
    current = (i + state.frames.length) % state.frames.length;
    renderThumbnails();
    renderFrame();
    panels.hemisphereSelection();
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
    $("mode-help").textContent = W.modeHelp(mode, state.revision, W.chartHelp(pending.chart, f.name, CHART_CORNERS));
  }

  function drawOverlay() {
    var o = $("overlay"), f = frame();
    o.textContent = "";
    var scale = state.frameWidth / Math.max(1, o.getBoundingClientRect().width || state.frameWidth);
    spheres().forEach(function (s, k) {
      o.appendChild(svg("circle", { class: "sphere" + (pending.spheres ? " changed" : ""), cx: s.cx, cy: s.cy, r: s.r, "data-sphere": k }));
      var at = G.sphereLabel(s, scale);
      var t = svg("text", { class: "sphere-label", x: at.x, y: at.y });
      t.textContent = "sphere " + (k + 1);
      o.appendChild(t);
      var h = G.handleSquare(s, scale);
      o.appendChild(svg("rect", { class: "handle", x: h.x, y: h.y, width: h.width, height: h.height, "data-sphere": k }));
    });
    G.highlightMarks(f, pending.highlights, D.highlightKey).forEach(function (m) {
      var r = 6 * scale;
      o.appendChild(svg("circle", { class: "highlight " + m.cls, cx: m.x, cy: m.y, r: r, "data-sphere": m.sphere }));
      o.appendChild(svg("path", { class: "highlight " + m.cls, d: G.crossPath(m, r) }));
    });
    drawChart(o, f, scale);
  }

  // --- the colour chart: the outline the last run recorded, and the corners marked here ---
  function drawChart(o, f, scale) {
    var c = state.chart;
    if (c && c.corners && c.image === f.name) {
      o.appendChild(svg("polygon", { class: "chart found", points: G.cornersPoints(c.corners) }));
      var t = svg("text", { class: "chart-label found", x: c.corners[0], y: c.corners[1] - 6 * scale });
      t.textContent = "colour chart (" + (c.method === "given" ? "given" : "found") + ")";
      o.appendChild(t);
    }
    var p = pending.chart;
    if (!p || p.none || p.image !== f.name || !p.points.length) return;
    o.appendChild(svg(p.points.length === 4 ? "polygon" : "polyline", { class: "chart pending", points: G.pointsList(p.points) }));
    p.points.forEach(function (q, i) {
      o.appendChild(svg("circle", { class: "chart-corner", cx: q.x, cy: q.y, r: 5 * scale, "data-corner": i }));
      var at = G.cornerLabel(q, scale);
      var t = svg("text", { class: "chart-label", x: at.x, y: at.y });
      t.textContent = (i + 1) + " " + CHART_CORNERS[i];
      o.appendChild(t);
    });
  }
  function chartClick(p) {
    var f = frame(), c = pending.chart;
    if (c && !c.none && c.image === f.name && c.points.length === 4) { say("All four corners are marked: Reset the corners to mark them again.", "warning"); return; }
    if (!c || c.none || c.image !== f.name) {
      if (c && !c.none) say("The corners marked on " + c.image + " are dropped: the chart is marked on one frame.", "warning");
      if (!c || c.none) pending.chartReason = "";
      c = pending.chart = { image: f.name, points: [] };
    }
    c.points.push(G.withinFrame(p, state.frameWidth, state.frameHeight));
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
    box.appendChild(el("p", { id: "chart-recorded", text: W.chartRecorded(c) }));
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
    if (f.light) row("light", W.lightFact(f.light));
    f.highlights.forEach(function (h) { row("sphere " + (h.sphere + 1), W.highlightFact(h)); });
    var c = state.chart;
    if (c && c.corners && c.image === f.name)
      row("colour chart", (c.method === "given" ? "given" : "found") + ", CIEDE2000 " + shown(c.deltaE2000Mean, 2) + " mean after correction");
    for (var k in pending.highlights) if (pending.highlights[k].image === f.name) {
      var h = pending.highlights[k];
      row("sphere " + (h.sphere + 1) + " (to apply)", "highlight at " + shown(h.x) + ", " + shown(h.y));
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
      ? "corners at " + W.pointsText(pending.chart.points)
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
  function showEquivalent() {
    if (!changeCount()) { $("equivalent").textContent = ""; return; }
    post("/api/options", D.decisions(pending, state.revision)).then(function (r) {
      $("equivalent").textContent = r.ok ? D.commandLine(state.capture, r.body.options) : r.body.message;
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
      var k = G.sphereAt(p, list);
      if (k < 0) { say("Click inside a sphere's circle: the highlight is on a sphere.", "warning"); return; }
      var f = frame();
      pending.highlights[D.highlightKey(f.name, k)] = { image: f.name, sphere: k, x: p.x, y: p.y };
      say("Highlight of " + f.name + " on sphere " + (k + 1) + " placed at " + shown(p.x) + ", " + shown(p.y) + " (apply to record it).", "");
      drawOverlay(); renderFrameFacts(); renderThumbnails(); renderPending();
      return;
    }
    var target = e.target, index = target.getAttribute && target.getAttribute("data-sphere");
    if (index == null) {
      var at = G.sphereAt(p, list);
      if (at < 0) return;
      index = String(at);
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
      drag.sphere.r = G.resized(drag, p);
    } else {
      var c = G.moved(drag, p, state.frameWidth, state.frameHeight);
      drag.sphere.cx = c.cx;
      drag.sphere.cy = c.cy;
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

  function apply() {
    var missing = D.missingReason(pending);
    if (missing) { say(missing, "warning"); return; }
    busy = true;
    renderPending();
    say("Running\u2026 the page will show the new record when the run ends.", "");
    watchProgress(true);
    post("/api/apply", D.decisions(pending, state.revision)).then(function (r) {
      watchProgress(false);
      if (r.ok) {
        pending = D.emptyPending();
        // Busy until the new record is shown: the look at the revision every few seconds would
        // otherwise take this page's own Apply for another command's change.
        return loadState().then(function () {
          busy = false;
          renderPending();
          var run = state.runs[state.runs.length - 1];
          say("Applied: " + (run ? "run " + run.id + " " + run.outcome + ". " : "") + "The same as: " + D.commandLine(state.capture, r.body.options), "ok");
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
    pending.spheres.push(G.newSphere(state.frameWidth, state.frameHeight));
    setMode("sphere");
    renderPending();
    say("A new circle is in the middle of the frame: drag it onto the sphere and resize it with its orange square.", "");
  });
  $("previous-frame").addEventListener("click", function () { select(current - 1); });
  $("next-frame").addEventListener("click", function () { select(current + 1); });
  $("apply").addEventListener("click", apply);
  $("discard").addEventListener("click", function () { pending = D.emptyPending(); renderAll(); say("Changes discarded.", ""); });
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
