#include "batch/work_list.h"

#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

#include "archive/bag_text.h"
#include "core/error.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

std::vector<WorkItem> readWorkList(std::istream& in, const std::string& listName) {
  // Lists made on Windows: PowerShell's > writes UTF-16 with a byte-order mark, editors put a
  // mark before UTF-8. Taken as bytes, the mark became part of the first path, which then named
  // a capture that does not exist, in a message where the mark cannot be seen.
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0) {
    std::string why;
    const std::optional<std::string> decoded = archive::decodeTagText(text, "UTF-16", &why);
    if (!decoded)
      throw Error(ErrorKind::Usage, listName, "batch list",
                  "starts as UTF-16 text but cannot be read as such (" + why + "); save it as UTF-8, one path a line");
    text = *decoded;
  }
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  std::istringstream lines(text);
  std::vector<WorkItem> items;
  std::map<std::string, std::size_t> seen;  // normalised path -> line
  std::string line;
  std::size_t lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (line.find('\0') != std::string::npos)
      throw Error(ErrorKind::Usage, listName, "batch list",
                  "line " + std::to_string(lineNumber) + " holds a NUL byte: this is not a text list of paths");
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
    // "cap/" and "cap" are one capture: the same lock, the same package.
    std::string key = fs::path(line).lexically_normal().string();
    while (key.size() > 1 && key.back() == '/') key.pop_back();
    if (const auto it = seen.find(key); it != seen.end())
      throw Error(ErrorKind::Usage, listName, "batch list",
                  "line " + std::to_string(lineNumber) + " (" + line + ") repeats line " +
                      std::to_string(it->second) + ": give each capture or package once");
    seen[key] = lineNumber;
    while (line.size() > 1 && line.back() == '/') line.pop_back();
    WorkItem item;
    item.number = items.size() + 1;
    item.path = line;
    item.isPackage = looksLikePackage(line);
    items.push_back(std::move(item));
  }
  return items;
}

std::vector<WorkItem> readWorkList(const std::string& list) {
  std::vector<WorkItem> items;
  if (list == "-") {
    items = readWorkList(std::cin, "standard input");
  } else {
    std::ifstream in(list);
    if (!in)
      throw Error(ErrorKind::Input, list, "batch list",
                  "cannot be read; give a text file of capture folders or packages, one a line");
    items = readWorkList(in, list);
  }
  if (items.empty())
    throw Error(ErrorKind::Usage, list == "-" ? "standard input" : list, "batch list",
                "holds no capture folder or package (one a line; # starts a comment)");
  return items;
}

bool looksLikePackage(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return fs::is_regular_file(path / "bagit.txt", ec);
  const std::string ext = path.extension().string();
  return ext == ".zip" || ext == ".tar";
}

fs::path packagePathFor(const fs::path& capture, const fs::path& packagesDir, const std::string& format) {
  fs::path folder = capture.lexically_normal();
  if (folder.filename().empty()) folder = folder.parent_path();  // "cap/"
  std::string name = folder.filename().string();
  if (name.empty() || name == "." || name == "..") name = fs::absolute(folder).lexically_normal().filename().string();
  const fs::path file = name + "." + format;
  if (!packagesDir.empty()) return packagesDir / file;
  return folder.parent_path() / file;
}

void requireDistinctPackages(const std::vector<WorkItem>& items, const fs::path& packagesDir,
                             const std::string& format) {
  std::map<std::string, const WorkItem*> byPackage;
  for (const WorkItem& item : items) {
    if (item.isPackage) continue;
    const std::string package =
        fs::absolute(packagePathFor(item.path, packagesDir, format)).lexically_normal().string();
    const auto [it, added] = byPackage.emplace(package, &item);
    if (!added)
      throw Error(ErrorKind::Usage, item.path, "batch list",
                  "would be packed into " + package + ", as item " + std::to_string(it->second->number) + " (" +
                      it->second->path + ") would: two captures of one name cannot share a --packages folder; "
                      "rename one, or give the batch no --packages (each package is then beside its capture)");
  }
}

}  // namespace surrogate::batch
