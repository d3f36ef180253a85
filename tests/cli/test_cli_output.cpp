// What the terminal and scripts see: progress bars on a terminal (emulated with script(1))
// and nowhere else; --json gives exactly one JSON object on stdout, for success and failure.
#include <catch2/catch.hpp>

#include <cctype>
#include <regex>
#include <sstream>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

// A strict JSON syntax check (RFC 8259): one value, nothing after it but white space.
class JsonChecker {
 public:
  explicit JsonChecker(const std::string& text) : s_(text) {}
  bool valid() {
    skip();
    if (!value()) return false;
    skip();
    return i_ == s_.size();
  }

 private:
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool literal(const char* word) {
    const std::string w = word;
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  bool string() {
    if (i_ >= s_.size() || s_[i_] != '"') return false;
    for (++i_; i_ < s_.size(); ++i_) {
      const unsigned char c = static_cast<unsigned char>(s_[i_]);
      if (c == '"') {
        ++i_;
        return true;
      }
      if (c < 0x20) return false;
      if (c == '\\') {
        if (++i_ >= s_.size()) return false;
        const char e = s_[i_];
        if (e == 'u') {
          for (int k = 0; k < 4; ++k)
            if (++i_ >= s_.size() || !std::isxdigit(static_cast<unsigned char>(s_[i_]))) return false;
        } else if (std::string("\"\\/bfnrt").find(e) == std::string::npos) {
          return false;
        }
      }
    }
    return false;
  }
  bool number() {
    if (i_ < s_.size() && s_[i_] == '-') ++i_;
    const std::size_t integer = i_;
    auto digits = [&] {
      const std::size_t b = i_;
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      return i_ > b;
    };
    if (!digits()) return false;
    if (s_[integer] == '0' && i_ - integer > 1) return false;  // no leading zeros
    if (i_ < s_.size() && s_[i_] == '.' && (++i_, !digits())) return false;
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
      if (!digits()) return false;
    }
    return true;
  }
  bool value() {
    skip();
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++i_;
      skip();
      if (i_ < s_.size() && s_[i_] == close) {
        ++i_;
        return true;
      }
      while (true) {
        skip();
        if (c == '{') {
          if (!string()) return false;
          skip();
          if (i_ >= s_.size() || s_[i_++] != ':') return false;
        }
        if (!value()) return false;
        skip();
        if (i_ >= s_.size()) return false;
        if (s_[i_] == close) {
          ++i_;
          return true;
        }
        if (s_[i_++] != ',') return false;
      }
    }
    if (c == '"') return string();
    if (c == 't') return literal("true");
    if (c == 'f') return literal("false");
    if (c == 'n') return literal("null");
    return number();
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

// Runs surrogate with stdout only (stderr discarded).
e2e::CommandResult stdoutOf(const std::string& args) {
  return e2e::runShell("(" + std::string(SURROGATE_EXE) + " " + args + " 2>/dev/null)");
}

// Runs surrogate under script(1), which gives it a terminal; returns what the terminal showed.
e2e::CommandResult onTerminal(const std::string& args) {
  return e2e::runShell("script -qec " + e2e::quote(std::string(SURROGATE_EXE) + " " + args) + " /dev/null");
}

bool oneJsonObject(const std::string& out) {
  if (out.empty() || out.back() != '\n' || out.find('\n') != out.size() - 1 || out.front() != '{')
    return false;
  return JsonChecker(out).valid();
}

}  // namespace

TEST_CASE("the JSON checker used here accepts JSON and rejects near misses") {
  CHECK(JsonChecker(R"({"a":[1,-2.5e3,true,null,"x\"\u00e9"],"b":{}})").valid());
  CHECK_FALSE(JsonChecker(R"({"a":1,})").valid());
  CHECK_FALSE(JsonChecker(R"({"a":01})").valid());
  CHECK_FALSE(JsonChecker(R"({"a":nan})").valid());
  CHECK_FALSE(JsonChecker(R"({"a":1} x)").valid());
}

TEST_CASE("surrogate run shows progress on a terminal for decoding, detection and fitting") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("progress"));
  const e2e::CommandResult r = onTerminal("run " + e2e::quote(capture));
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  for (const char* label : {"Decoding images", "Sphere detection", "Highlight detection", "Fitting ptm-lrgb",
                            "Fitting hsh2", "100%"})
    CHECK_THAT(r.output, Catch::Contains(label));
  CHECK_THAT(r.output, Catch::Contains("\rDecoding images"));  // redrawn in place after a carriage return
}

TEST_CASE("progress stays quiet with --quiet, with --json, and when stderr is not a terminal") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("quiet"));
  for (const char* options : {" --quiet", " --json"}) {
    const e2e::CommandResult r = onTerminal("run " + e2e::quote(capture) + options);
    INFO(options << "\n" << r.output);
    REQUIRE(r.exitCode == 0);
    CHECK(r.output.find("Decoding images") == std::string::npos);
    // The bar ends "NN%" (cli/progress.cpp); a warning's text may hold a percentage, "(6.05 %)".
    CHECK_FALSE(std::regex_search(r.output, std::regex("[0-9]%")));
  }
  const e2e::CommandResult piped = e2e::surrogate("run " + e2e::quote(capture));  // stderr is a pipe
  INFO(piped.output);
  REQUIRE(piped.exitCode == 0);
  CHECK(piped.output.find('\r') == std::string::npos);
  CHECK(piped.output.find("Decoding images") == std::string::npos);
}

TEST_CASE("every command that reports prints exactly one JSON object on stdout with --json") {
  const fs::path work = e2e::freshDir("json");
  const fs::path capture = e2e::smallCapture(work);
  const std::string c = e2e::quote(capture);
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"lights " + c + " -o " + e2e::quote(work / "l.lp") + " --json", "\"lights\":8"},
      {"run " + c + " --json", "\"report\":"},
      {"fit --lp " + e2e::quote(capture / "assembly-files/lights.lp") + " -o " + e2e::quote(work / "f.ptm") + " --json",
       "\"rmse\":"},
      {"render " + e2e::quote(work / "f.ptm") + " --light 0.5,0,0.8 -o " + e2e::quote(work / "r.png") + " --json",
       "\"width\":400"},
      {"info " + c + " --json", "\"carrier\":{\"kind\":\"carrier\""},
      {"info " + e2e::quote(capture / "assembly-files/carrier.xml") + " --json", "\"kind\":\"carrier\""},
      {"info " + e2e::quote(work / "f.ptm") + " --json", "\"kind\":\"ptm\""},
      {"info " + e2e::quote(capture / "assembly-files/lights.lp") + " --json", "\"kind\""},
      {"info " + e2e::quote(capture / "original-captures/IMG_0001.dng") + " --json", "\"kind\":\"image\""},
      {"report " + c + " -o " + e2e::quote(work / "r.html") + " --json", "\"lights\":8"},
  };
  for (const auto& [args, expected] : commands) {
    const e2e::CommandResult r = stdoutOf(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exitCode == 0);
    CHECK(oneJsonObject(r.output));
    CHECK_THAT(r.output, Catch::Contains(expected));
  }
  const fs::path bag = work / "bag.tar";
  for (const std::string& args : {"pack " + c + " -o " + e2e::quote(bag) + " --json",
                                  "verify " + e2e::quote(bag) + " --json",
                                  "report " + e2e::quote(bag) + " --verify -o " + e2e::quote(work / "v.html") + " --json"}) {
    const e2e::CommandResult r = stdoutOf(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exitCode == 0);
    CHECK(oneJsonObject(r.output));
  }
}

TEST_CASE("with --json a failure is a JSON error object on stdout and the documented exit code") {
  const fs::path work = e2e::freshDir("json-error");
  const e2e::CommandResult missing = stdoutOf("info " + e2e::quote(work / "nowhere.ptm") + " --json");
  INFO(missing.output);
  CHECK(missing.exitCode == 1);
  CHECK(oneJsonObject(missing.output));
  CHECK_THAT(missing.output, Catch::Contains("{\"error\":{\"exitCode\":1,"));
  CHECK_THAT(missing.output, Catch::Contains("nowhere.ptm"));

  const e2e::CommandResult usage = stdoutOf("report " + e2e::quote(work) + " --json");
  INFO(usage.output);
  CHECK(usage.exitCode == 2);
  CHECK(oneJsonObject(usage.output));
  // Without --json, stdout stays empty on failure (the message goes to stderr).
  CHECK(stdoutOf("info " + e2e::quote(work / "nowhere.ptm")).output.empty());
}

TEST_CASE("surrogate pack and verify show progress on a terminal, and none with --quiet") {
  const fs::path work = e2e::freshDir("pack-progress");
  const fs::path capture = e2e::smallCapture(work);
  const std::string bag = e2e::quote(work / "bag.tar");
  const e2e::CommandResult pack = onTerminal("pack " + e2e::quote(capture) + " -o " + bag);
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK_THAT(pack.output, Catch::Contains("100%"));
  const e2e::CommandResult verify = onTerminal("verify " + bag + " --reexecute");
  INFO(verify.output);
  REQUIRE(verify.exitCode == 0);
  CHECK_THAT(verify.output, Catch::Contains("re-executing"));
  CHECK_THAT(verify.output, Catch::Contains("100%"));
  const e2e::CommandResult quiet = onTerminal("verify " + bag + " --quiet");
  INFO(quiet.output);
  REQUIRE(quiet.exitCode == 0);
  CHECK(quiet.output.find('%') == std::string::npos);  // (a terminal ends lines with \r\n)
  CHECK(quiet.output.find("[#") == std::string::npos);
}
