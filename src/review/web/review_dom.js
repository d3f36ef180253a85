// The review page's small DOM helpers: an element by id, elements and SVG elements made with
// their attributes and children, the status line, and a button that asks for a reason before it
// records a change. Used by review_page.js (served after this file, as the global reviewDom).
/* exported reviewDom */
var reviewDom = (function () {
  "use strict";
  var SVG = "http://www.w3.org/2000/svg";

  function $(id) { return document.getElementById(id); }
  // el("p", { class: "note", text: "..." }, child, ...): "text" sets the text, "onclick" listens.
  function el(tag, attrs) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) {
      if (k === "text") e.textContent = attrs[k];
      else if (k === "onclick") e.addEventListener("click", attrs[k]);
      else e.setAttribute(k, attrs[k]);
    }
    for (var i = 2; i < arguments.length; ++i) {
      var c = arguments[i];
      if (c == null) continue;
      e.appendChild(typeof c === "string" ? document.createTextNode(c) : c);
    }
    return e;
  }
  function svg(tag, attrs) {
    var e = document.createElementNS(SVG, tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    return e;
  }
  // The status line, with its kind: "", "ok", "warning" or "bad".
  function say(text, kind) {
    var s = $("status");
    s.textContent = text;
    s.className = kind || "";
  }

  // A button that asks for a reason before it records a change: done(reason), never with none.
  function withReason(label, placeholder, done) {
    var wrap = el("span");
    var b = el("button", { type: "button", text: label });
    b.addEventListener("click", function () {
      wrap.textContent = "";
      var input = el("input", { type: "text", placeholder: placeholder });
      var ok = el("button", { type: "button", text: "OK" });
      ok.addEventListener("click", function () {
        if (!input.value.trim()) { say("Give a reason: it is recorded with the decision.", "warning"); input.focus(); return; }
        done(input.value.trim());
      });
      wrap.appendChild(el("span", { class: "inline-reason" }, input, ok));
      input.focus();
    });
    wrap.appendChild(b);
    return wrap;
  }

  return { $: $, el: el, svg: svg, say: say, withReason: withReason };
})();
