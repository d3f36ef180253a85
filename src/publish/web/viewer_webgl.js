// The published viewer's WebGL 2 set-up: the shaders (shader.js) compiled, the planes and the
// normals and albedo pictures in one texture array, and the draw of one view; the canvas read
// back for the test mode. A plane's bytes are numbers, not colours, and reach the shader as they are.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.webgl = (function (shaders, relighting) {
  "use strict";

  function compile(gl, type, source) {
    var s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("shader: " + gl.getShaderInfoLog(s));
    return s;
  }

  // The program and the texture array for `data` (viewer-data.js's object) and its decoded
  // `pictures` (the planes, then the normals and the albedo): gives draw(view, light, camera),
  // which draws "relight", "normals" or "albedo" and returns the WebGL context.
  function makeRenderer(canvas, data, pictures) {
    var gl = canvas.getContext("webgl2", { antialias: false });
    if (!gl) throw new Error("this browser gives the page no WebGL 2; the viewer needs it");
    var info = data.info, images = data.planes.length;
    var program = gl.createProgram();
    gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, shaders.vertex));
    gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, shaders.fragment));
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
      var w = relighting.weights(info, light);
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

  return { makeRenderer, snapshot, loadPicture };
})(surrogateViewer.shaders, surrogateViewer.relighting);
