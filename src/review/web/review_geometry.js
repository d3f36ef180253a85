// The review page's geometry, in the frame's pixels (the overlay's viewBox): where a click
// falls, how a dragged circle moves or grows, and where the overlay draws the circles' handles
// and labels, the highlights' crosses and the colour chart's outline. `scale` is frame pixels per
// screen pixel, so that marks keep their size on the screen whatever the frame's. Pure
// functions: review_page.js draws with them, tests/web/review_geometry.test.js runs them in Node.
var reviewGeometry = (function () {
  "use strict";

  // The first circle (index in `spheres`) that holds point p, or -1.
  function sphereAt(p, spheres) {
    for (var i = 0; i < spheres.length; ++i) if (Math.hypot(p.x - spheres[i].cx, p.y - spheres[i].cy) <= spheres[i].r) return i;
    return -1;
  }
  function clamp(v, high) { return Math.min(high, Math.max(0, v)); }
  // Point p kept within a frame of width × height.
  function withinFrame(p, width, height) { return { x: clamp(p.x, width), y: clamp(p.y, height) }; }

  // A drag that started at drag.start on a circle then at (drag.cx, drag.cy) of radius drag.r:
  // the circle's centre with the pointer at p (kept in the frame), or its radius (at least 3).
  function moved(drag, p, width, height) {
    return { cx: clamp(drag.cx + p.x - drag.start.x, width), cy: clamp(drag.cy + p.y - drag.start.y, height) };
  }
  function resized(drag, p) { return Math.max(3, Math.hypot(p.x - drag.cx, p.y - drag.cy)); }
  // The circle "Add a sphere" puts in the middle of the frame.
  function newSphere(width, height) { return { cx: width / 2, cy: height / 2, r: Math.min(width, height) / 8 }; }

  // The circle's label, above its top left; its resize handle, a square on its bottom right edge.
  function sphereLabel(s, scale) { return { x: s.cx - s.r, y: s.cy - s.r - 4 * scale }; }
  function handleSquare(s, scale) {
    var h = 7 * scale;
    return { x: s.cx + s.r * Math.SQRT1_2 - h, y: s.cy + s.r * Math.SQRT1_2 - h, width: 2 * h, height: 2 * h };
  }

  // The highlights drawn on frame f: those the record holds (flagged when doubtful) unless one
  // placed here replaces it, then those placed here ({image, sphere, x, y} by key).
  function highlightMarks(f, placed, keyOf) {
    var marks = [];
    f.highlights.forEach(function (h) {
      if (h.x == null || placed[keyOf(f.name, h.sphere)]) return;
      var flagged = (h.flag !== "ok" && h.flag !== "manual" && h.flag !== "multiple") || (h.confidence != null && h.confidence < 0.5);
      marks.push({ x: h.x, y: h.y, cls: flagged ? "flagged" : h.flag, sphere: h.sphere });
    });
    for (var key in placed) {
      var p = placed[key];
      if (p.image === f.name) marks.push({ x: p.x, y: p.y, cls: "pending", sphere: p.sphere });
    }
    return marks;
  }
  // A highlight's cross around its ring of radius r: four strokes, from 2r to r off the centre.
  function crossPath(m, r) {
    return "M" + (m.x - 2 * r) + " " + m.y + "h" + r + "m" + 2 * r + " 0h" + r +
           "M" + m.x + " " + (m.y - 2 * r) + "v" + r + "m0 " + 2 * r + "v" + r;
  }

  // An SVG points list: of the recorded chart's corners [x0, y0, ... x3, y3], or of points {x, y}.
  function cornersPoints(corners) {
    return [0, 1, 2, 3].map(function (i) { return corners[2 * i] + "," + corners[2 * i + 1]; }).join(" ");
  }
  function pointsList(points) { return points.map(function (q) { return q.x + "," + q.y; }).join(" "); }
  // A marked corner's label, up and to the right of it.
  function cornerLabel(q, scale) { return { x: q.x + 8 * scale, y: q.y - 8 * scale }; }

  return { sphereAt: sphereAt, withinFrame: withinFrame, moved: moved, resized: resized, newSphere: newSphere,
           sphereLabel: sphereLabel, handleSquare: handleSquare, highlightMarks: highlightMarks, crossPath: crossPath,
           cornersPoints: cornersPoints, pointsList: pointsList, cornerLabel: cornerLabel };
})();
if (typeof module === "object") module.exports = reviewGeometry;
