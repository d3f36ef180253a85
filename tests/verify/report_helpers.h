// Test support for the verifier's tests: a report as text, a check's outcome, a clean bag to
// break, and running the verifier. Header-only (the fixture library does not link the verifier).
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "bag_fixture.h"
#include "verify/verify.h"

namespace verify_test {

// Every check, "ok"/"FAIL", with its where-lines: for INFO and Contains.
inline std::string allText(const surrogate::verify::Report& r) {
  std::string s;
  for (const surrogate::verify::Check& c : r.checks) {
    s += (c.passed ? "ok   " : "FAIL ") + c.name + ": " + c.what + "\n";
    for (const std::string& w : c.where) s += "  " + w + "\n";
  }
  return s;
}

// Whether the check `name` ran and failed.
inline bool failed(const surrogate::verify::Report& r, const std::string& name) {
  for (const surrogate::verify::Check& c : r.checks)
    if (c.name == name) return !c.passed;
  return false;
}

// A valid bag of the tiny capture, in a fresh folder.
inline std::filesystem::path cleanBag(const std::string& name) {
  const std::filesystem::path dir = freshDir(name);
  makeBag(tinyCapture(dir), dir / "bag");
  return dir / "bag";
}

inline surrogate::verify::Report run(const std::filesystem::path& p, bool reexecute = false) {
  surrogate::verify::VerifyOptions options;
  options.reexecute = reexecute;
  return surrogate::verify::verifyPackage(p, options);
}

// Replaces the first `from` in the file (which must be there) by `to`.
inline void replaceInFile(const std::filesystem::path& p, const std::string& from, const std::string& to) {
  std::string text = readText(p);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  writeText(p, text);
}

}  // namespace verify_test
