// The published viewer's shaders, GLSL ES 3.0 as JavaScript strings (web/viewer_webgl.js compiles
// them): a triangle that covers the canvas, and the relighting of the texel under each pixel.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.shaders = {
  vertex: "#version 300 es\nin vec2 corner;\nvoid main() { gl_Position = vec4(corner, 0.0, 1.0); }\n",
  // The canvas has the level's size; a canvas pixel shows the texel origin + p / zoom (p the
  // pixel's centre from the top left, rows top-first as in the layers), read with texelFetch
  // (no filtering): zoomed, each texel is relit as it is unzoomed, only larger. At zoom 1 and
  // origin 0 one pixel is one texel. coefficient = (byte/255 - bias) * scale.
  fragment: [
    "#version 300 es",
    "precision highp float; precision highp int; precision highp sampler2DArray;",
    "uniform sampler2DArray layers;",
    "uniform int mode;    // 0 relight, 1 show layer `shown` as a picture",
    "uniform int shown, images, lrgb, width, height;",
    "uniform vec2 origin;",
    "uniform float zoom;",
    "uniform float w[9];",
    "uniform vec3 scale[9], bias[9];",
    "out vec4 color;",
    "vec3 coefficient(ivec2 t, int j) { return (texelFetch(layers, ivec3(t, j), 0).rgb - bias[j]) * scale[j]; }",
    "void main() {",
    "  vec2 p = vec2(gl_FragCoord.x, float(height) - gl_FragCoord.y);",
    "  ivec2 t = ivec2(floor(origin + p / zoom));",
    "  if (t.x < 0 || t.y < 0 || t.x >= width || t.y >= height) { color = vec4(0.0, 0.0, 0.0, 1.0); return; }",
    "  if (mode == 1) { color = vec4(texelFetch(layers, ivec3(t, shown), 0).rgb, 1.0); return; }",
    "  vec3 v = vec3(0.0);",
    "  if (lrgb == 1) {",
    "    float l = dot(coefficient(t, 1), vec3(w[0], w[1], w[2])) + dot(coefficient(t, 2), vec3(w[3], w[4], w[5]));",
    "    v = coefficient(t, 0) * l;",
    "  } else {",
    "    for (int j = 0; j < images; ++j) v += coefficient(t, j) * w[j];",
    "  }",
    "  color = vec4(clamp(v, 0.0, 1.0), 1.0);",
    "}"].join("\n"),
};
