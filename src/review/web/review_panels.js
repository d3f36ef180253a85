// The review page's side panels drawn from the record's state: the light directions (the
// report's hemisphere plot, a click on a light shows its frame), the checks (a failed one can be
// accepted with a reason), the standing decisions (each withdrawn with a reason), the
// description and the last runs. review_page.js makes them with reviewPanels(page), where page
// gives the state and the changes waiting as they are at each call, and what to draw again.
/* global reviewDecisions, reviewDom */
/* exported reviewPanels */
// page: { state(), pending(), frame(), select(i), renderAll(), renderPending() }
function reviewPanels(page) {
  "use strict";
  var D = reviewDecisions, $ = reviewDom.$, el = reviewDom.el, withReason = reviewDom.withReason;

  function renderHemisphere() {
    var state = page.state(), box = $("hemisphere-box");
    // The plot is the report's own (src/report/hemisphere.cpp), every text in it escaped there.
    box.innerHTML = state.hemisphere || "";
    if (!state.hemisphere) box.appendChild(el("p", { class: "note", text: "No light directions are recorded yet." }));
    Array.prototype.forEach.call(box.querySelectorAll(".light"), function (c) {
      c.addEventListener("click", function () {
        var path = c.getAttribute("data-image");
        for (var i = 0; i < state.frames.length; ++i) if (state.frames[i].path === path) { page.select(i); return; }
      });
    });
    renderHemisphereSelection();
  }
  function renderHemisphereSelection() {
    var f = page.frame();
    Array.prototype.forEach.call($("hemisphere-box").querySelectorAll(".light"), function (c) {
      c.classList.toggle("selected", !!f && c.getAttribute("data-image") === f.path);
    });
  }


  function renderChecks() {
    var state = page.state(), pending = page.pending(), box = $("checks");
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
        cell.appendChild(withReason("Accept\u2026", "why the result is right", function (reason) { page.pending().accept[c.name] = reason; renderChecks(); page.renderPending(); }));
      var named = el("td", {}, el("code", { text: c.name }));
      if (c.on) named.appendChild(el("div", { class: "note", text: c.on }));
      table.appendChild(el("tr", { "data-check": c.name }, named,
                           el("td", { class: "status-" + c.status, text: c.status }), el("td", { text: c.detail }), cell));
    });
    box.appendChild(table);
  }

  function renderDecisions() {
    var state = page.state(), box = $("decisions");
    box.textContent = "";
    if (!state.decisions.length) { box.appendChild(el("p", { class: "note", text: "None: every step works from its defaults." })); return; }
    var ul = el("ul");
    state.decisions.forEach(function (d) {
      var li = el("li", { "data-kind": d.kind, "data-target": d.target }, d.what, el("br"),
                  el("span", { class: "note", text: "by " + d.who + ", " + d.time + ": \u201c" + d.reason + "\u201d " }));
      var forget = null;
      if (d.kind === "exclude-image") forget = function (reason) { page.pending().forgetExclusions[D.excludedFrameName(d.target)] = reason; };
      // Circles moved here would give the withdrawn circle again: dropped with it.
      if (d.kind === "manual-sphere") forget = function (reason) { page.pending().forgetSpheres[d.target] = reason; page.pending().spheres = null; };
      if (d.kind === "manual-highlight") forget = function (reason) {
        var h = D.highlightTarget(d.target);
        page.pending().forgetHighlights[d.target] = { image: h.image, sphere: h.sphere, reason: reason };
      };
      if (d.kind === "accept-check") forget = function (reason) { page.pending().forgetAccept[d.target] = reason; };
      if (forget) li.appendChild(withReason("Withdraw\u2026", "why it no longer holds", function (reason) { forget(reason); page.renderAll(); }));
      ul.appendChild(li);
    });
    box.appendChild(ul);
  }

  function renderDescription() {
    var state = page.state(), pending = page.pending();
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
    var state = page.state(), box = $("runs");
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

  return { hemisphere: renderHemisphere, hemisphereSelection: renderHemisphereSelection, checks: renderChecks,
           decisions: renderDecisions, description: renderDescription, runs: renderRuns };
}
