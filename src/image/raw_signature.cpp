#include "image/raw_signature.h"

#include <cstring>
#include <fstream>

namespace surrogate::image {

namespace {
bool at(const unsigned char* h, std::size_t n, std::size_t offset, const char* sig, std::size_t len) {
  return n >= offset + len && std::memcmp(h + offset, sig, len) == 0;
}
}  // namespace

RawContainer rawContainerOf(const unsigned char* h, std::size_t n) {
  if (at(h, n, 0, "II*\0", 4) || at(h, n, 0, "MM\0*", 4)) return RawContainer::Tiff;
  if (at(h, n, 6, "HEAPCCDR", 8)) return RawContainer::Ciff;
  if (at(h, n, 4, "ftypcrx ", 8)) return RawContainer::Cr3;
  if (at(h, n, 0, "FUJIFILM", 8) || at(h, n, 0, "IIRO", 4) || at(h, n, 0, "IIRS", 4) ||
      at(h, n, 0, "MMOR", 4) || at(h, n, 0, "IIU\0", 4) || at(h, n, 0, "FOVb", 4) ||
      at(h, n, 0, "\0MRM", 4))
    return RawContainer::Other;
  return RawContainer::None;
}

RawContainer rawContainerOf(const std::filesystem::path& path) {
  unsigned char head[16] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  return rawContainerOf(head, static_cast<std::size_t>(in.gcount()));
}

}  // namespace surrogate::image
