// The report's relighting arithmetic (no DOM): the models of the page's relight-data
// (report/embed.h) and the light's vector and bases, the same formulas as the C++ renderers so
// that the page relights as `surrogate render` does. report.js draws with them; Node's tests
// (tests/web/report_relight_model.test.js) load this file as a module.
var surrogateRelightModel = (function () {
  "use strict";

  function decodeBase64(text) {
    var bin = atob(text), out = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) out[i] = bin.charCodeAt(i);
    return out;
  }
  // As the C++ renderer's toSample: clamp to 0..255, then round half away from zero.
  function sample(v) { return v <= 0 ? 0 : v >= 255 ? 255 : Math.round(v); }
  var degree = Math.PI / 180;

  // A light in the hemisphere plot's angles (azimuth -180..180, 0 right, 90 up; elevation 0 at
  // grazing, 90 on the camera's axis) as a unit vector x right, y up, z towards the camera.
  function lightVector(light) {
    var a = light.azimuth * degree, e = light.elevation * degree;
    return [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
  }

  // src/fit/basis.h's kHshMaxTheta (1.5607963267948966 there: the same double, written as
  // JavaScript prints it).
  var hshMaxTheta = 1.5607963267948965;

  // The HSH basis of src/fit/basis.cpp (hshBasis), term for term, theta clamped the same way.
  function hshBasis(l, terms) {
    var n = Math.sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    var z = n > 0 ? Math.min(1, Math.max(-1, l[2] / n)) : 1;
    var theta = Math.min(Math.acos(z), hshMaxTheta), phi = Math.atan2(l[1], l[0]);
    var pi = Math.PI, c = Math.cos(theta), s = Math.sqrt(c - c * c), t = 2 * c - 1;
    var cp = Math.cos(phi), sp = Math.sin(phi), c2p = Math.cos(2 * phi), s2p = Math.sin(2 * phi);
    var s3 = Math.pow(c - c * c, 1.5);
    var h = [1 / Math.sqrt(2 * pi), Math.sqrt(6 / pi) * cp * s, Math.sqrt(3 / (2 * pi)) * t,
             Math.sqrt(6 / pi) * sp * s, Math.sqrt(30 / pi) * c2p * (c * c - c),
             Math.sqrt(30 / pi) * cp * t * s, Math.sqrt(5 / (2 * pi)) * (6 * c * c - 6 * c + 1),
             Math.sqrt(30 / pi) * sp * t * s, Math.sqrt(30 / pi) * s2p * (c * c - c),
             2 * Math.sqrt(35 / pi) * Math.cos(3 * phi) * s3,
             Math.sqrt(210 / pi) * c2p * t * (c * c - c),
             2 * Math.sqrt(21 / pi) * cp * s * (5 * c * c - 5 * c + 1),
             Math.sqrt(7 / (2 * pi)) * (20 * c * c * c - 30 * c * c + 12 * c - 1),
             2 * Math.sqrt(21 / pi) * sp * s * (5 * c * c - 5 * c + 1),
             Math.sqrt(210 / pi) * s2p * t * (c * c - c),
             2 * Math.sqrt(35 / pi) * Math.sin(3 * phi) * s3];
    return h.slice(0, terms);
  }

  // A learned model's weights at light l as src/fit/learned_render.cpp (learnedLightWeights)
  // and OpenLIME compute them: the nodes' weights (rbf: exp(-eps d^2) normalised, eps = 8 / the
  // exp(-2 d)-weighted mean distance; bln: bilinear on the rotated octahedral map), then per
  // plane and channel the weighted basis values, summed in float as a Float32Array does.
  function learnedWeights(m, basisBytes, l) {
    var norm = Math.hypot(l[0], l[1], l[2]), x = l[0] / norm, y = l[1] / norm, z = l[2] / norm, nodes = [];
    if (m.basis === "rbf") {
      var rbfCount = m.nodes.length / 3, d = [], num = 0, den = 0, total = 0;
      for (var i = 0; i < rbfCount; ++i) {
        var dx = m.nodes[3 * i] - x, dy = m.nodes[3 * i + 1] - y, dz = m.nodes[3 * i + 2] - z;
        d.push(Math.sqrt(dx * dx + dy * dy + dz * dz));
        var e = Math.exp(-2 * d[i]); num += d[i] * e; den += e;
      }
      var eps = 8 / (num / den);
      for (var j = 0; j < rbfCount; ++j) { nodes.push([j, Math.exp(-eps * d[j] * d[j])]); total += nodes[j][1]; }
      nodes.forEach(function (nw) { nw[1] /= total; });
    } else {
      var R = m.resolution, s = Math.abs(x) + Math.abs(y) + Math.abs(z);
      var u = ((x + y) / s + 1) / 2 * (R - 1), v = ((y - x) / s + 1) / 2 * (R - 1);
      var sx = Math.min(R - 2, Math.max(0, Math.floor(u))), sy = Math.min(R - 2, Math.max(0, Math.floor(v)));
      var fx = u - sx, fy = v - sy;
      nodes = [[sx + sy * R, (1 - fx) * (1 - fy)], [sx + 1 + sy * R, fx * (1 - fy)],
               [sx + (sy + 1) * R, (1 - fx) * fy], [sx + 1 + (sy + 1) * R, fx * fy]];
    }
    var count = m.basis === "rbf" ? m.nodes.length / 3 : m.resolution * m.resolution;
    var W = new Float32Array((m.planes + 1) * 3), f = Math.fround;
    for (var p = 0; p <= m.planes; ++p)
      for (var k = 0; k < 3; ++k) {
        var sum = 0;
        nodes.forEach(function (nw) {
          var b = basisBytes[(p * count + nw[0]) * 3 + k];
          var value = p === 0 ? f(b / 255) : f(f(b - 127) / m.range[p - 1]);
          sum = f(sum + f(f(nw[1]) * value));
        });
        W[p * 3 + k] = sum;
      }
    return W;
  }

  // A model of one entry of relight-data with render(light, rgba pixels), the same formulas as
  // src/fit/render.cpp:
  //   PTM LRGB: out_c = C_c * L(lx, ly) / 255; RGB: out_c = L_c(lx, ly);
  //   L = a0 lx^2 + a1 ly^2 + a2 lx ly + a3 lx + a4 ly + a5, a_k = (byte - bias_k) * scale_k;
  //   HSH: out_c = 255 * sum_k (byte / 255 * scale_k + bias_k) H_k(theta, phi);
  //   learned: out_k = W_0k + sum_p W_(p+1)k (byte_p / 255 - bias_p) scale_p, clamped to 0..1.
  function makeModel(m) {
    var w = m.width, h = m.height, n = w * h, coef = decodeBase64(m.coefficients);
    if (m.model === "learned") {
      var basisBytes = decodeBase64(m.basisBytes), P = m.planes;
      if (coef.length !== n * P) throw new Error("learned relighting data has the wrong size");
      return { m: m, render: function (l, px) {
        var W = learnedWeights(m, basisBytes, l), a = new Float32Array(P * 3), base = [W[0], W[1], W[2]];
        for (var k = 0; k < 3; ++k)
          for (var p = 0; p < P; ++p) {
            a[p * 3 + k] = W[(p + 1) * 3 + k] * m.scale[p] / 255;
            base[k] -= W[(p + 1) * 3 + k] * m.bias[p] * m.scale[p];
          }
        for (var t = 0; t < n; ++t) {
          for (var c = 0; c < 3; ++c) {
            var v = base[c], o = t * P;
            for (var q = 0; q < P; ++q) v += a[q * 3 + c] * coef[o + q];
            px[t * 4 + c] = sample(Math.min(1, Math.max(0, v)) * 255);
          }
          px[t * 4 + 3] = 255;
        }
      } };
    }
    if (m.model === "hsh") {
      if (coef.length !== n * 3 * m.terms) throw new Error("HSH relighting data has the wrong size");
      return { m: m, render: function (l, px) {
        var H = hshBasis(l, m.terms), terms = m.terms, weight = [], offset = 0;
        for (var k = 0; k < terms; ++k) { weight.push(m.scale[k] * H[k]); offset += m.bias[k] * H[k]; }
        for (var t = 0; t < n; ++t) {
          for (var c = 0; c < 3; ++c) {
            var base = (t * 3 + c) * terms, v = offset * 255;
            for (var q = 0; q < terms; ++q) v += coef[base + q] * weight[q];
            px[t * 4 + c] = sample(v);
          }
          px[t * 4 + 3] = 255;
        }
      } };
    }
    var channels = m.format === "rgb" ? 3 : 1, rgb = decodeBase64(m.rgb);
    if (coef.length !== n * 6 * channels || (channels === 1 && rgb.length !== n * 3))
      throw new Error("PTM relighting data has the wrong size");
    return { m: m, render: function (l, px) {
      var u = l[0], v = l[1], s = m.scale, b = m.bias;
      var wk = [s[0] * u * u, s[1] * v * v, s[2] * u * v, s[3] * u, s[4] * v, s[5]];
      var bk = 0;
      for (var k = 0; k < 6; ++k) bk += b[k] * wk[k];
      function evaluate(i) {
        return coef[i] * wk[0] + coef[i + 1] * wk[1] + coef[i + 2] * wk[2] + coef[i + 3] * wk[3] +
               coef[i + 4] * wk[4] + coef[i + 5] * wk[5] - bk;
      }
      for (var t = 0; t < n; ++t) {
        if (channels === 1) {
          var lum = evaluate(t * 6);
          for (var c = 0; c < 3; ++c) px[t * 4 + c] = sample(rgb[t * 3 + c] * lum / 255);
        } else {
          for (var d = 0; d < 3; ++d) px[t * 4 + d] = sample(evaluate((d * n + t) * 6));
        }
        px[t * 4 + 3] = 255;
      }
    } };
  }

  return { degree: degree, decodeBase64: decodeBase64, sample: sample, lightVector: lightVector,
           hshBasis: hshBasis, learnedWeights: learnedWeights, makeModel: makeModel };
})();
if (typeof module === "object") module.exports = surrogateRelightModel;
