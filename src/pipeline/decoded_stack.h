// DecodedStack: the decoded photographs of a capture, each kept once, at its source's depth.
//
// 8-bit sources (JPEG, 8-bit PNG and TIFF) keep one byte a sample, camera raw and 16-bit
// sources two: 36 JPEGs of 6 Mpx take 648 MB, half of what 16-bit copies took. readRows gives
// the samples as Image does (8-bit widened by 257), so readers see the same values whatever
// the depth; readSamples gives them as stored, for readers that work on bytes.
//
// Placement is decided once, before decoding (stages::stackFitsInMemory): in memory when the
// stack fits --memory, where each decoded image is moved in without a copy; otherwise in an
// anonymous temporary file, each image written once with pwrite and read back by row bands
// with pread, so resident memory stays at the bands being processed. The file is unlinked at
// creation: nothing is left behind even if the process is killed.
//
//   DecodedStack stack(36, {3000, 2000, 3, 1, Transfer::Srgb}, DecodedStack::Placement::Memory);
//   stack.store(i, std::move(pixels.narrow.pixels));   // from any thread, each index once
//   stack.readRows(i, y0, y1, rows);                   // 16-bit, as Image
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "core/stack.h"

namespace surrogate::pipeline {

// The folder spill files go to: `requested`, else $TMPDIR, else /tmp.
std::filesystem::path spillDirectory(const std::filesystem::path& requested = {});
// Bytes an unprivileged process may still write in that folder's file system (statvfs), or
// nothing when it cannot be told.
std::optional<std::uint64_t> spillSpaceAvailable(const std::filesystem::path& directory = {});

class DecodedStack : public ImageStack {
 public:
  enum class Placement { Memory, TemporaryFile };
  struct Format {
    int width = 0, height = 0;
    int channels = 0;        // 1 or 3
    int bytesPerSample = 0;  // 1 (8-bit source) or 2
    Transfer transfer = Transfer::Srgb;
  };

  // An empty stack of `count` images; a temporary file is created under `directory` ($TMPDIR
  // or /tmp when empty) for Placement::TemporaryFile.
  DecodedStack(int count, Format format, Placement placement, const std::filesystem::path& directory = {});
  ~DecodedStack() override;
  DecodedStack(const DecodedStack&) = delete;
  DecodedStack& operator=(const DecodedStack&) = delete;

  // Stores image `index`: its samples in Image's layout, of the stack's depth (8-bit samples
  // for bytesPerSample 1, 16-bit for 2) and size. Thread-safe for distinct indices.
  void store(int index, std::vector<std::uint8_t> samples);
  void store(int index, std::vector<std::uint16_t> samples);

  const Format& format() const { return format_; }
  Placement placement() const { return placement_; }
  // The bytes `count` images of `format` take (in memory or in the file).
  static std::uint64_t bytesFor(int count, const Format& format);

  int size() const override { return count_; }
  int width() const override { return format_.width; }
  int height() const override { return format_.height; }
  int channels() const override { return format_.channels; }
  Transfer transfer() const override { return format_.transfer; }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override;
  // Rows [y0, y1) of image `index` as stored: (y1 - y0) * width * channels samples of
  // bytesPerSample bytes each.
  void readSamples(int index, int y0, int y1, void* out) const;

 private:
  std::uint64_t rowBytes() const;
  std::uint64_t imageBytes() const;
  void checkRows(int index, int y0, int y1) const;
  int count_;
  Format format_;
  Placement placement_;
  std::vector<std::vector<std::uint8_t>> narrow_;  // in memory, 8-bit
  std::vector<std::vector<std::uint16_t>> wide_;   // in memory, 16-bit
  int fd_ = -1;                                    // the temporary file
};

}  // namespace surrogate::pipeline
