
(function () {
  "use strict";
  var errors = [];
  function record(message) {
    errors.push(String(message));
    document.body.setAttribute("data-errors", errors.join(" | "));
  }
  window.addEventListener("error", function (e) { record(e.message || "script error"); });
  window.addEventListener("unhandledrejection", function (e) {
    record(e.reason && e.reason.message || String(e.reason));
  });
  var originalConsoleError = console.error;
  console.error = function () {
    record(Array.prototype.join.call(arguments, " "));
    return originalConsoleError.apply(console, arguments);
  };
  window.surrogateRecordError = record;
})();
