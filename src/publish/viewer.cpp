#include "publish/viewer.h"

#include "core/base64.h"

namespace surrogate::publish {

namespace {
std::string jpegUri(const std::string& bytes) { return "\"data:image/jpeg;base64," + base64(bytes) + "\""; }
}  // namespace

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

const char* const kViewerHtml = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; script-src 'self' 'unsafe-inline'; img-src data:; style-src 'unsafe-inline'">
<title>Relightable model</title>
<style>
:root { --ink:#1d1d22; --muted:#62636a; --line:#d6d6dc; --accent:#3446b8; --card:#fafafb; }
body { margin:0; font:15px/1.45 system-ui, sans-serif; color:var(--ink); background:#fff; }
main { display:flex; flex-wrap:wrap; gap:16px; padding:12px 16px; align-items:flex-start; }
#stage { flex:1 1 480px; min-width:0; }
#view { display:block; width:100%; height:auto; max-height:calc(100vh - 90px); object-fit:contain; background:#000;
        border:1px solid var(--line); cursor:crosshair; touch-action:none; }
#side { flex:0 0 260px; }
#pad { display:block; border:1px solid var(--line); border-radius:50%; background:var(--card); cursor:crosshair; touch-action:none; }
#views { display:flex; gap:6px; margin:0 0 10px; }
#views button { font:inherit; padding:4px 10px; border:1px solid var(--line); border-radius:4px; background:var(--card); cursor:pointer; }
#views button[aria-pressed="true"] { background:var(--accent); color:#fff; border-color:var(--accent); }
#caption, #readout, #legend { color:var(--muted); margin:6px 0; font-variant-numeric:tabular-nums; }
#message { color:#a01010; }
</style>
</head>
<body>
<main>
  <div id="stage"><canvas id="view" width="1" height="1" aria-label="the relit model"></canvas>
    <p id="caption"></p><p id="message"></p></div>
  <div id="side">
    <div id="views" role="group" aria-label="view">
      <button type="button" data-view="relight" aria-pressed="true">Relight</button>
      <button type="button" data-view="normals" aria-pressed="false">Normals</button>
      <button type="button" data-view="albedo" aria-pressed="false">Albedo</button>
    </div>
    <canvas id="pad" width="240" height="240" aria-label="light direction: drag the light"></canvas>
    <p id="readout"></p>
    <p id="legend">Drag over the picture or the disc to move the light: the centre is the camera's axis,
      the rim the horizon. Normals: red = x (right), green = y (up), blue = z (towards you).</p>
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

  var vertexSource = "#version 300 es\nin vec2 corner;\nvoid main() { gl_Position = vec4(corner, 0.0, 1.0); }\n";
  // One fragment per texel, read with texelFetch (no filtering); rows top-first in the layers,
  // so row = height - 1 - the framebuffer's y. coefficient = (byte/255 - bias) * scale.
  var fragmentSource = [
    "#version 300 es",
    "precision highp float; precision highp int; precision highp sampler2DArray;",
    "uniform sampler2DArray layers;",
    "uniform int mode;    // 0 relight, 1 show layer `shown` as a picture",
    "uniform int shown, images, lrgb, height;",
    "uniform float w[9];",
    "uniform vec3 scale[9], bias[9];",
    "out vec4 color;",
    "vec3 coefficient(ivec2 t, int j) { return (texelFetch(layers, ivec3(t, j), 0).rgb - bias[j]) * scale[j]; }",
    "void main() {",
    "  ivec2 t = ivec2(int(gl_FragCoord.x), height - 1 - int(gl_FragCoord.y));",
    "  if (mode == 1) { color = vec4(texelFetch(layers, ivec3(t, shown), 0).rgb, 1.0); return; }",
    "  vec3 v = vec3(0.0);",
    "  if (lrgb == 1) {",
    "    float l = dot(coefficient(t, 1), vec3(w[0], w[1], w[2])) + dot(coefficient(t, 2), vec3(w[3], w[4], w[5]));",
    "    v = coefficient(t, 0) * l;",
    "  } else {",
    "    for (int j = 0; j < images; ++j) v += coefficient(t, j) * w[j];",
    "  }",
    "  color = vec4(clamp(v, 0.0, 1.0), 1.0);",
    "}"].join("\n");

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
    gl.uniform1i(u("height"), data.height);
    gl.uniform1i(u("layers"), 0);
    gl.viewport(0, 0, data.width, data.height);
    return function draw(view, light) {
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

  function setUp(data) {
    var canvas = document.getElementById("view"), pad = document.getElementById("pad");
    var info = data.info, options = settings(), view = "relight", light = fromAngles(45, 45), draw = null;
    if (options.light) {
      var l = options.light.split(",").map(Number), n = Math.hypot(l[0], l[1], l[2]);
      if (n > 0) light = [l[0] / n, l[1] / n, l[2] / n];
    }
    if (options.view === "normals" || options.view === "albedo") view = options.view;
    canvas.width = data.width; canvas.height = data.height;
    document.getElementById("caption").textContent = (info.type === "ptm" ? "PTM " + info.colorspace.toUpperCase()
        : "HSH order " + Math.round(Math.sqrt(info.nplanes / 3))) + " model, " + info.width + "\u00d7" + info.height +
        (data.halvings === 0 ? "" : "; shown at " + data.width + "\u00d7" + data.height + ", halved " + data.halvings +
         (data.halvings === 1 ? " time" : " times") + (data.level >= 0 ? " (Deep Zoom level " + data.level + ")" : ""));
    function angles() {
      return { azimuth: Math.atan2(light[1], light[0]) / degree, elevation: Math.asin(Math.max(-1, Math.min(1, light[2]))) / degree };
    }
    function drawPad() {
      var g = pad.getContext("2d"), cx = pad.width / 2, cy = pad.height / 2, r = pad.width / 2 - 12, a = angles();
      g.clearRect(0, 0, pad.width, pad.height);
      g.strokeStyle = "#c9c9d0";
      [0, 30, 60].forEach(function (e) { g.beginPath(); g.arc(cx, cy, r * (90 - e) / 90, 0, 2 * Math.PI); g.stroke(); });
      var d = r * (90 - a.elevation) / 90;
      g.fillStyle = "#f0b400"; g.strokeStyle = "#222";
      g.beginPath(); g.arc(cx + d * Math.cos(a.azimuth * degree), cy - d * Math.sin(a.azimuth * degree), 7, 0, 2 * Math.PI);
      g.fill(); g.stroke();
      document.getElementById("readout").textContent = "Light: azimuth " + a.azimuth.toFixed(1) + "\u00b0, elevation " +
          a.elevation.toFixed(1) + "\u00b0 (x " + light[0].toFixed(3) + ", y " + light[1].toFixed(3) + ", z " + light[2].toFixed(3) + ")";
    }
    var pending = false;
    function redraw() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(function () { pending = false; draw(view, light); drawPad(); });
    }
    // A pointer on the disc, or on the picture taken as the same disc round its centre.
    function setFrom(element, event) {
      var box = element.getBoundingClientRect();
      var radius = element === pad ? (pad.width / 2 - 12) * box.width / pad.width : Math.min(box.width, box.height) / 2;
      var dx = event.clientX - (box.left + box.width / 2), dy = event.clientY - (box.top + box.height / 2);
      var f = Math.min(1, Math.hypot(dx, dy) / radius), a = angles();
      light = fromAngles(f > 0 ? Math.atan2(-dy, dx) / degree : a.azimuth, 90 * (1 - f));
      if (view !== "relight") choose("relight");
      redraw();
    }
    [canvas, pad].forEach(function (element) {
      var dragging = false;
      element.addEventListener("pointerdown", function (e) { dragging = true; element.setPointerCapture(e.pointerId); setFrom(element, e); });
      element.addEventListener("pointermove", function (e) { if (dragging) setFrom(element, e); });
      element.addEventListener("pointerup", function () { dragging = false; });
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

    var uris = data.planes.concat([data.normals, data.albedo]);
    return Promise.all(uris.map(loadPicture)).then(function (pictures) {
      draw = makeRenderer(canvas, data, pictures);
      if ("test" in options) {
        ["relight", "normals", "albedo"].forEach(function (name) {
          var shot = snapshot(draw(name, light), data.width, data.height);
          body.setAttribute("data-pixels-" + name, shot.png);
          body.setAttribute("data-mean-" + name, shot.mean);
        });
      }
      draw(view, light);
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

}  // namespace surrogate::publish
