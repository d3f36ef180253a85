#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/resident.h"

namespace surrogate {

namespace fs = std::filesystem;

namespace {
fs::path temporaryNameFor(const fs::path& finalPath, const fs::path& folder) {
  static std::atomic<unsigned> counter{0};
  std::ostringstream name;
  name << "." << finalPath.filename().string() << ".part-" << ::getpid() << "-" << counter++;
  return folder / name.str();
}

void syncFile(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}
}  // namespace

AtomicFile::AtomicFile(fs::path finalPath)
    : final_(std::move(finalPath)), temp_(temporaryNameFor(final_, final_.parent_path())) {}

AtomicFile::AtomicFile(fs::path finalPath, const fs::path& tempFolder)
    : final_(std::move(finalPath)), temp_(temporaryNameFor(final_, tempFolder)) {}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

void AtomicFile::commit() {
  if (fs::is_regular_file(temp_)) syncFile(temp_);
  std::error_code ec;
  fs::rename(temp_, final_, ec);
  if (ec) {
    throw Error(ErrorKind::Internal, final_.string(), "write",
                "could not move the finished file into place: " + ec.message());
  }
  committed_ = true;
}

void writeTemporary(const AtomicFile& file, const std::string& content) {
  std::ofstream f(file.tempPath(), std::ios::binary);
  f.write(content.data(), static_cast<std::streamsize>(content.size()));
  f.flush();
  if (!f) {
    throw Error(ErrorKind::Internal, file.finalPath().string(), "write",
                std::string("could not write the file (") + std::strerror(errno) +
                    "); check free disk space and permissions");
  }
}

void writeFileAtomically(const fs::path& path, const std::string& content, const fs::path& tempFolder) {
  AtomicFile out(path, tempFolder.empty() ? path.parent_path() : tempFolder);
  writeTemporary(out, content);
  out.commit();
}

std::string readFile(const fs::path& path, const std::string& step) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throwInputError(path.string(), step, "cannot open the file for reading");
  // One read of the size the file says it has, straight into the string (a stream copy grows
  // and copies a photograph's bytes several times); then whatever is left, if it has grown or
  // has no size to tell (a pipe).
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::string out;
  resizeResident(out, ec ? 0 : static_cast<std::size_t>(size));
  f.read(out.data(), static_cast<std::streamsize>(out.size()));
  out.resize(static_cast<std::size_t>(f.gcount()));
  char more[65536];
  while (f && f.read(more, sizeof more).gcount() > 0) out.append(more, static_cast<std::size_t>(f.gcount()));
  if (f.bad()) throwInputError(path.string(), step, "reading the file failed");
  return out;
}

}  // namespace surrogate
