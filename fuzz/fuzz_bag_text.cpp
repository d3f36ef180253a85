// libFuzzer target: bagit.txt, bag-info.txt, manifest and fetch.txt parsing, tag files in other
// encodings, and path checks.
#include <cstdint>
#include <string>

#include "archive/bag_text.h"
#include "core/file_names.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace surrogate::archive;
  const std::string text(reinterpret_cast<const char*>(data), size);
  parseDeclaration(text);
  const BagInfo info = parseBagInfo(text);
  for (const auto& [label, value] : info.fields) parseOxum(value);
  for (const ManifestEntry& e : parseManifest(text, "sha256", 64).entries) {
    // Every accepted path must stay inside the bag.
    std::string why;
    const std::string& p = e.path;
    const bool escapes = p == ".." || p.compare(0, 3, "../") == 0 ||
                         p.find("/../") != std::string::npos ||
                         (p.size() >= 3 && p.compare(p.size() - 3, 3, "/..") == 0);
    if (!safeBagPath(p, &why) || escapes || p[0] == '/') __builtin_trap();
  }
  for (const FetchEntry& e : parseFetch(text).entries) {
    std::string why;
    if (!safeBagPath(e.path, &why)) __builtin_trap();
  }
  std::string why;
  for (const char* encoding : {"UTF-16", "ISO-8859-1"}) {
    if (const auto decoded = decodeTagText(text, encoding, &why)) parseManifest(*decoded, "md5", 32);
  }
  safeBagPath(percentDecode(text), &why);
  surrogate::caseFoldKey(text);
  surrogate::findNameProblems({text, "data/" + text}, 5);
  return 0;
}
