// AtomicFile: write a file under a temporary name in the same directory (or in a given folder
// of the same file system), then rename it into place on commit(). If commit() is never called (an error was thrown), the destructor removes
// the temporary file, so no partial output is ever left under the final name.
//
//   AtomicFile out(path);
//   writeEverything(out.tempPath());
//   out.commit();
#pragma once

#include <filesystem>
#include <string>

namespace surrogate {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path finalPath);
  // The temporary file in `tempFolder` instead, which must be on the same file system: a
  // writer whose target folder must never hold anything but finished files (a capture's
  // output folders) writes in its work folder and renames from there.
  AtomicFile(std::filesystem::path finalPath, const std::filesystem::path& tempFolder);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& tempPath() const { return temp_; }
  const std::filesystem::path& finalPath() const { return final_; }
  // Flushes the temporary file to disk and renames it to the final name.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Writes `content` to `file`'s temporary file (not yet in place: commit() does that). Throws
// Error naming the final path when the bytes cannot be written.
void writeTemporary(const AtomicFile& file, const std::string& content);

// Writes `content` to `path` atomically (temporary name, fsync, rename); the temporary file
// goes in `tempFolder` when one is given (see AtomicFile).
void writeFileAtomically(const std::filesystem::path& path, const std::string& content,
                         const std::filesystem::path& tempFolder = {});

// Reads a whole file; throws Error(Input) naming the file if it cannot be read.
std::string readFile(const std::filesystem::path& path, const std::string& step);

}  // namespace surrogate
