// Counter-based randomness: a value depends only on (seed, stream, index), never on the order
// of calls, so parallel rendering gives the same bytes at any thread count. (std::
// distributions are not used: their output differs between standard libraries.)
#pragma once

#include <cmath>
#include <cstdint>

namespace surrogate::generator {

inline std::uint64_t mix64(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

inline std::uint64_t hash3(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  return mix64(a ^ mix64(b ^ mix64(c)));
}

// Uniform in [0, 1).
inline double uniform(std::uint64_t h) { return (h >> 11) * (1.0 / 9007199254740992.0); }

// Standard normal by Box-Muller from two hashes.
inline double gaussian(std::uint64_t h) {
  const double u1 = uniform(mix64(h)) + 1e-300, u2 = uniform(mix64(h + 1));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

}  // namespace surrogate::generator
