// Test support for the report's size budget: how much of a page its pictures take.
#pragma once

#include <cstddef>
#include <string>

namespace report_test {

// The bytes of a page's pictures: the data: URIs of its <img> elements.
inline std::size_t pictureBytes(const std::string& html) {
  std::size_t n = 0;
  const std::string start = "src=\"data:image/";
  for (std::size_t at = html.find(start); at != std::string::npos; at = html.find(start, at + 1))
    n += html.find('"', at + 5) - (at + 5);
  return n;
}

}  // namespace report_test
