// Private to src/publish: how the web layout orders the PTM terms against a .ptm
// (docs/formats.md, "The bases, term by term").
#pragma once

#include <array>

namespace surrogate::publish {

// The web viewers order the PTM terms (1, u, v, u^2, uv, v^2); a .ptm stores a0..a5 as
// (u^2, v^2, uv, u, v, 1) (formats/ptm.h). kWebPtmTerm[j] is the .ptm index of web term j.
constexpr std::array<int, 6> kWebPtmTerm = {5, 3, 4, 0, 2, 1};

}  // namespace surrogate::publish
