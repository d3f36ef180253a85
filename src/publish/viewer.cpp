#include "publish/viewer.h"

#include "core/base64.h"
#include "core/text.h"
#include "publish/viewer_parts.h"

namespace surrogate::publish {

namespace {
std::string jpegUri(const std::string& bytes) { return "\"data:image/jpeg;base64," + base64(bytes) + "\""; }

// A folder name as a relative URL's path segment: every byte but the unreserved ones of RFC
// 3986 percent-encoded (a folder named after a file may hold spaces, '#', '?' or '%').
std::string segment(const std::string& name) {
  static const char* const hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : name) {
    if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
        c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// Only a web address becomes a link: any other scheme (javascript:, data:, file:) stays text.
bool isWebAddress(const std::string& text) {
  auto startsWith = [&](const char* p) { return text.compare(0, std::char_traits<char>::length(p), p) == 0; };
  return (startsWith("https://") || startsWith("http://")) && text.find_first_of(" \t\r\n\"<>") == std::string::npos;
}

std::string shownTitle(const WebDescription& d) { return d.title.empty() ? "Relightable model" : d.title; }

// The page's head of description: title, creators with roles, rights, licence and, when
// given, the model's basis. Elements without text are left out.
std::string aboutHtml(const WebDescription& d, const std::string& basis) {
  std::string out = "<h1 id=\"title\">" + escapeHtml(shownTitle(d)) + "</h1>\n";
  if (!d.creators.empty()) {
    out += "<p id=\"creators\">By ";
    for (std::size_t i = 0; i < d.creators.size(); ++i) {
      if (i) out += "; ";
      out += "<span class=\"creator\">" + escapeHtml(d.creators[i].first);
      if (!d.creators[i].second.empty()) out += " (" + escapeHtml(d.creators[i].second) + ")";
      out += "</span>";
    }
    out += "</p>\n";
  }
  if (!d.rights.empty()) out += "<p id=\"rights\">Rights: " + escapeHtml(d.rights) + "</p>\n";
  if (!d.license.empty()) {
    out += "<p id=\"license\">Licence: ";
    out += isWebAddress(d.license) ? "<a href=\"" + escapeHtml(d.license) + "\" rel=\"license\">" + escapeHtml(d.license) + "</a>"
                                   : escapeHtml(d.license);
    out += "</p>\n";
  }
  if (!basis.empty())
    out += "<p id=\"basis\">Model: " + escapeHtml(basisLabel(basis)) + " (" + escapeHtml(basis) + ")</p>\n";
  return out;
}

void replaceOnce(std::string& text, const std::string& marker, const std::string& by) {
  text.replace(text.find(marker), marker.size(), by);
}

extern const char* const kViewerTemplate;
extern const char* const kIndexTemplate;
}  // namespace

std::string basisLabel(const std::string& basis) {
  if (basis == "ptm-lrgb") return "PTM LRGB";
  if (basis == "ptm-rgb") return "PTM RGB";
  if (basis.size() == 4 && basis.compare(0, 3, "hsh") == 0 && basis[3] >= '1' && basis[3] <= '3')
    return std::string("HSH order ") + basis[3];
  if (basis == "rbf") return "RBF (learned)";
  if (basis == "bln") return "Bilinear (learned)";
  return basis;
}

std::string viewerHtml(const WebDescription& description, const std::string& basis) {
  std::string page = kViewerTemplate;
  // The disc first: the description's text, which may hold anything, comes in after it.
  replaceOnce(page, "@DISC_STYLE@", kDiscStyle);
  replaceOnce(page, "@SHADER_SCRIPT@", kShaderScript);
  replaceOnce(page, "@DISC_SCRIPT@", kDiscScript);
  replaceOnce(page, "@DISC@", discHtml(description));
  replaceOnce(page, "@TITLE@", escapeHtml(shownTitle(description) + " (" + basisLabel(basis) + ")"));
  replaceOnce(page, "@ABOUT@", aboutHtml(description, basis));
  return page;
}

std::string webIndexHtml(const WebDescription& description, const std::vector<IndexedModel>& models) {
  std::string list;
  for (const IndexedModel& m : models) {
    // A learned basis has no page of its own: this viewer draws PTM and HSH only; its folder
    // is what OpenLIME's RTI layer or relight's viewer reads.
    const bool learned = m.basis == "rbf" || m.basis == "bln";
    list += "<li><a href=\"" + segment(m.folder) + (learned ? "/info.json" : "/index.html") + "\">" +
            escapeHtml(basisLabel(m.basis)) + "</a> (" + escapeHtml(m.basis) + "), in " + escapeHtml(m.folder) + "/" +
            (learned ? " (for OpenLIME or relight's viewer)" : "") + "</li>\n";
  }
  std::string page = kIndexTemplate;
  replaceOnce(page, "@TITLE@", escapeHtml(shownTitle(description)));
  replaceOnce(page, "@ABOUT@", aboutHtml(description, ""));
  replaceOnce(page, "@MODELS@", list);
  return page;
}

std::string viewerDataJs(const ViewerData& d) {
  std::string js =
      "// Written by Surrogate's publish for index.html: the planes of info.json at the size the viewer\n"
      "// shows, the normals and the albedo, as data: URIs of JPEG images (a page opened from file://\n"
      "// cannot read the plane files themselves).\n"
      "window.surrogateViewerData = {\n\"info\": " + d.infoJson + ",\n\"width\": " + std::to_string(d.width) +
      ", \"height\": " + std::to_string(d.height) + ", \"halvings\": " + std::to_string(d.halvings) +
      ", \"level\": " + std::to_string(d.level) + ",\n\"planes\": [";
  for (std::size_t j = 0; j < d.planes.size(); ++j) js += (j ? ",\n" : "\n") + jpegUri(d.planes[j]);
  js += "],\n\"normals\": " + jpegUri(d.normals) + ",\n\"albedo\": " + jpegUri(d.albedo) + "\n};\n";
  return js;
}

namespace {
const char* const kViewerTemplate = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; script-src 'self' 'unsafe-inline'; img-src data:; style-src 'unsafe-inline'">
<title>@TITLE@</title>
<style>
:root { --ink:#1d1d22; --muted:#62636a; --line:#d6d6dc; --accent:#3446b8; --card:#fafafb; }
body { margin:0; font:15px/1.45 system-ui, sans-serif; color:var(--ink); background:#fff; }
main { display:flex; flex-wrap:wrap; gap:16px; padding:12px 16px; align-items:flex-start; }
#stage { flex:1 1 400px; min-width:0; }
#view { display:block; width:100%; height:auto; max-height:calc(100vh - 90px); object-fit:contain; background:#000;
        border:1px solid var(--line); cursor:grab; touch-action:none; }
#view.light { cursor:crosshair; }
#side { flex:0 0 260px; }
#bar { display:flex; flex-wrap:wrap; gap:6px 18px; margin:0 0 8px; align-items:center; }
#views { display:flex; gap:6px; }
#views button { font:inherit; padding:4px 10px; border:1px solid var(--line); border-radius:4px; background:var(--card); cursor:pointer; }
#views button[aria-pressed="true"] { background:var(--accent); color:#fff; border-color:var(--accent); }
#caption, #readout, #legend { color:var(--muted); margin:6px 0; font-variant-numeric:tabular-nums; }
#message { color:#a01010; }
header { padding:12px 16px 0; }
h1 { font-size:1.35em; margin:0 0 4px; }
#about p { margin:2px 0; color:var(--muted); }
#about a { color:var(--accent); }
#tools { display:flex; flex-wrap:wrap; gap:6px; align-items:center; }
#tools button { font:inherit; padding:3px 9px; border:1px solid var(--line); border-radius:4px; background:var(--card); cursor:pointer; }
#tools button[aria-pressed="true"] { background:var(--accent); color:#fff; border-color:var(--accent); }@DISC_STYLE@</style>
</head>
<body>
<header id="about">
@ABOUT@
</header>
<main>
  <div id="stage">
    <div id="bar"><div id="views" role="group" aria-label="view">
      <button type="button" data-view="relight" aria-pressed="true">Relight</button>
      <button type="button" data-view="normals" aria-pressed="false">Normals</button>
      <button type="button" data-view="albedo" aria-pressed="false">Albedo</button>
    </div><div id="tools" role="group" aria-label="picture">
      <span>Drag on the picture moves</span>
      <button type="button" data-drag="pan" aria-pressed="true">the picture</button>
      <button type="button" data-drag="light" aria-pressed="false">the light</button>
      <button type="button" id="reset">Reset zoom</button>
      <span id="zoom"></span>
    </div></div>
    <canvas id="view" width="1" height="1" aria-label="the relit model"></canvas>
    <p id="caption"></p><p id="message"></p></div>
  <div id="side">
    @DISC@    <p id="legend">Drag the disc to move the light: the centre is the camera's axis, the rim the horizon.
      On the picture: the wheel or a pinch zooms about the pointer, a drag pans (or moves the light, as
      chosen above; Shift+drag does the other). Normals: red = x (right), green = y (up), blue = z (towards you).</p>
  </div>
</main>
<script src="viewer-data.js"></script>
<script>
(function () {
  "use strict";
  var body = document.body, errors = [];
  function record(message) {
    errors.push(String(message));
    body.setAttribute("data-errors", errors.join(" | "));
    document.getElementById("message").textContent = errors.join("; ");
  }
  window.addEventListener("error", function (e) { record(e.message || "script error"); });
  var degree = Math.PI / 180;
@DISC_SCRIPT@
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

  // Unit light vector, x right, y up, z towards the camera; azimuth 0 right, 90 up.
  function fromAngles(azimuth, elevation) {
    var a = azimuth * degree, e = elevation * degree;
    return [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  }

  // The HSH functions in the order and normalisation of an .rti (docs/hrti-math.md), the polar
  // angle clamped at pi/2 - 0.01 as surrogate render does.
  function hshBasis(l, terms) {
    var theta = Math.min(Math.acos(Math.min(1, Math.max(-1, l[2]))), Math.PI / 2 - 0.01), phi = Math.atan2(l[1], l[0]);
    var pi = Math.PI, c = Math.cos(theta), s = Math.sqrt(c - c * c), t = 2 * c - 1;
    var cp = Math.cos(phi), sp = Math.sin(phi), c2p = Math.cos(2 * phi), s2p = Math.sin(2 * phi);
    var h = [1 / Math.sqrt(2 * pi), Math.sqrt(6 / pi) * cp * s, Math.sqrt(3 / (2 * pi)) * t,
             Math.sqrt(6 / pi) * sp * s, Math.sqrt(30 / pi) * c2p * (c * c - c),
             Math.sqrt(30 / pi) * cp * t * s, Math.sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1),
             Math.sqrt(30 / pi) * sp * t * s, Math.sqrt(30 / pi) * s2p * (c * c - c)];
    return h.slice(0, terms);
  }

  // Weights of the planes' coefficients for a light, in plane order: PTM 1, u, v, u^2, uv, v^2
  // with (u, v) = (lx, ly); HSH the functions above.
  function weights(info, l) {
    if (info.type === "ptm") { var u = l[0], v = l[1]; return [1, u, v, u * u, u * v, v * v]; }
    return hshBasis(l, info.nplanes / 3);
  }

@SHADER_SCRIPT@

  function compile(gl, type, source) {
    var s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("shader: " + gl.getShaderInfoLog(s));
    return s;
  }

  function makeRenderer(canvas, data, pictures) {
    var gl = canvas.getContext("webgl2", { antialias: false });
    if (!gl) throw new Error("this browser gives the page no WebGL 2; the viewer needs it");
    var info = data.info, images = data.planes.length;
    var program = gl.createProgram();
    gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertexSource));
    gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragmentSource));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error("program: " + gl.getProgramInfoLog(program));
    gl.useProgram(program);
    var buffer = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([-1, -1, 3, -1, -1, 3]), gl.STATIC_DRAW);
    var corner = gl.getAttribLocation(program, "corner");
    gl.enableVertexAttribArray(corner);
    gl.vertexAttribPointer(corner, 2, gl.FLOAT, false, 0, 0);
    // The planes are numbers, not colours: no colour conversion, no premultiplication, no flip.
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    var texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.RGBA8, data.width, data.height, pictures.length);
    pictures.forEach(function (img, layer) {
      gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, layer, data.width, data.height, 1, gl.RGBA, gl.UNSIGNED_BYTE, img);
    });
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    function u(name) { return gl.getUniformLocation(program, name); }
    var scale = [], bias = [], material = info.materials[0];
    for (var p = 0; p < 27; ++p) {
      scale.push(p < info.nplanes ? material.scale[p] : 0);
      bias.push(p < info.nplanes ? material.bias[p] : 0);
    }
    gl.uniform3fv(u("scale"), scale);
    gl.uniform3fv(u("bias"), bias);
    gl.uniform1i(u("images"), images);
    gl.uniform1i(u("lrgb"), info.colorspace === "lrgb" ? 1 : 0);
    gl.uniform1i(u("width"), data.width);
    gl.uniform1i(u("height"), data.height);
    gl.uniform1i(u("layers"), 0);
    gl.viewport(0, 0, data.width, data.height);
    return function draw(view, light, camera) {
      gl.uniform2f(u("origin"), camera.x, camera.y);
      gl.uniform1f(u("zoom"), camera.zoom);
      var w = weights(info, light);
      while (w.length < 9) w.push(0);
      gl.uniform1fv(u("w"), w);
      gl.uniform1i(u("mode"), view === "relight" ? 0 : 1);
      gl.uniform1i(u("shown"), view === "normals" ? images : images + 1);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      var problem = gl.getError();
      if (problem !== gl.NO_ERROR) throw new Error("WebGL error " + problem);
      return gl;
    };
  }

  // The canvas's pixels, rows top-first, as a PNG data URL and their mean (0..255).
  function snapshot(gl, width, height) {
    var px = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    var copy = document.createElement("canvas");
    copy.width = width; copy.height = height;
    var context = copy.getContext("2d"), picture = context.createImageData(width, height), sum = 0;
    for (var y = 0; y < height; ++y) {
      var from = (height - 1 - y) * width * 4;
      picture.data.set(px.subarray(from, from + width * 4), y * width * 4);
    }
    for (var i = 0; i < px.length; i += 4) sum += px[i] + px[i + 1] + px[i + 2];
    context.putImageData(picture, 0, 0);
    return { png: copy.toDataURL("image/png"), mean: (sum / (3 * width * height)).toFixed(3) };
  }

  function loadPicture(uri) {
    return new Promise(function (resolve, reject) {
      var img = new Image();
      img.onload = function () { resolve(img); };
      img.onerror = function () { reject(new Error("a plane of viewer-data.js could not be decoded")); };
      img.src = uri;
    });
  }

  // Zoom is canvas pixels per texel: 1 shows the whole level, kMaxZoom a texel as a block of
  // 32 x 32 canvas pixels, which is as far as there is anything more to see.
  var kMaxZoom = 32;

  function setUp(data) {
    var canvas = document.getElementById("view"), pad = document.getElementById("pad");
    var info = data.info, options = settings(), view = "relight", light = fromAngles(45, 45), draw = null;
    var camera = { zoom: 1, x: 0, y: 0 }, dragMoves = "pan";
    if (options.light) {
      var l = options.light.split(",").map(Number), n = Math.hypot(l[0], l[1], l[2]);
      if (n > 0) light = [l[0] / n, l[1] / n, l[2] / n];
    }
    if (options.view === "normals" || options.view === "albedo") view = options.view;
    canvas.width = data.width; canvas.height = data.height;
    labelDisc(pad);
    document.getElementById("caption").textContent = (info.type === "ptm" ? "PTM " + info.colorspace.toUpperCase()
        : "HSH order " + Math.round(Math.sqrt(info.nplanes / 3))) + " model, " + info.width + "\u00d7" + info.height +
        (data.halvings === 0 ? "" : "; shown at " + data.width + "\u00d7" + data.height + ", halved " + data.halvings +
         (data.halvings === 1 ? " time" : " times") + (data.level >= 0 ? " (Deep Zoom level " + data.level + ")" : ""));
    function angles() {
      return { azimuth: Math.atan2(light[1], light[0]) / degree, elevation: Math.asin(Math.max(-1, Math.min(1, light[2]))) / degree };
    }
    function drawPad() {
      var a = angles();
      drawDisc(pad, a);
      describeLight(pad, a, light);
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
      var radius = element === pad ? discRadius(pad) * box.width / pad.width : Math.min(box.width, box.height) / 2;
      var dx = event.clientX - (box.left + box.width / 2), dy = event.clientY - (box.top + box.height / 2);
      var f = Math.min(1, Math.hypot(dx, dy) / radius), a = angles();
      light = fromAngles(f > 0 ? Math.atan2(-dy, dx) / degree : a.azimuth, 90 * (1 - f));
      if (view !== "relight") choose("relight");
      redraw();
    }
    function capture(element, e) {
      try { element.setPointerCapture(e.pointerId); } catch (ignored) { /* a pointer already gone */ }
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

    // Test mode: gestures=wheel,X,Y,DY;drag,X0,Y0,X1,Y1;shiftdrag,...;pinch,X,Y,D,S;mode,light;
    // mode,pan;reset (canvas pixels) are played on the picture as the browser's own events would
    // come, in order, and the view after each is recorded as data-pixels-gesture-N with
    // data-camera-gesture-N ("zoom x y") and data-light-gesture-N ("x y z").
    function at(p) {
      var f = frame();
      return { clientX: f.left + p[0] * f.scale, clientY: f.top + p[1] * f.scale };
    }
    function pointer(type, id, p, touch, shift) {
      var c = at(p);
      canvas.dispatchEvent(new PointerEvent(type, { pointerId: id, pointerType: touch ? "touch" : "mouse", isPrimary: id === 1 || id === 11,
        clientX: c.clientX, clientY: c.clientY, buttons: type === "pointerup" ? 0 : 1, shiftKey: !!shift, bubbles: true, cancelable: true }));
    }
    function play(step) {
      var a = step.split(","), v = a.slice(1).map(Number);
      if (a[0] === "wheel") {
        var c = at([v[0], v[1]]);
        canvas.dispatchEvent(new WheelEvent("wheel", { clientX: c.clientX, clientY: c.clientY, deltaY: v[2], deltaMode: 0, bubbles: true, cancelable: true }));
      } else if (a[0] === "drag" || a[0] === "shiftdrag") {
        var shift = a[0] === "shiftdrag";
        pointer("pointerdown", 1, [v[0], v[1]], false, shift);
        pointer("pointermove", 1, [(v[0] + v[2]) / 2, (v[1] + v[3]) / 2], false, shift);
        pointer("pointermove", 1, [v[2], v[3]], false, shift);
        pointer("pointerup", 1, [v[2], v[3]], false, shift);
      } else if (a[0] === "mode") {
        document.querySelector("#tools button[data-drag=" + (a[1] === "light" ? "light" : "pan") + "]").click();
      } else if (a[0] === "pinch") {
        var d = v[2], s = v[3];
        pointer("pointerdown", 11, [v[0] - d, v[1]], true);
        pointer("pointerdown", 12, [v[0] + d, v[1]], true);
        pointer("pointermove", 11, [v[0] - d * s, v[1]], true);
        pointer("pointermove", 12, [v[0] + d * s, v[1]], true);
        pointer("pointerup", 11, [v[0] - d * s, v[1]], true);
        pointer("pointerup", 12, [v[0] + d * s, v[1]], true);
      } else if (a[0] === "reset") {
        document.getElementById("reset").click();
      } else {
        throw new Error("unknown test gesture " + a[0]);
      }
    }

    var uris = data.planes.concat([data.normals, data.albedo]);
    return Promise.all(uris.map(loadPicture)).then(function (pictures) {
      draw = makeRenderer(canvas, data, pictures);
      if ("test" in options) {
        ["relight", "normals", "albedo"].forEach(function (name) {
          var shot = snapshot(draw(name, light, camera), data.width, data.height);
          body.setAttribute("data-pixels-" + name, shot.png);
          body.setAttribute("data-mean-" + name, shot.mean);
        });
        (options.gestures ? options.gestures.split(";") : []).forEach(function (step, i) {
          play(step);
          var shot = snapshot(draw("relight", light, camera), data.width, data.height);
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
})();
</script>
</body>
</html>
)HTML";

// The index of a web copy's models: no script at all.
const char* const kIndexTemplate = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; style-src 'unsafe-inline'">
<title>@TITLE@</title>
<style>
body { margin:0; padding:12px 16px; font:15px/1.45 system-ui, sans-serif; color:#1d1d22; background:#fff; }
h1 { font-size:1.35em; margin:0 0 4px; }
#about p { margin:2px 0; color:#62636a; }
a { color:#3446b8; }
</style>
</head>
<body>
<header id="about">
@ABOUT@
</header>
<main>
<h2>Relightable models</h2>
<p>Each opens in a viewer of its own, from disk or from a web server: move the light, zoom and pan.</p>
<ul id="models">
@MODELS@</ul>
</main>
</body>
</html>
)HTML";
}  // namespace

}  // namespace surrogate::publish
