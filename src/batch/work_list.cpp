#include "batch/work_list.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "archive/bag_text.h"
#include "batch/descriptor.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

namespace {

Error badList(const std::string& listName, const std::string& what) {
  return Error(ErrorKind::Input, escapedText(listName), "batch list", what);
}

Error tooLarge(const std::string& listName) {
  return badList(listName, "is larger than " + std::to_string(kMaxListBytes >> 20) +
                               " MiB: this is not a list of paths; split it into several batches");
}

// Reads at most kMaxListBytes through `readSome` (bytes read into the buffer, 0 at the end),
// refusing a NUL byte as soon as it arrives: a stream of zeros on standard input ends at its
// first block rather than after filling the memory.
template <typename ReadSome>
std::string boundedText(ReadSome readSome, const std::string& listName) {
  std::string text;
  char block[1 << 16];
  for (std::size_t n; (n = readSome(block, sizeof block)) > 0;) {
    if (text.size() + n > kMaxListBytes)
      throw tooLarge(listName);
    const std::size_t start = text.size();
    text.append(block, n);
    // UTF-16 text holds a NUL in every other byte of ASCII: its lines are checked once decoded.
    const bool utf16 = text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0;
    if (const std::size_t nul = text.find('\0', start); !utf16 && nul != std::string::npos)
      throw badList(listName, "line " + std::to_string(std::count(text.begin(), text.begin() + nul, '\n') + 1) +
                                  " holds a NUL byte: this is not a text list of paths");
  }
  return text;
}

// The real path of an item, for telling one capture reached by two spellings (a symbolic
// link, an absolute and a relative path); the lexical form when it cannot be resolved.
std::string realPathOf(const std::string& path) {
  std::error_code ec;
  fs::path real = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) real = fs::absolute(path).lexically_normal();
  std::string key = real.string();
  while (key.size() > 1 && key.back() == '/') key.pop_back();
  return key;
}

// The folder a list's relative paths are read from: the list file's own ("" : the current one).
fs::path listFolder(const std::string& list) { return list == "-" ? fs::path() : fs::path(list).parent_path(); }

// A line's path as read from `base`: itself when absolute or when `base` is the current folder.
std::string within(const fs::path& base, const std::string& line) {
  return fs::path(line).is_absolute() || base.empty() ? line : (base / line).string();
}

std::vector<WorkItem> itemsOf(std::string text, const std::string& listName, const fs::path& base) {
  // Lists made on Windows: PowerShell's > writes UTF-16 with a byte-order mark, editors put a
  // mark before UTF-8. Taken as bytes, the mark became part of the first path, which then named
  // a capture that does not exist, in a message where the mark cannot be seen.
  if (text.rfind("\xFF\xFE", 0) == 0 || text.rfind("\xFE\xFF", 0) == 0) {
    std::string why;
    const std::optional<std::string> decoded = archive::decodeTagText(text, "UTF-16", &why);
    if (!decoded)
      throw badList(listName, "starts as UTF-16 text but cannot be read as such (" + why +
                                  "); save it as UTF-8, one path a line");
    text = *decoded;
  }
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  std::istringstream lines(text);
  std::vector<WorkItem> items;
  std::map<std::string, std::pair<std::size_t, std::string>> seen;  // real path -> line and its text
  std::string line;
  std::size_t lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (line.find('\0') != std::string::npos)
      throw badList(listName, "line " + std::to_string(lineNumber) + " holds a NUL byte: this is not a text list of paths");
    if (line.size() > kMaxListLineBytes)
      throw badList(listName, "line " + std::to_string(lineNumber) + " is longer than " +
                                  std::to_string(kMaxListLineBytes) + " bytes: this is not a list of paths");
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
    // "cap/" and "cap", a link to cap, its absolute path: one capture, the same lock, the same
    // carrier. Taken twice, it would be run and packed once per spelling, each pack's change to
    // the carrier making the other's package out of date, in every batch.
    const std::string key = realPathOf(within(base, line));
    if (const auto it = seen.find(key); it != seen.end())
      throw Error(ErrorKind::Usage, escapedText(listName), "batch list",
                  "line " + std::to_string(lineNumber) + " (" + escapedText(line) + ") repeats line " +
                      std::to_string(it->second.first) + " (" + escapedText(it->second.second) + ")" +
                      (line == it->second.second ? "" : ", both " + escapedText(key)) +
                      ": give each capture or package once");
    seen.emplace(key, std::make_pair(lineNumber, line));
    while (line.size() > 1 && line.back() == '/') line.pop_back();
    WorkItem item;
    item.number = items.size() + 1;
    item.path = line;
    item.location = within(base, line);
    item.isPackage = looksLikePackage(item.location);
    items.push_back(std::move(item));
  }
  return items;
}

}  // namespace

std::vector<WorkItem> readWorkList(std::istream& in, const std::string& listName, const fs::path& base) {
  return itemsOf(boundedText(
                     [&](char* buffer, std::size_t size) {
                       in.read(buffer, static_cast<std::streamsize>(size));
                       return static_cast<std::size_t>(in.gcount());
                     },
                     listName),
                 listName, base);
}

std::vector<WorkItem> readWorkList(const std::string& list) {
  std::vector<WorkItem> items;
  if (list == "-") {
    items = readWorkList(std::cin, "standard input");
  } else {
    // Opened without waiting (a FIFO with no writer would hold the batch forever), then read
    // only as a regular file, from the descriptor checked: a device or a FIFO is no list, and
    // /dev/zero never ends.
    const Descriptor d{::open(list.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (d.fd < 0)
      throw badList(list, std::string("cannot be read (") + std::strerror(errno) +
                              "); give a text file of capture folders or packages, one a line");
    struct stat st {};
    if (::fstat(d.fd, &st) != 0 || !S_ISREG(st.st_mode))
      throw badList(list, std::string("is not a regular file (") +
                              (S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a device or socket") +
                              "); give a text file of capture folders or packages, one a line, or - for standard input");
    if (static_cast<std::uint64_t>(st.st_size) > kMaxListBytes) throw tooLarge(list);
    items = itemsOf(boundedText(
                        [&](char* buffer, std::size_t size) -> std::size_t {
                          for (;;) {
                            const ssize_t n = ::read(d.fd, buffer, size);
                            if (n >= 0) return static_cast<std::size_t>(n);
                            if (errno != EINTR)
                              throw badList(list, std::string("cannot be read (") + std::strerror(errno) + ")");
                          }
                        },
                        list),
                    list, listFolder(list));
  }
  if (items.empty())
    throw Error(ErrorKind::Usage, list == "-" ? "standard input" : escapedText(list), "batch list",
                "holds no capture folder or package (one a line; # starts a comment)");
  return items;
}

std::string listFolderNote(const std::string& list, const std::vector<WorkItem>& items) {
  const bool relative = std::any_of(items.begin(), items.end(),
                                    [](const WorkItem& i) { return !fs::path(i.path).is_absolute(); });
  if (!relative) return "";
  const fs::path base = listFolder(list);
  std::string folder = (base.empty() ? fs::current_path() : fs::absolute(base)).lexically_normal().string();
  while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
  return list == "-" ? "Relative paths in the list are read from the current folder, " + escapedText(folder) + "."
                     : "Relative paths in " + escapedText(list) + " are read from its folder, " + escapedText(folder) + ".";
}

std::string pathArgument(const std::string& path) { return path.rfind('-', 0) == 0 ? "./" + path : path; }

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
        fs::absolute(packagePathFor(item.where(), packagesDir, format)).lexically_normal().string();
    const auto [it, added] = byPackage.emplace(package, &item);
    if (!added)
      throw Error(ErrorKind::Usage, item.path, "batch list",
                  "would be packed into " + package + ", as item " + std::to_string(it->second->number) + " (" +
                      it->second->path + ") would: two captures of one name cannot share a --packages folder; "
                      "rename one, or give the batch no --packages (each package is then beside its capture)");
  }
}

}  // namespace surrogate::batch
