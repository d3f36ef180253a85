// SpillStack: an ImageStack whose pixels live in an anonymous temporary file.
//
// A capture of 60 photographs of 24 Mpx is 8.6 GB as 16-bit RGB: more than a workstation
// should hold in memory. When the decoded images do not fit --memory
// (stages::stacksFitInMemory), each is decoded once, written to the spill file with pwrite,
// and read back by row bands with pread: resident memory stays at the bands being processed
// (the operating system's page cache does the rest). The file is unlinked at creation, so
// nothing is left behind even if the process is killed.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "core/stack.h"

namespace surrogate::pipeline {

// The folder spill files go to: `requested`, else $TMPDIR, else /tmp.
std::filesystem::path spillDirectory(const std::filesystem::path& requested = {});
// Bytes an unprivileged process may still write in that folder's file system (statvfs), or
// nothing when it cannot be told.
std::optional<std::uint64_t> spillSpaceAvailable(const std::filesystem::path& directory = {});
// The bytes `count` images of width x height x channels take in a spill file.
std::uint64_t spillBytes(int count, int width, int height, int channels);

class SpillStack : public ImageStack {
 public:
  // Creates an empty stack of `count` images in a temporary file under `directory`
  // ($TMPDIR or /tmp when empty).
  SpillStack(int count, int width, int height, int channels, Transfer transfer,
             const std::filesystem::path& directory = {});
  ~SpillStack() override;
  SpillStack(const SpillStack&) = delete;
  SpillStack& operator=(const SpillStack&) = delete;

  // Stores image `index` (same size and channels as the stack). Thread-safe for distinct
  // indices.
  void write(int index, const Image& image);

  int size() const override { return count_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  int channels() const override { return channels_; }
  Transfer transfer() const override { return transfer_; }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;
  // A whole image (for small images and tests).
  Image read(int index) const;

 private:
  std::uint64_t imageBytes() const;
  int count_, width_, height_, channels_;
  Transfer transfer_;
  int fd_ = -1;
};

}  // namespace surrogate::pipeline
