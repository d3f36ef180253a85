#include "capture/output_rule.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstring>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::capture {

namespace fs = std::filesystem;

namespace {

constexpr std::array<const char*, 4> kManagedFolders = {kAssemblyDir, kFinishedDir, kWorkDir, kSupersededDir};

template <std::size_t N>
bool isOneOf(const std::string& name, const std::array<const char*, N>& names) {
  for (const char* n : names)
    if (name == n) return true;
  return false;
}

// Output-rule refusals are exit 1, like any input that cannot be processed: the path names
// something the command must not touch (docs/user-guide.md, "Where commands write").
[[noreturn]] void refuse(const std::string& option, const fs::path& output, const std::string& why) {
  throw Error(ErrorKind::Input, option + " " + escapedText(output.string()), "command line", why);
}

// What is at the path when it is not a regular file (fileTypeName); "" for a regular file or
// nothing at all.
std::string specialKind(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  return fileTypeName(st.st_mode);
}

// What kind of package folder `dir` is, by the files each layout puts at its root; "" when
// none. Files of a package are listed in its manifests or inventory: one added or replaced
// makes the package invalid. (An OCFL storage root is not one: `pack --layout ocfl` may put a
// new object anywhere in its hierarchy.)
std::string packageFolderKind(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir / "bagit.txt", ec)) return "a bag (it holds bagit.txt)";
  for (const char* namaste : {"0=ocfl_object_1.0", "0=ocfl_object_1.1"})
    if (fs::exists(dir / namaste, ec)) return "an OCFL object";
  if (fs::is_regular_file(dir / "METS.xml", ec) && fs::is_directory(dir / "representations", ec))
    return "an E-ARK package";
  return "";
}

// What archive the regular file at `path` is, by its first bytes (a ZIP's local header or end
// record, a POSIX tar header's "ustar" magic); "" for anything else or a file that cannot be
// read. Only `pack` writes archives: any other command meeting one is meeting a package.
std::string archiveKind(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return "";
  char head[512] = {};
  const ssize_t n = ::pread(fd, head, sizeof head, 0);
  ::close(fd);
  if (n >= 4 && (std::memcmp(head, "PK\x03\x04", 4) == 0 || std::memcmp(head, "PK\x05\x06", 4) == 0 ||
                 std::memcmp(head, "PK\x07\x08", 4) == 0))
    return "a ZIP archive";
  if (n >= 262 && std::memcmp(head + 257, "ustar", 5) == 0) return "a tar archive";
  return "";
}

// The checks of an existing regular file at the path, by what it is rather than where.
void checkExistingFile(const fs::path& output, const std::string& option, ExistingOutput existing) {
  struct stat st {};
  if (::lstat(output.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
  if (st.st_nlink > 1)
    refuse(option, output,
           "has " + std::to_string(st.st_nlink) + " names (hard links): it may be an original, a package or a "
           "recorded file under another name, and Surrogate never writes over a file it cannot tell is not "
           "one; choose another name, or remove this name first if the file is yours");
  if (existing == ExistingOutput::ReplaceOutput)
    if (const std::string kind = archiveKind(output); !kind.empty())
      refuse(option, output,
             "is " + kind + ", a package or someone's archive, which this command never replaces: choose "
             "another name");
}

bool isCaptureFolder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / kCarrierPath, ec) || hasSourceFolder(dir);
}

// The rule inside one capture `root`; `out` is canonical and lies in it.
void checkInsideCapture(const fs::path& root, const fs::path& out, const fs::path& given,
                        const std::string& option, OutputPlace place) {
  const fs::path rel = out.lexically_relative(root);
  const std::string first = rel.empty() ? "." : rel.begin()->string();
  if (first == ".")
    refuse(option, given, "is the capture folder " + root.string() + " itself; name a file outside it");
  if (isOneOf(first, kManagedFolders))
    refuse(option, given,
           "is inside the capture's " + first + "/ folder (capture " + root.string() +
               "), which only Surrogate's runs write and record; a file put there would make the "
               "capture's record incomplete: choose a place outside the capture");
  if (place == OutputPlace::OutsideCaptures)
    refuse(option, given,
           "is inside the capture " + root.string() +
               ", where it would become part of the capture's record; choose a place outside it");
  std::error_code ec;
  if (!fs::is_regular_file(root / kCarrierPath, ec)) return;
  carrier::Carrier c;
  try {
    c = carrier::loadCarrier(root / kCarrierPath);
  } catch (const Error&) {
    return;  // a damaged carrier is `run`'s and `pack`'s to report; the folders above still hold
  }
  const bool exists = fs::exists(out, ec);
  for (const carrier::FileRecord& f : c.files) {
    const fs::path recorded = (root / f.path).lexically_normal();
    if (recorded == out || (exists && fs::equivalent(recorded, out, ec)))
      refuse(option, given,
             "is " + f.path + ", a file the carrier of capture " + root.string() + " records (" + f.role +
                 "): Surrogate never writes over a recorded file; choose another name");
  }
}

}  // namespace

std::string fileTypeName(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISDIR(mode)) return "a folder";
  return "";
}

void checkOutputTarget(const fs::path& output, const std::string& option, ExistingOutput existing,
                       OutputPlace place, const std::string& refuseHint) {
  const std::string special = specialKind(output);
  if (!special.empty() && special != "a folder")
    refuse(option, output,
           "is " + special + ", not a regular file; Surrogate writes only regular files and never "
           "replaces or writes through anything else: choose a file name");
  std::error_code ec;
  checkExistingFile(output, option, existing);
  if (special.empty() && existing == ExistingOutput::Refuse && fs::exists(output, ec))
    refuse(option, output,
           "already exists; Surrogate does not replace it" + (refuseHint.empty() ? "" : ": " + refuseHint));
  // The folders above, as they are on disk (a link to a capture's folder is that folder).
  fs::path out = fs::weakly_canonical(fs::absolute(output, ec), ec);
  if (ec) out = fs::absolute(output, ec).lexically_normal();  // e.g. a file named as a folder
  for (fs::path dir = out.parent_path();; dir = dir.parent_path()) {
    const std::string name = dir.filename().string();
    if (isOneOf(name, kSourceFolders))
      refuse(option, output,
             "is inside a capture's " + name + "/ folder (" + dir.string() +
                 "), which holds the untouched originals: Surrogate never writes there; choose a "
                 "place outside the capture");
    if (const std::string kind = packageFolderKind(dir); !kind.empty())
      refuse(option, output,
             "is inside " + escapedText(dir.string()) + ", which is " + kind + ": a file written there makes the "
             "package invalid (its manifests list every file); choose a place outside the package");
    if (isCaptureFolder(dir)) checkInsideCapture(dir, out, output, option, place);
    if (dir == dir.root_path() || dir.empty()) break;
  }
}

}  // namespace surrogate::capture
