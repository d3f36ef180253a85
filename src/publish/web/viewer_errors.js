// The published viewer (web/viewer.html), its first script: every error of the page's scripts
// is recorded on <body> as data-errors (which the browser tests read) and shown in #message.
// It starts the page's one global, window.surrogateViewer, which the scripts after it extend:
// each of them is a script of its own and takes what it needs from there.
var surrogateViewer = surrogateViewer || {};
surrogateViewer.record = (function () {
  "use strict";
  var body = document.body, errors = [];
  function record(message) {
    errors.push(String(message));
    body.setAttribute("data-errors", errors.join(" | "));
    document.getElementById("message").textContent = errors.join("; ");
  }
  window.addEventListener("error", function (e) { record(e.message || "script error"); });
  return record;
})();
