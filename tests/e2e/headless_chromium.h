// Test support for the browser tests (the report, the published viewer): a page opened from
// file:// in headless Chromium, the DOM after its scripts ran, and its console messages.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
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

// A copy of `page` beside it, named `name`, with `script` run first thing in <body>: for what the
// page shows but does not record itself (where things are, what covers what). A script added at
// the end could run after the page is done (the parser may yield between scripts); this one can
// wrap document.body.setAttribute and measure when the page sets data-ready (probeOnReady).
inline std::filesystem::path probedCopy(const std::filesystem::path& page, const std::string& name,
                                        const std::string& script) {
  std::string html = bytesOf(page);
  const std::size_t open = html.find("<body"), end = html.find('>', open);
  if (open == std::string::npos || end == std::string::npos) throw std::runtime_error(page.string() + " has no <body>");
  html.insert(end + 1, "<script>\n" + script + "\n</script>\n");
  const std::filesystem::path copy = page.parent_path() / name;
  std::ofstream(copy, std::ios::binary) << html;
  return copy;
}

// The JavaScript of a probe that calls `measure` (a JavaScript function expression) when the page
// sets data-ready on <body>: in the same task, so before chromium dumps the page.
inline std::string probeOnReady(const std::string& measure) {
  return "(function () {\n  var body = document.body, set = body.setAttribute, measure = " + measure +
         ";\n  body.setAttribute = function (name, value) {\n    if (name === \"data-ready\") measure();\n"
         "    set.call(body, name, value);\n  };\n})();\n";
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
