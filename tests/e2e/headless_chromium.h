// Test support for the browser tests (the report, the published viewer): a page opened from
// file:// in headless Chromium, the DOM after its scripts ran, and its console messages.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace e2e {

// The chromium program ($SURROGATE_CHROMIUM, else chromium or chromium-browser); without one
// the test program exits 77, which ctest counts as skipped. `test` names it in that message.
inline std::string chromiumOrSkip(const std::string& test) {
  std::vector<std::string> candidates = {"chromium", "chromium-browser"};
  if (const char* env = std::getenv("SURROGATE_CHROMIUM"); env && *env) candidates = {env};
  for (const std::string& name : candidates)
    if (runShell("command -v " + quote(name) + " >/dev/null").exitCode == 0) return name;
  std::cerr << "SKIPPED: chromium is not installed (apt-get install chromium, or run "
               "scripts/install-deps); " << test << " needs it\n";
  std::exit(77);
}

struct BrowserRun {
  int exitCode = -1;
  std::string dom;  // what --dump-dom printed
  std::string log;  // chromium's log, with the page's console messages
};

// Opens `url` in headless chromium with `flags` (e.g. "--window-size=1200,900 --dump-dom") and
// a profile folder of its own in `work`, where its output and log are also kept.
inline BrowserRun runChromium(const std::string& chromium, const std::string& flags, const std::string& url,
                              const std::filesystem::path& work) {
  const std::filesystem::path out = work / "dom.html", err = work / "chromium.log";
  const std::string command = "timeout 120 " + chromium +
                              " --headless=new --no-sandbox --disable-gpu --no-first-run "
                              "--enable-logging=stderr --v=0 --user-data-dir=" + quote(work / "chromium-profile") +
                              " " + flags + " " + quote(url) + " > " + quote(out) + " 2> " + quote(err);
  BrowserRun r;
  r.exitCode = runShell(command).exitCode;
  r.dom = bytesOf(out);
  r.log = bytesOf(err);
  return r;
}

inline std::string fileUrl(const std::filesystem::path& page) {
  return "file://" + std::filesystem::absolute(page).string();
}

// An attribute of the page's <body> (where the pages under test record what they did). A plain
// search: the tag may hold data URLs of hundreds of kilobytes, too long for std::regex.
inline std::string bodyAttribute(const std::string& dom, const std::string& name) {
  const std::size_t open = dom.find("<body"), close = dom.find('>', open);
  if (open == std::string::npos || close == std::string::npos) return "";
  const std::string tag = dom.substr(open, close - open);
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

// The lines of chromium's log that are the page's console messages (errors, CSP violations...).
inline std::vector<std::string> consoleLines(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.find(":CONSOLE") != std::string::npos) out.push_back(line);
  return out;
}

}  // namespace e2e
