// The batch end-to-end tests' shared helpers (batch_e2e_support.h).
#include "batch_e2e_support.h"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>

#include "core/digest.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;

namespace batch_e2e {

fs::path makeCaptures(const fs::path& dir, int count, int images, int width, int height) {
  std::string list;
  for (int i = 1; i <= count; ++i) {
    const fs::path cap = dir / ("cap" + std::to_string(i));
    const auto r = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(cap) + " --images " +
                                 std::to_string(images) + " --width " + std::to_string(width) + " --height " +
                                 std::to_string(height) + " --sphere-radius " + std::to_string(height / 6) +
                                 " --seed " + std::to_string(i));
    REQUIRE(r.exitCode == 0);
    fs::remove_all(cap / "truth");
    list += cap.string() + "\n";
  }
  std::ofstream(dir / "list.txt") << "# generated captures\n" << list;
  return dir / "list.txt";
}

std::size_t count(const std::vector<json>& lines, const std::string& capture, const std::string& step, int exit) {
  std::size_t n = 0;
  for (const json& j : lines)
    n += j["capture"] == capture && j["step"] == step && j["exit"] == exit;
  return n;
}

std::string sha(const fs::path& p) { return surrogate::digestFile(p).sha256; }

std::string version() {
  std::string v = e2e::surrogate("--version").output;  // "surrogate 0.1.0\n" and the libraries
  v = v.substr(0, v.find('\n'));
  return v.substr(v.find(' ') + 1);
}

std::vector<int> processesNaming(const std::string& text) {
  std::vector<int> out;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream f(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (cmdline.find(text) != std::string::npos && std::stoi(name) != ::getpid()) out.push_back(std::stoi(name));
  }
  return out;
}

}  // namespace batch_e2e
