// The published viewer's page, set up once viewer-data.js has given window.surrogateViewerData:
// the view chosen (relight, normals, albedo), the picture zoomed and panned (wheel, drag,
// pinch), the light moved on the disc or on the picture, and the test mode (?test), which
// records the pixels of every view on <body>. The last of the page's scripts: it uses the
// others' parts of window.surrogateViewer.
var surrogateViewer = surrogateViewer || {};
(function (viewer) {
  "use strict";
  var body = document.body, record = viewer.record, geometry = viewer.geometry, disc = viewer.disc, webgl = viewer.webgl;

  // ?light=x,y,z&view=normals&test (or after #): a first view for links, and the test mode,
  // which records the pixels of every view on <body> as PNG data URLs.
  function settings() {
    var out = {};
    (location.search + "&" + location.hash).replace(/[?#]/g, "&").split("&").forEach(function (part) {
      if (!part) return;
      var kv = part.split("=");
      out[kv[0]] = kv.length > 1 ? decodeURIComponent(kv[1]) : "";
    });
    return out;
  }

  // Zoom is canvas pixels per texel: 1 shows the whole level, kMaxZoom a texel as a block of
  // 32 x 32 canvas pixels, which is as far as there is anything more to see.
  var kMaxZoom = 32;

  function setUp(data) {
    var canvas = document.getElementById("view"), pad = document.getElementById("pad");
    var info = data.info, options = settings(), view = "relight", light = geometry.fromAngles(45, 45), draw = null;
    var camera = { zoom: 1, x: 0, y: 0 }, dragMoves = "pan";
    if (options.light) {
      var l = options.light.split(",").map(Number), n = Math.hypot(l[0], l[1], l[2]);
      if (n > 0) light = [l[0] / n, l[1] / n, l[2] / n];
    }
    if (options.view === "normals" || options.view === "albedo") view = options.view;
    canvas.width = data.width; canvas.height = data.height;
    disc.labelDisc(pad);
    document.getElementById("caption").textContent = (info.type === "ptm" ? "PTM " + info.colorspace.toUpperCase()
        : "HSH order " + Math.round(Math.sqrt(info.nplanes / 3))) + " model, " + info.width + "\u00d7" + info.height +
        (data.halvings === 0 ? "" : "; shown at " + data.width + "\u00d7" + data.height + ", halved " + data.halvings +
         (data.halvings === 1 ? " time" : " times") + (data.level >= 0 ? " (Deep Zoom level " + data.level + ")" : ""));
    function angles() { return geometry.anglesOf(light); }
    function drawPad() {
      var a = angles();
      disc.drawDisc(pad, a);
      disc.describeLight(pad, a, light);
      document.getElementById("zoom").textContent = "zoom \u00d7" + camera.zoom.toFixed(2);
    }
    var pending = false;
    function redraw() {
      if (pending || !draw) return;
      pending = true;
      requestAnimationFrame(function () { pending = false; draw(view, light, camera); drawPad(); });
    }

    // Where the canvas's pixels are on the screen: the element's box, the picture centred in it
    // at one scale (object-fit: contain).
    function frame() {
      var box = canvas.getBoundingClientRect();
      var s = Math.min(box.width / canvas.width, box.height / canvas.height);
      return { left: box.left + (box.width - canvas.width * s) / 2, top: box.top + (box.height - canvas.height * s) / 2, scale: s };
    }
    function toCanvas(clientX, clientY) {
      var f = frame();
      return [(clientX - f.left) / f.scale, (clientY - f.top) / f.scale];
    }
    // The view stays on the model: its top-left texel from 0 to the size less what is shown.
    function keepInside() {
      camera.x = Math.max(0, Math.min(data.width - data.width / camera.zoom, camera.x));
      camera.y = Math.max(0, Math.min(data.height - data.height / camera.zoom, camera.y));
    }
    // Zooms by `factor` keeping the texel under canvas point p where it is.
    function zoomAbout(p, factor) {
      var tx = camera.x + p[0] / camera.zoom, ty = camera.y + p[1] / camera.zoom;
      camera.zoom = Math.max(1, Math.min(kMaxZoom, camera.zoom * factor));
      camera.x = tx - p[0] / camera.zoom;
      camera.y = ty - p[1] / camera.zoom;
      keepInside();
      redraw();
    }
    // Moves the picture with the pointer by (dx, dy) canvas pixels.
    function panBy(dx, dy) {
      camera.x -= dx / camera.zoom;
      camera.y -= dy / camera.zoom;
      keepInside();
      redraw();
    }
    function resetView() {
      camera.zoom = 1; camera.x = 0; camera.y = 0;
      redraw();
    }

    // A pointer on the disc, or on the picture taken as the same disc round its centre.
    function setFrom(element, event) {
      var box = element.getBoundingClientRect();
      var radius = element === pad ? disc.discRadius(pad) * box.width / pad.width : Math.min(box.width, box.height) / 2;
      var dx = event.clientX - (box.left + box.width / 2), dy = event.clientY - (box.top + box.height / 2);
      light = geometry.lightAt(dx, dy, radius, angles().azimuth);
      if (view !== "relight") choose("relight");
      redraw();
    }
    function capture(element, e) {
      try { element.setPointerCapture(e.pointerId); } catch { /* a pointer already gone */ }
    }

    var padDragging = false;
    pad.addEventListener("pointerdown", function (e) { padDragging = true; capture(pad, e); setFrom(pad, e); });
    pad.addEventListener("pointermove", function (e) { if (padDragging) setFrom(pad, e); });
    pad.addEventListener("pointerup", function () { padDragging = false; });
    pad.addEventListener("pointercancel", function () { padDragging = false; });

    // On the picture: one pointer pans (or moves the light: the chosen mode, Shift the other),
    // two pointers pinch, zooming about and moving with their midpoint.
    var pointers = {}, gesture = null;
    function down() { return Object.keys(pointers); }
    canvas.addEventListener("pointerdown", function (e) {
      pointers[e.pointerId] = [e.clientX, e.clientY];
      capture(canvas, e);
      var ids = down();
      if (ids.length === 1) {
        gesture = (dragMoves === "light") !== e.shiftKey ? "light" : "pan";
        if (gesture === "light") setFrom(canvas, e);
      } else if (ids.length === 2) {
        gesture = "pinch";
      } else {
        gesture = null;
      }
      e.preventDefault();
    });
    canvas.addEventListener("pointermove", function (e) {
      var before = pointers[e.pointerId];
      if (!before) return;
      var now = [e.clientX, e.clientY];
      pointers[e.pointerId] = now;
      if (gesture === "light") {
        setFrom(canvas, e);
      } else if (gesture === "pan") {
        var s = frame().scale;
        panBy((now[0] - before[0]) / s, (now[1] - before[1]) / s);
      } else if (gesture === "pinch") {
        var ids = down(), other = pointers[ids[0] === String(e.pointerId) ? ids[1] : ids[0]];
        var was = Math.hypot(before[0] - other[0], before[1] - other[1]), is = Math.hypot(now[0] - other[0], now[1] - other[1]);
        var from = toCanvas((before[0] + other[0]) / 2, (before[1] + other[1]) / 2);
        var to = toCanvas((now[0] + other[0]) / 2, (now[1] + other[1]) / 2);
        if (was > 0 && is > 0) zoomAbout(from, is / was);
        panBy(to[0] - from[0], to[1] - from[1]);
      }
    });
    function lift(e) {
      delete pointers[e.pointerId];
      gesture = null;  // the pointer left down starts nothing until it is lifted and put down again
    }
    canvas.addEventListener("pointerup", lift);
    canvas.addEventListener("pointercancel", lift);
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      var perLine = e.deltaMode === 1 ? 40 : e.deltaMode === 2 ? 800 : 1;
      zoomAbout(toCanvas(e.clientX, e.clientY), Math.exp(-e.deltaY * perLine * 0.0015));
    }, { passive: false });
    document.getElementById("reset").addEventListener("click", resetView);
    Array.prototype.forEach.call(document.querySelectorAll("#tools button[data-drag]"), function (b) {
      b.addEventListener("click", function () {
        dragMoves = b.getAttribute("data-drag");
        canvas.classList.toggle("light", dragMoves === "light");
        Array.prototype.forEach.call(document.querySelectorAll("#tools button[data-drag]"), function (c) {
          c.setAttribute("aria-pressed", String(c === b));
        });
      });
    });

    function choose(name) {
      view = name;
      Array.prototype.forEach.call(document.querySelectorAll("#views button"), function (b) {
        b.setAttribute("aria-pressed", String(b.getAttribute("data-view") === name));
      });
      redraw();
    }
    Array.prototype.forEach.call(document.querySelectorAll("#views button"), function (b) {
      b.addEventListener("click", function () { choose(b.getAttribute("data-view")); });
    });

    var play = viewer.gestures(canvas, frame);

    var uris = data.planes.concat([data.normals, data.albedo]);
    return Promise.all(uris.map(webgl.loadPicture)).then(function (pictures) {
      draw = webgl.makeRenderer(canvas, data, pictures);
      if ("test" in options) {
        ["relight", "normals", "albedo"].forEach(function (name) {
          var shot = webgl.snapshot(draw(name, light, camera), data.width, data.height);
          body.setAttribute("data-pixels-" + name, shot.png);
          body.setAttribute("data-mean-" + name, shot.mean);
        });
        (options.gestures ? options.gestures.split(";") : []).forEach(function (step, i) {
          play(step);
          var shot = webgl.snapshot(draw("relight", light, camera), data.width, data.height);
          body.setAttribute("data-pixels-gesture-" + i, shot.png);
          body.setAttribute("data-camera-gesture-" + i, camera.zoom + " " + camera.x + " " + camera.y);
          body.setAttribute("data-light-gesture-" + i, light.join(" "));
        });
      }
      draw(view, light, camera);
      choose(view);
      drawPad();
      body.setAttribute("data-size", data.width + "x" + data.height);
      body.setAttribute("data-rendered", "yes");
    });
  }

  var data = window.surrogateViewerData;
  var done = data ? setUp(data) : Promise.reject(new Error("viewer-data.js is missing or did not load; keep it beside index.html"));
  done.catch(function (e) { record(e.message); }).then(function () { body.setAttribute("data-ready", "yes"); });
})(surrogateViewer);
