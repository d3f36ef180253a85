// DecodedStack: the decoded photographs of a capture, each kept once, at its source's depth.
//
// 8-bit sources (JPEG, 8-bit PNG and TIFF) keep one byte a sample, camera raw and 16-bit
// sources two: 36 JPEGs of 6 Mpx take 648 MB, half of what 16-bit copies took. readRows gives
// the samples as Image does (8-bit widened by 257), so readers see the same values whatever
// the depth; readSamples gives them as stored, for readers that work on bytes.
//
// Placement is decided once, before decoding (stages::stackFitsInMemory): in memory when the
// stack fits --memory, as one block with a slot per image that a decoder can write into
// directly (slot, then markStored: no copy, and no zeroing of memory about to be overwritten);
// otherwise in an anonymous temporary file, each image written once with pwrite and read back
// by row bands with pread, so resident memory stays at the bands being processed. The file is
// unlinked at creation: nothing is left behind even if the process is killed.
//
//   DecodedStack stack(36, {3000, 2000, 3, 1, Transfer::Srgb}, DecodedStack::Placement::Memory);
//   decodeInto(stack.slot(i)); stack.markStored(i);   // from any thread, each index once
//   stack.store(i, std::move(pixels.narrow.pixels));   // or: a copy of pixels decoded elsewhere
//   stack.readRows(i, y0, y1, rows);                   // 16-bit, as Image
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/resident.h"
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
  void store(int index, const std::vector<std::uint8_t>& samples);
  void store(int index, const std::vector<std::uint16_t>& samples);
  // In memory: where image `index`'s imageBytes() bytes go, for a decoder to write them in
  // place; nullptr in a temporary file. The image counts as stored once markStored(index) is
  // called. Thread-safe for distinct indices.
  std::uint8_t* slot(int index);
  void markStored(int index);
  // The bytes one image takes: width * height * channels * bytesPerSample.
  std::uint64_t imageBytes() const;

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
  // In memory, a stored row of bytes (8-bit sources). 16-bit samples are not given in place
  // (heldRow stays nullptr): the block holds bytes, which readRows copies out as 16-bit values.
  const std::uint8_t* heldByteRow(int index, int y) const override;
  // Rows [y0, y1) of image `index` as stored: (y1 - y0) * width * channels samples of
  // bytesPerSample bytes each.
  void readSamples(int index, int y0, int y1, void* out) const;
  // Rows [y0, y1) of image `index` where they are held, for readers that need no copy: the
  // stored samples (as readSamples gives them) in memory, or nullptr for a stack kept in a
  // temporary file.
  const std::uint8_t* heldSamples(int index, int y0, int y1) const;

 private:
  std::uint64_t rowBytes() const;
  void checkRows(int index, int y0, int y1) const;
  void checkIndex(int index) const;
  // Image `index` in memory, once stored.
  const std::uint8_t* storedImage(int index) const;
  void storeBytes(int index, const void* samples);
  int count_;
  Format format_;
  Placement placement_;
  // In memory: count_ images of imageBytes() each, left uninitialised until decoded into
  // (16-bit samples in the machine's byte order); stored_[i] says image i was stored.
  MappedBlock block_;
  std::vector<std::uint8_t> stored_;
  int fd_ = -1;  // the temporary file
};

}  // namespace surrogate::pipeline
