// Whether a .tar or .zip read through libarchive ends where it should. libarchive takes a tar
// cut at an entry boundary, or a tar or zip followed by a second archive, for a whole one: the
// tar's blocks are followed here as its bytes are read, and a zip's end records are read back
// from the file. The archive source (archive_source.cpp) asks at its end; the answer tells a
// truncation (damaged) from data appended after the end (trailing).
#include "archive/archive_end.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace surrogate::archive {

void TarLayout::feed(const char* data, std::size_t n) {
  while (n > 0) {
    if (skip_ > 0) {  // an entry's data and padding
      const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(skip_, n));
      if (collect_ > 0) {
        const std::size_t keep = static_cast<std::size_t>(std::min<std::uint64_t>(collect_, take));
        pax_.append(data, keep);
        collect_ -= keep;
      }
      skip_ -= take;
      data += take;
      n -= take;
      offset_ += take;
      if (skip_ == 0 && collecting_) {
        collecting_ = false;
        paxSize_ = paxSize(pax_);
        pax_.clear();
      }
      continue;
    }
    if (state_ == State::Padding) {  // after the end marker: zeros only
      if (!trailingAt_) {
        for (std::size_t i = 0; i < n; ++i)
          if (data[i] != 0) {
            trailingAt_ = offset_ + i;
            break;
          }
      }
      offset_ += n;
      return;
    }
    const std::size_t take = std::min(n, 512 - block_.size());
    block_.append(data, take);
    data += take;
    n -= take;
    offset_ += take;
    if (block_.size() == 512) {
      header(offset_ - 512);
      block_.clear();
    }
  }
}

std::string TarLayout::problem(bool& truncation) const {
  truncation = true;
  if (broken_) return *broken_;
  if (skip_ > 0 || !block_.empty())
    return "it ends inside an entry or a 512-byte block, at byte " + std::to_string(offset_);
  if (state_ == State::Header)
    return "it ends at byte " + std::to_string(offset_) +
           " without the tar end-of-archive marker: it was cut at an entry boundary";
  if (state_ == State::SecondZero)
    return "it ends after the first of the two end-of-archive blocks";
  if (trailingAt_) {
    truncation = false;
    return std::to_string(offset_ - *trailingAt_) + " bytes from byte " +
           std::to_string(*trailingAt_) + ", after the end-of-archive marker at byte " +
           std::to_string(endAt_);
  }
  // After the marker, writers pad with zeros to the end of their last record, whose size
  // varies (10240 bytes for most, pack's are larger): only whole 512-byte blocks of zeros.
  if (offset_ % 512 != 0)
    return "it ends inside a 512-byte block of its end padding, at byte " + std::to_string(offset_);
  return "";
}

bool TarLayout::zero(const std::string& block) {
  return std::all_of(block.begin(), block.end(), [](char c) { return c == 0; });
}

std::optional<std::uint64_t> TarLayout::number(const char* field, std::size_t size) {
  const auto* u = reinterpret_cast<const unsigned char*>(field);
  if (u[0] & 0x80) {
    if (u[0] != 0x80) return std::nullopt;  // negative or too large
    std::uint64_t v = 0;
    for (std::size_t i = 1; i < size; ++i) {
      if (v >> 56) return std::nullopt;
      v = (v << 8) | u[i];
    }
    return v;
  }
  std::size_t i = 0;
  while (i < size && (field[i] == ' ' || field[i] == 0)) ++i;
  std::uint64_t v = 0;
  bool digits = false;
  for (; i < size && field[i] >= '0' && field[i] <= '7'; ++i) {
    v = v * 8 + static_cast<std::uint64_t>(field[i] - '0');
    digits = true;
  }
  for (; i < size; ++i)
    if (field[i] != ' ' && field[i] != 0) return std::nullopt;
  return digits ? std::optional<std::uint64_t>(v) : std::optional<std::uint64_t>(0);
}

std::optional<std::uint64_t> TarLayout::paxSize(const std::string& text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t space = text.find(' ', at);
    if (space == std::string::npos) break;
    const std::uint64_t length = std::strtoull(text.c_str() + at, nullptr, 10);
    // The record holds its own "<length> " and ends with a newline, inside the text.
    if (length <= space - at + 1 || length > text.size() - at) break;
    const std::string record = text.substr(space + 1, at + length - space - 2);
    if (record.compare(0, 5, "size=") == 0) {
      const std::string digits = record.substr(5);
      if (!digits.empty() && digits.size() < 20 &&
          std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return std::strtoull(digits.c_str(), nullptr, 10);
    }
    at += length;
  }
  return std::nullopt;
}

void TarLayout::header(std::uint64_t at) {
  if (zero(block_)) {
    if (state_ == State::Header) {
      endAt_ = at;
      state_ = State::SecondZero;
    } else {
      state_ = State::Padding;
    }
    return;
  }
  if (state_ == State::SecondZero) {  // one zero block, then more: what follows is not ours
    trailingAt_ = at;
    state_ = State::Padding;
    return;
  }
  const auto size = number(block_.data() + 124, 12);
  if (!size) {
    if (!broken_) broken_ = "the tar header at byte " + std::to_string(at) + " is malformed";
    state_ = State::Padding;
    return;
  }
  const char type = block_[156];
  std::uint64_t bytes = *size;
  if (type == 'x' || type == 'g' || type == 'L' || type == 'K') {
    if (type == 'x' && bytes <= (1u << 20)) {
      collecting_ = true;
      collect_ = bytes;
      pax_.clear();
    }
  } else {
    if (paxSize_) bytes = *paxSize_;
    paxSize_.reset();
    // Links, devices, folders and FIFOs have no data blocks.
    if (type >= '1' && type <= '6') bytes = 0;
  }
  skip_ = (bytes + 511) / 512 * 512;
  if (skip_ == 0 && collecting_) {
    collecting_ = false;
    collect_ = 0;
  }
}

std::string zipEndProblem(int fd, std::uint64_t fileSize, std::uint64_t entriesRead, bool& truncation) {
  truncation = true;
  auto u16 = [](const unsigned char* p) { return std::uint64_t(p[0]) | std::uint64_t(p[1]) << 8; };
  auto u32 = [&](const unsigned char* p) { return u16(p) | u16(p + 2) << 16; };
  auto u64 = [&](const unsigned char* p) { return u32(p) | u32(p + 4) << 32; };
  const std::uint64_t tail = std::min<std::uint64_t>(fileSize, 22 + 65535);
  std::vector<unsigned char> buffer(static_cast<std::size_t>(tail));
  if (tail < 22 || ::pread(fd, buffer.data(), buffer.size(), static_cast<off_t>(fileSize - tail)) !=
                       static_cast<ssize_t>(tail))
    return "it is too short to hold a zip end-of-central-directory record";
  const std::uint64_t base = fileSize - tail;
  // The last record whose comment reaches at least to its own end; its end must be the file's.
  for (std::size_t i = buffer.size() - 22 + 1; i-- > 0;) {
    const unsigned char* p = buffer.data() + i;
    if (u32(p) != 0x06054b50) continue;
    const std::uint64_t at = base + i;
    const std::uint64_t end = at + 22 + u16(p + 20);
    if (end > fileSize) continue;  // a signature inside other data, or a cut comment
    if (end < fileSize) {
      truncation = false;
      return std::to_string(fileSize - end) + " bytes after the end-of-central-directory record at byte " +
             std::to_string(at);
    }
    std::uint64_t entries = u16(p + 10), cdSize = u32(p + 12), cdOffset = u32(p + 16);
    std::uint64_t cdEnd = at;
    if (entries == 0xFFFF || cdSize == 0xFFFFFFFF || cdOffset == 0xFFFFFFFF) {
      unsigned char locator[20], record[56];
      if (at < 20 || ::pread(fd, locator, 20, static_cast<off_t>(at - 20)) != 20 ||
          u32(locator) != 0x07064b50)
        return "its zip64 end-of-central-directory locator is missing";
      const std::uint64_t recordAt = u64(locator + 8);
      if (recordAt + 56 > at - 20 || ::pread(fd, record, 56, static_cast<off_t>(recordAt)) != 56 ||
          u32(record) != 0x06064b50)
        return "its zip64 end-of-central-directory record is missing";
      entries = u64(record + 32);
      cdSize = u64(record + 40);
      cdOffset = u64(record + 48);
      cdEnd = recordAt;
    }
    if (cdOffset + cdSize != cdEnd) {
      // A whole zip followed by another one: the last end record repeats the offsets of the
      // first (each zip counts from its own start), whose end record then follows its central
      // directory, before the end of the file.
      unsigned char first[22];
      const std::uint64_t firstAt = cdOffset + cdSize;
      if (firstAt + 22 <= at && ::pread(fd, first, 22, static_cast<off_t>(firstAt)) == 22 &&
          u32(first) == 0x06054b50 && u32(first + 16) + u32(first + 12) == firstAt) {
        const std::uint64_t firstEnd = firstAt + 22 + u16(first + 20);
        if (firstEnd < fileSize) {
          truncation = false;
          return std::to_string(fileSize - firstEnd) +
                 " bytes after the end-of-central-directory record at byte " + std::to_string(firstAt);
        }
      }
      return "its central directory (" + std::to_string(cdSize) + " bytes at byte " +
             std::to_string(cdOffset) + ") does not end where the end record begins (byte " +
             std::to_string(cdEnd) + ")";
    }
    if (entries != entriesRead)
      return "its central directory lists " + std::to_string(entries) + " entries, " +
             std::to_string(entriesRead) + " were read";
    return "";
  }
  return "it does not end with a zip end-of-central-directory record: it was cut short, or "
         "other data follow it";
}

}  // namespace surrogate::archive
