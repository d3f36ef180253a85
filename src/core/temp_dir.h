// A private temporary folder (mkdtemp under $TMPDIR, mode 0700), removed with everything in
// it when the object goes: where packages are unpacked for re-execution or for the report.
//
//   TempDir temp("verify");               // /tmp/surrogate-verify-Ab12Cd
//   extractFiles(package, ..., temp.path(), ...);
//
// Removal works whatever the work inside left behind: read-only files and folders (the
// verifier's replay copy), folders without read or search permission. It happens on every way
// out of the scope (return or exception), and also when the process is stopped by SIGINT,
// SIGTERM or SIGHUP (Ctrl-C, kill, a closed terminal), as long as the program has not installed
// its own handler for them: the handler removes every live TempDir, then lets the signal end
// the process as it would have. (SIGKILL cannot be caught: what it leaves is writable by its
// owner, so `rm -rf` removes it.)
#pragma once

#include <filesystem>
#include <string>

namespace surrogate {

class TempDir {
 public:
  // `purpose` names the folder and the step in the error if it cannot be made.
  explicit TempDir(const std::string& purpose);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int slot_ = -1;  // in the table the signal handler empties
};

// Removes `path` and everything under it, first giving its owner full permission on each
// folder (so that read-only or unreadable folders can be emptied). Symbolic links are removed,
// never followed. Uses system calls only (safe in a signal handler). Returns whether the path
// is gone.
bool removeTreeForcibly(const char* path);

}  // namespace surrogate
