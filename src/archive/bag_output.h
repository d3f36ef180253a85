// Private to src/archive: where writeBag (bag.cpp) puts a bag's entries: a folder, or a .tar or
// .zip written by libarchive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "archive/bag.h"

namespace surrogate::archive {

// The entries of one bag, in the order written: begin, its bytes in pieces, end; then close once.
// A failed write throws the Error of writeBag (bag.h) naming the output.
class Sink {
 public:
  virtual ~Sink() = default;
  virtual void begin(const std::string& bagPath, std::uint64_t size) = 0;
  virtual void write(const void* data, std::size_t size) = 0;
  virtual void end() = 0;
  virtual void close() = 0;
};

// The sink of a bag in `format` written at `staging` (the output's temporary name, from
// AtomicFile), whose errors name `out`. Every entry gets the time `epoch`, permissions 0644 and,
// in an archive, owner root and a place under one folder named after `out` ("pkg.zip" ->
// "pkg/"). While an archive's sink lives, its thread writes names as UTF-8 and, for a zip, the
// time zone is UTC, so that the bytes do not depend on the machine.
std::unique_ptr<Sink> openSink(BagFormat format, const std::filesystem::path& staging,
                               const std::filesystem::path& out, std::int64_t epoch);

}  // namespace surrogate::archive
