// The report page's inline stylesheet and script (no network access: everything is in the page).
#pragma once

namespace surrogate::report {

extern const char* const kReportCss;
// Runs on load: counts the plotted lights and records script errors on <body> (data-lights-
// plotted, data-errors, data-ready) so a headless browser's DOM dump shows them; draws the
// interactive relighting view from the JSON in <script id="relight-data"> when present
// (data-relight, and data-relight-mean: the mean brightness of its first rendering).
extern const char* const kReportJs;

// Runs first on the report's page and on the review's: records every script error, unhandled
// promise rejection and console.error in <body data-errors> (joined by " | "), which the
// browser tests read, and offers window.surrogateRecordError(message) to the page's own script.
extern const char* const kPageErrorsJs;

}  // namespace surrogate::report
