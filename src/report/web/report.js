// The report page's script, its DOM side (report/page_assets.h says what it records on <body>):
// the interactive relighting view from the JSON block with id relight-data when present, the
// difference pictures' zoom, the plotted lights' count and the layout the tests read. It runs
// after page_errors.js (window.surrogateRecordError), relight_model.js and relight_view.js (the
// arithmetic, unit-tested in Node), all in the page's one script element.
/* global surrogateRelightModel, surrogateRelightView */
(function () {
  "use strict";
  var body = document.body;
  var record = window.surrogateRecordError;
  var model = surrogateRelightModel, view = surrogateRelightView;

  function setUpRelight() {
    var dataElement = document.getElementById("relight-data");
    var canvas = document.getElementById("relight-canvas");
    var pad = document.getElementById("light-pad");
    if (!dataElement || !canvas || !pad) { body.setAttribute("data-relight", "absent"); return; }
    var models = JSON.parse(dataElement.textContent).map(model.makeModel);
    var readout = document.getElementById("light-readout");
    var caption = document.getElementById("relight-caption");
    var context = canvas.getContext("2d");
    var current = null, picture = null, pending = false;
    var settings = view.parseHash(location.hash);
    var light = view.startLight(canvas.getAttribute("data-start-light"), settings);

    function draw() {
      pending = false;
      current.render(model.lightVector(light), picture.data);
      context.putImageData(picture, 0, 0);
      drawPad();
      readout.textContent = view.readoutText(light);
    }
    function redraw() {
      if (!pending) { pending = true; requestAnimationFrame(draw); }
    }
    function choose(index) {
      current = models[index];
      var m = current.m;
      canvas.width = m.width; canvas.height = m.height;
      picture = context.createImageData(m.width, m.height);
      caption.textContent = view.captionText(m);
      body.setAttribute("data-relight-model", m.basis);
      Array.prototype.forEach.call(document.querySelectorAll("#model-choice button"), function (b) {
        b.setAttribute("aria-pressed", String(Number(b.getAttribute("data-model")) === index));
      });
      draw();
    }
    function padGeometry() { return view.padGeometry(pad.width, pad.height); }
    function drawPad() {
      var g = pad.getContext("2d"), p = padGeometry(), marks = view.padMarks(p);
      g.clearRect(0, 0, pad.width, pad.height);
      g.lineWidth = 1; g.strokeStyle = "#c9c9d0"; g.font = "11px system-ui, sans-serif";
      g.textAlign = "center"; g.textBaseline = "middle";
      marks.rings.forEach(function (ring) {
        g.beginPath(); g.arc(p.cx, p.cy, ring.r, 0, 2 * Math.PI); g.stroke();
        g.fillStyle = "#3446b8";
        g.fillText(ring.label, ring.x, ring.y);
      });
      marks.spokes.forEach(function (spoke) {
        g.beginPath(); g.moveTo(p.cx, p.cy);
        g.lineTo(spoke.endX, spoke.endY); g.stroke();
        g.fillStyle = "#62636a";
        g.fillText(spoke.label, spoke.x, spoke.y);
      });
      var spot = view.lightSpot(p, light);
      g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
      g.beginPath(); g.arc(spot.x, spot.y, 7, 0, 2 * Math.PI); g.fill(); g.stroke();
    }
    // A pointer on the disc, or on the picture taken as the same disc round its centre.
    function setFrom(element, event) {
      var box = element.getBoundingClientRect(), p = padGeometry();
      var scale = element === pad ? pad.width / box.width : 1;
      var radius = element === pad ? p.r / scale : Math.min(box.width, box.height) / 2;
      var dx = event.clientX - (box.left + box.width / 2), dy = event.clientY - (box.top + box.height / 2);
      light = view.lightFromPointer(dx, dy, radius, light.azimuth);
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
    choose(view.firstModel(settings, models.length));
    var figures = view.renderingFigures(picture.data, current.m.width, current.m.height, light);
    body.setAttribute("data-relight-mean", figures.mean);
    body.setAttribute("data-relight-light", figures.light);
    body.setAttribute("data-relight-probes", figures.probes);
    body.setAttribute("data-relight-models", models.map(function (m) { return m.m.basis; }).join(" "));
    body.setAttribute("data-relight", "rendered");
  }

  // Where the page lays things out, for the layout test: the viewport, the viewer's place and
  // any element reaching past the viewport's edges (scrolling boxes count, not their content).
  function recordLayout() {
    var width = document.documentElement.clientWidth, outside = [];
    (function check(element) {
      var box = element.getBoundingClientRect();
      if (box.width > 0 && (box.right > width + 0.5 || box.left < -0.5) && outside.length < 5)
        outside.push(view.elementName(element.tagName, element.id, element.className));
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
