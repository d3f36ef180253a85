// The report page's inline stylesheet and scripts (no network access: everything is in the
// page), written as web code in src/report/web/ and embedded at build time by
// src/report/CMakeLists.txt (surrogate_embed): the generated report/web_files.h declares each
// as `extern const char* const` in this namespace. The page's one <script> holds, in order,
// kPageErrorsJs, kRelightModelJs, kRelightViewJs and kReportJs.
//
// kReportCss (web/report.css): the report's stylesheet; the review page builds on it.
// kPageErrorsJs (web/page_errors.js): runs first on the report's page and on the review's:
//   records every script error, unhandled promise rejection and console.error in <body
//   data-errors> (joined by " | "), which the browser tests read, and offers
//   window.surrogateRecordError(message) to the page's own script.
// kRelightModelJs (web/relight_model.js), kRelightViewJs (web/relight_view.js): the relighting
//   view's arithmetic, with no DOM (unit-tested in Node, tests/web/report_*.test.js).
// kReportJs (web/report.js): runs on load: counts the plotted lights and records script errors
//   on <body> (data-lights-plotted, data-errors, data-ready) so a headless browser's DOM dump
//   shows them; draws the interactive relighting view from the JSON in <script
//   id="relight-data"> when present (data-relight, and data-relight-mean: the mean brightness of
//   its first rendering).
#pragma once

#include "report/web_files.h"
