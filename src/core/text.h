// Small text helpers every library needs; one copy of each.
#pragma once

#include <string>

namespace surrogate {

// `s` with each byte passed through std::tolower: for file extensions, hash names and other
// ASCII keywords compared without regard to case.
std::string lowerCase(std::string s);

// `v` with exactly `digits` decimals ("%.*f"), for log lines and messages.
std::string fixedDecimals(double v, int digits);

}  // namespace surrogate
