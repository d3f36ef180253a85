// The review page's sentences made from the record's state (/api/state): numbers as shown, a
// frame's doubtful highlights, its light, the colour chart the last run recorded, the help for
// each mode and the capture's line under the title. Pure functions: review_page.js puts them in
// the page, tests/web/review_words.test.js runs them in Node.
var reviewWords = (function () {
  "use strict";

  function shown(v, digits) { return v == null ? "-" : Number(v).toFixed(digits == null ? 1 : digits); }

  // What is doubtful in frame f's highlights, a line each (its thumbnail's "!" and title).
  function frameFlags(f) {
    var flags = [];
    f.highlights.forEach(function (h) {
      var doubtful = h.confidence != null && h.confidence < 0.5;
      if ((h.flag !== "ok" && h.flag !== "manual") || doubtful)
        flags.push("sphere " + (h.sphere + 1) + ": " + h.flag + (h.reason ? " \u2014 " + h.reason : ""));
    });
    return flags;
  }
  function pointsText(points) { return points.map(function (p) { return shown(p.x) + "," + shown(p.y); }).join(" "); }

  function captureLine(state) {
    return "Capture " + state.capture + " \u2014 decisions recorded as made by " + state.who +
      (state.revision === "none" ? " \u2014 not processed yet" : " \u2014 record " + state.revision.slice(7, 19));
  }
  function lightFact(light) {
    return "elevation " + shown(light.elevation) + "\u00b0, azimuth " + shown(light.azimuth) + "\u00b0" +
      (light.uncertaintyDegrees != null ? " \u00b1" + shown(light.uncertaintyDegrees) + "\u00b0 (95 %)" : "") +
      (light.rmse != null ? ", residual " + shown(light.rmse, 2) + " levels" : "");
  }
  function highlightFact(h) {
    return h.flag + (h.x != null ? " at " + shown(h.x) + ", " + shown(h.y) : "") +
      (h.confidence != null ? ", confidence " + shown(h.confidence, 2) : "") + (h.reason ? " \u2014 " + h.reason : "");
  }
  // The colour chart c as the last run recorded it (state.chart, or null).
  function chartRecorded(c) {
    if (!c) return "No colour correction is recorded yet: a run with a fit looks for a chart.";
    if (c.outcome === "corrected")
      return "The last run " + (c.method === "given" ? "took the chart as given" : "found the chart") + " in " + c.image +
        " (green outline): CIEDE2000 " + shown(c.deltaE2000MeanBefore, 2) + " before, " + shown(c.deltaE2000Mean, 2) +
        " mean and " + shown(c.deltaE2000Max, 2) + " largest after correction.";
    if (c.chart === "none") return "The last run used no colour chart (--colour-chart none): the images keep their colours.";
    return "The last run: " + (c.outcome || "no chart recorded") + ".";
  }

  // The help under the toolbar: for a `mode`, on a record at `revision`; chart mode's is given
  // (chartHelp), since it follows the corners marked.
  function modeHelp(mode, revision, chartHelpText) {
    if (mode === "none") return revision === "none"
      ? "Not processed yet: first press \u201cRun the capture\u201d (under Changes to apply); Surrogate finds the spheres and their highlights, which you can then check and correct here."
      : "No sphere circle yet: press \u201cAdd a sphere\u201d, drag the circle onto the sphere and resize it with its orange square.";
    if (mode === "sphere") return "Drag a circle to move it, its orange square to resize it. The circles are the same in every frame.";
    if (mode === "chart") return chartHelpText;
    return "Click the centre of the highlight inside a sphere's circle: it becomes this frame's highlight on that sphere.";
  }
  // Chart mode's help on frame `frameName`, with the chart marked so far (pending.chart) and the
  // corners' names in their order.
  function chartHelp(chart, frameName, corners) {
    if (chart && chart.none) return "No colour chart: the images keep their colours. Press \u201cNo colour chart\u201d again to mark one instead.";
    var n = chart && chart.image === frameName ? chart.points.length : 0;
    if (n === 4) return "The chart is marked on this frame: Reset the corners to mark it again.";
    return "Click the outer corner of the " + corners[n] + " patch (corner " + (n + 1) + " of 4). The corners go in this order: " +
      "dark skin, bluish green, black, white; the grid they span is measured in every frame.";
  }

  return { shown: shown, frameFlags: frameFlags, pointsText: pointsText, captureLine: captureLine, lightFact: lightFact,
           highlightFact: highlightFact, chartRecorded: chartRecorded, modeHelp: modeHelp, chartHelp: chartHelp };
})();
if (typeof module === "object") module.exports = reviewWords;
