// The review page: its HTML, script and stylesheet, served by review.h's server. They are web
// files (src/review/web: review.html, review.css, review_*.js) embedded at build time
// (surrogate_embed in CMakeLists.txt, review/web_files.h). The page loads no resource from
// elsewhere (Content-Security-Policy, kPageSecurityPolicy): the script, the stylesheet (the
// report's, report/page_assets.h, with the page's own rules), the state and the frames'
// previews all come from the server that served it.
#pragma once

#include <string>

namespace surrogate::review {

inline constexpr const char* kPageSecurityPolicy =
    "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; connect-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

// The page's HTML: a frame, empty, filled by the script from /api/state.
std::string pageHtml();
// /review.js: the report's error recorder (report/page_assets.h), the key taken out of the
// address (access_key.h) and the page's own scripts (src/review/web/*.js), in one.
std::string pageScript();
// /review.css: the report's stylesheet and the page's own rules.
std::string pageCss();

}  // namespace surrogate::review
