// walkFolder (folder_walk.h): a folder package listed without following anything.
#include "archive/folder_walk.h"

#include <system_error>

namespace fs = std::filesystem;

namespace surrogate::archive {

FolderWalk walkFolder(const fs::path& root, const std::string& holder) {
  FolderWalk w;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string rel = it->path().lexically_relative(root).generic_string();
    const fs::file_status st = it->symlink_status(ec);
    if (fs::is_directory(st)) w.folders.insert(rel);
    else if (fs::is_regular_file(st)) w.files.insert(rel);
    else w.problems.push_back(rel + ": " + (fs::is_symlink(st) ? "a symbolic link" : "not a regular file or folder") +
                              " (" + holder + " holds files and folders only)");
  }
  if (ec) w.problems.push_back(root.string() + ": cannot be listed (" + ec.message() + ")");
  return w;
}

}  // namespace surrogate::archive
