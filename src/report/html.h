// Small helpers for writing HTML from untrusted text (carrier fields, file names).
#pragma once

#include <string>

#include "core/text.h"  // escapeHtml, for text in element content and quoted attributes

namespace surrogate::report {

// A JSON string literal safe to embed inside <script>: also escapes '<', '>' and '&', and
// U+2028/U+2029, so no carrier text can close the script element.
std::string scriptString(const std::string& text);

// A number for display: up to `digits` decimals, trailing zeros removed ("12.5", "3").
std::string displayNumber(double value, int digits = 1);

}  // namespace surrogate::report
