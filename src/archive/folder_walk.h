// What a folder package (an OCFL object, an E-ARK SIP) holds, walked without following links:
// its files and folders relative to it, '/' separated, and one sentence for each entry that is
// neither (a symbolic link, a device, a FIFO) or a listing that failed. The verifier walks the
// layouts it checks with it, and `pack --layout ocfl` the object it adds a version to
// (archive/ocfl_object.h): a link in an object could make either read or reuse a file outside it.
//
//   const FolderWalk w = walkFolder("repo/stela12", "an OCFL object");
//   if (!w.problems.empty()) refuse(w.problems.front());   // "v1/content/bagit.txt: a symbolic link (...)"
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace surrogate::archive {

struct FolderWalk {
  std::set<std::string> files, folders;
  std::vector<std::string> problems;
};
// `holder` names the package in the sentences: "an OCFL object".
FolderWalk walkFolder(const std::filesystem::path& root, const std::string& holder);

}  // namespace surrogate::archive
