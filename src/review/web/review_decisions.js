// The review page's changes waiting to be applied ("pending") and the decisions they become: the
// request body /api/apply and /api/options take (src/review/decisions.h), what is still missing
// before Apply, and the command line shown as the equivalent. Pure functions of their arguments:
// the page (review_page.js) holds the state, and tests/web/review_decisions.test.js runs these in
// Node. Served first of the page's own scripts (server.cpp), as the global reviewDecisions.
var reviewDecisions = (function () {
  "use strict";

  // The chart's corners, in the order --colour-chart takes them (stages/colour_chart_options.h).
  var CHART_CORNERS = ["dark skin", "bluish green", "black", "white"];

  function emptyPending() {
    return { spheres: null, sphereReason: "", highlightReason: "", highlights: {},
             forgetHighlights: {}, forgetSpheres: {}, exclude: {}, forgetExclusions: {}, accept: {}, forgetAccept: {},
             chart: null, chartReason: "",  // chart: {image, points: [{x, y}...]} or {none: true}
             title: "", rights: "", license: "", creators: [], meta: [] };
  }
  // Positions are sent to a tenth of a pixel: what the record keeps.
  function round1(v) { return Math.round(v * 10) / 10; }
  function highlightKey(image, sphere) { return image + ":" + sphere; }

  function changeCount(pending) {
    var n = (pending.spheres ? 1 : 0) + (pending.chart ? 1 : 0) + pending.creators.length + pending.meta.length;
    ["highlights", "forgetHighlights", "forgetSpheres", "exclude", "forgetExclusions", "accept", "forgetAccept"].forEach(function (k) {
      n += Object.keys(pending[k]).length;
    });
    ["title", "rights", "license"].forEach(function (k) { if (pending[k]) ++n; });
    return n;
  }
  // The changes that concern frame `name` (its thumbnail's dot).
  function pendingFor(pending, name) {
    var n = (pending.exclude[name] != null) + (pending.forgetExclusions[name] != null);
    for (var k in pending.highlights) if (pending.highlights[k].image === name) ++n;
    if (pending.chart && pending.chart.image === name) ++n;
    return n;
  }
  function chartMarked(pending) { return !!(pending.chart && !pending.chart.none && pending.chart.points.length === 4); }

  // The decisions as the server takes them (src/review/decisions.h), on the record `revision`.
  function decisions(pending, revision) {
    var d = { revision: revision };
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
    else if (chartMarked(pending)) d.chart = { image: pending.chart.image, reason: pending.chartReason,
      corners: pending.chart.points.reduce(function (a, p) { return a.concat([round1(p.x), round1(p.y)]); }, []) };
    list("exclude", function (k, reason) { return { image: k, reason: reason }; });
    list("forgetExclusions", function (k, reason) { return { image: k, reason: reason }; });
    list("accept", function (k, reason) { return { check: k, reason: reason }; });
    list("forgetAccept", function (k, reason) { return { check: k, reason: reason }; });
    return d;
  }

  // What Apply still needs, in the page's words, or "" when nothing is missing.
  function missingReason(pending) {
    for (var k in pending.exclude) if (!pending.exclude[k].trim()) return "Say why " + k + " is left out: the reason is recorded with the decision.";
    for (var j in pending.forgetExclusions) if (!pending.forgetExclusions[j].trim()) return "Say why " + j + " comes back: the reason is recorded with the decision.";
    if (pending.chart && pending.chart.none && !pending.chartReason.trim()) return "Say why there is no colour chart: the reason is recorded with the decision.";
    // A reason is the person's: none is written for them, and a change made by hand needs one.
    if (pending.spheres && !pending.sphereReason.trim()) return "Say why the circles are placed by hand (under Changes to apply): the reason is recorded with the decision.";
    if (Object.keys(pending.highlights).length && !pending.highlightReason.trim()) return "Say why the highlights are placed by hand (under Changes to apply): the reason is recorded with the decision.";
    if (chartMarked(pending) && !pending.chartReason.trim()) return "Say why the colour chart is marked by hand (under Changes to apply): the reason is recorded with the decision.";
    if (pending.chart && !pending.chart.none && !chartMarked(pending))
      return "Mark the colour chart's four corners (" + pending.chart.points.length + " of 4 so far, next the " +
        CHART_CORNERS[pending.chart.points.length] + " patch), or undo it.";
    return "";
  }

  // The frame's name an exclude-image decision's target (the image's path) stands for.
  function excludedFrameName(target) { return target.replace(/^.*\//, "").replace(/\.[^.]*$/, ""); }
  // A manual-highlight decision's target, "image:sphere" (the image's name may hold colons).
  function highlightTarget(target) {
    var colon = target.lastIndexOf(":");
    return { image: target.slice(0, colon), sphere: Number(target.slice(colon + 1)) };
  }

  // A word of a POSIX shell command line, quoted only when it needs to be.
  function quoted(a) { return /^[A-Za-z0-9_.,:=/+-]+$/.test(a) ? a : "'" + a.replace(/'/g, "'\\''") + "'"; }
  // The command that does what Apply does: `options` as /api/options or /api/apply answer them.
  function commandLine(capture, options) { return "surrogate run " + quoted(capture) + " " + options.map(quoted).join(" "); }

  return { CHART_CORNERS: CHART_CORNERS, emptyPending: emptyPending, round1: round1, highlightKey: highlightKey,
           changeCount: changeCount, pendingFor: pendingFor, chartMarked: chartMarked, decisions: decisions,
           missingReason: missingReason, excludedFrameName: excludedFrameName, highlightTarget: highlightTarget,
           quoted: quoted, commandLine: commandLine };
})();
if (typeof module === "object") module.exports = reviewDecisions;
