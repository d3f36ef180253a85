// The review page: its HTML, script and stylesheet, served by review.h's server. The page loads
// no resource from elsewhere (Content-Security-Policy, kPageSecurityPolicy): the script, the
// stylesheet (the report's, report/page_assets.h, with the page's own rules), the state and the
// frames' previews all come from the server that served it.
#pragma once

#include <string>

namespace surrogate::review {

inline constexpr const char* kPageSecurityPolicy =
    "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; connect-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'";

// The page's HTML: a frame, empty, filled by the script from /api/state.
std::string pageHtml();
// /review.js
extern const char* const kReviewJs;
// /review.css: the report's stylesheet and the page's own rules.
std::string pageCss();

}  // namespace surrogate::review
