// AtomicFile: write a file under a temporary name in the same directory (or in a given folder
// of the same file system), then rename it into place on commit(). If commit() is never called (an error was thrown), the destructor removes
// the temporary file, so no partial output is ever left under the final name.
//
//   AtomicFile out(path);
//   writeEverything(out.tempPath());
//   out.commit();
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "core/error.h"

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
  // The same, but never over something that is at the final name by then (another process
  // wrote it meanwhile; for a folder, anything but an empty folder): renameat2 with
  // RENAME_NOREPLACE, or where the file system has no such rename, a hard link for a file and a
  // check then rename for a folder. Throws Error(Input) naming the final path when it is taken;
  // the temporary is then removed by the destructor.
  void commitWithoutReplacing();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// A temporary of `finalPath` that its writer left when it was killed: AtomicFile's name
// ".NAME.part-PID-N" beside `finalPath`, whose process PID no longer runs on this machine.
struct AbandonedTemporary {
  std::filesystem::path path;
  long pid = 0;
};
// Those temporaries, listed (nothing removed: what is the caller's to remove, it judges). Only
// "no such process" means a writer is gone: a running one, even another user's, or this
// process keeps its temporaries.
std::vector<AbandonedTemporary> abandonedTemporaries(const std::filesystem::path& finalPath);

// Error(Input) for a write that the environment refused, in a user's words and with what to
// do: no space left (ENOSPC, EDQUOT), a file-size limit (EFBIG), no permission (EACCES, EPERM),
// a read-only file system (EROFS); other errors as the system words them. `path` is what was
// being written, `step` the step writing it.
Error writeError(const std::filesystem::path& path, const std::string& step, int error);

// Writes `content` to `file`'s temporary file (not yet in place: commit() does that). Throws
// Error naming the final path when the bytes cannot be written.
void writeTemporary(const AtomicFile& file, const std::string& content);

// Writes to `file`'s temporary file (not yet in place: commit() does that) whatever `write` puts
// in the stream it is given, and closes it. Throws writeError(file.finalPath(), step, ...) when
// the file cannot be opened or any byte cannot be written. Each few MB are handed to the disk
// as soon as they are written (writeback started, not waited for), so that commit()'s fsync
// of a large file waits for its last MB only, not for all of it (a fit's model of 8-12 MB: the
// fsync was 8-10 ms with every core idle). The bytes are those `write` gave, in its order.
void writeTemporary(const AtomicFile& file, const std::string& step,
                    const std::function<void(std::ostream&)>& write);

// Writes `content` to `path` atomically (temporary name, fsync, rename); the temporary file
// goes in `tempFolder` when one is given (see AtomicFile).
void writeFileAtomically(const std::filesystem::path& path, const std::string& content,
                         const std::filesystem::path& tempFolder = {});

// Reads a whole file; throws Error(Input) naming the file if it cannot be read.
std::string readFile(const std::filesystem::path& path, const std::string& step);

}  // namespace surrogate
