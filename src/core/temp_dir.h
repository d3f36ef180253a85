// A private temporary folder (mkdtemp under $TMPDIR, mode 0700), removed with everything in
// it when the object goes: where packages are unpacked for re-execution or for the report.
//
//   TempDir temp("verify");               // /tmp/surrogate-verify-Ab12Cd
//   extractFiles(package, ..., temp.path(), ...);
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
};

}  // namespace surrogate
