// Small text helpers every library needs; one copy of each.
#pragma once

#include <string>

namespace surrogate {

// `s` with each byte passed through std::tolower: for file extensions, hash names and other
// ASCII keywords compared without regard to case.
std::string lowerCase(std::string s);

// `v` with exactly `digits` decimals ("%.*f"), for log lines and messages.
std::string fixedDecimals(double v, int digits);

// True when `s` is well-formed UTF-8: no stray continuation bytes, no overlong forms, no
// surrogates (U+D800..U+DFFF), nothing above U+10FFFF.
bool isValidUtf8(const std::string& s);

}  // namespace surrogate
