#include "formats/pronom.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <functional>
#include <set>
#include <unordered_map>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/error.h"
#include "core/text.h"
#include "formats/pronom_signatures.h"

namespace surrogate::formats {

namespace {

constexpr const char* kStep = "format identification";

struct ByteRange {
  unsigned char lo, hi;
};

// A run of bytes (one alternative, or several: "(a|b)"), or a gap of [gapMin, gapMax] bytes.
struct Element {
  bool gap = false;
  std::int64_t gapMin = 0, gapMax = 0;
  std::vector<std::vector<ByteRange>> alternatives;
  std::string exact;  // the bytes, when there is one alternative of single bytes (for memmem)
  bool isExact() const { return !gap && alternatives.size() == 1 && !exact.empty(); }
};

struct Part {
  PronomAnchor anchor;
  std::int64_t min, max;
  std::vector<Element> elements;
  std::int64_t minLength = 0, maxLength = 0;
};

struct Format {
  const PronomFormat* source;
  std::vector<std::vector<Part>> signatures;
};

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

[[noreturn]] void badExpression(const char* expression) {
  throw Error(ErrorKind::Internal, expression, kStep, "a PRONOM signature of the built-in table cannot be read");
}

unsigned char hexByte(const char*& p, const char* expression) {
  const int hi = hexValue(p[0]), lo = hi < 0 ? -1 : hexValue(p[1]);
  if (lo < 0) badExpression(expression);
  p += 2;
  return static_cast<unsigned char>(hi * 16 + lo);
}

// "aa", or "[aa:bb]".
ByteRange byteRange(const char*& p, const char* expression) {
  if (*p != '[') {
    const unsigned char b = hexByte(p, expression);
    return {b, b};
  }
  ++p;
  ByteRange r{};
  r.lo = hexByte(p, expression);
  r.hi = r.lo;
  if (*p == ':') r.hi = hexByte(++p, expression);
  if (*p++ != ']') badExpression(expression);
  return r;
}

std::int64_t number(const char*& p, const char* expression) {
  if (*p < '0' || *p > '9') badExpression(expression);
  std::int64_t v = 0;
  while (*p >= '0' && *p <= '9') v = v * 10 + (*p++ - '0');
  return v;
}

Part compile(const PronomPart& source) {
  Part part{source.anchor, source.min, source.max, {}, 0, 0};
  const char* expression = source.expression;
  for (const char* p = expression; *p;) {
    Element e;
    if (*p == '{') {
      ++p;
      e.gap = true;
      e.gapMin = e.gapMax = number(p, expression);
      if (*p == '-') e.gapMax = number(++p, expression);
      if (*p++ != '}') badExpression(expression);
      part.minLength += e.gapMin;
      part.maxLength += e.gapMax;
      part.elements.push_back(std::move(e));
      continue;
    }
    if (*p == '(') {
      ++p;
      e.alternatives.emplace_back();
      while (*p && *p != ')') {
        if (*p == '|') {
          e.alternatives.emplace_back();
          ++p;
        } else {
          e.alternatives.back().push_back(byteRange(p, expression));
        }
      }
      if (*p++ != ')') badExpression(expression);
    } else {
      e.alternatives.emplace_back();
      while (*p && *p != '{' && *p != '(') e.alternatives.back().push_back(byteRange(p, expression));
    }
    std::size_t shortest = SIZE_MAX, longest = 0;
    for (const auto& a : e.alternatives) {
      shortest = std::min(shortest, a.size());
      longest = std::max(longest, a.size());
    }
    if (e.alternatives.size() == 1) {
      bool single = true;
      for (const ByteRange& r : e.alternatives[0]) single = single && r.lo == r.hi;
      if (single)
        for (const ByteRange& r : e.alternatives[0]) e.exact.push_back(static_cast<char>(r.lo));
    }
    part.minLength += static_cast<std::int64_t>(shortest);
    part.maxLength += static_cast<std::int64_t>(longest);
    part.elements.push_back(std::move(e));
  }
  return part;
}

// The first occurrence of `needle` (not empty) in the `size` bytes at `data`, or nullptr: what
// memmem answers. Sequences PRONOM places anywhere in a file are sought through whole outputs
// (a PNG's "acTL", fmt/935, through its 4.5 MB of compressed pixels), which glibc's memmem
// read at about 1 GB/s; with SSE2, 16 places are tested at once on the needle's first and last
// bytes and only places where both agree are compared whole (in compressed data, one place in
// 65536), several times faster.
const char* find(const char* data, std::size_t size, const std::string& needle) {
  const std::size_t length = needle.size();
  if (length > size) return nullptr;
  std::size_t start = 0;
#if defined(__SSE2__)
  constexpr std::size_t kBlock = 16;
  if (length >= 2) {
    const __m128i first = _mm_set1_epi8(needle[0]), last = _mm_set1_epi8(needle[length - 1]);
    // Places start .. start + 15, each needing its last byte at place + length - 1 < size.
    for (; start + length - 1 + kBlock <= size; start += kBlock) {
      const __m128i atFirst = _mm_loadu_si128(reinterpret_cast<const __m128i*>(data + start));
      const __m128i atLast = _mm_loadu_si128(reinterpret_cast<const __m128i*>(data + start + length - 1));
      auto mask = static_cast<unsigned>(
          _mm_movemask_epi8(_mm_and_si128(_mm_cmpeq_epi8(atFirst, first), _mm_cmpeq_epi8(atLast, last))));
      for (; mask != 0; mask &= mask - 1) {
        const char* place = data + start + static_cast<std::size_t>(__builtin_ctz(mask));
        if (std::memcmp(place + 1, needle.data() + 1, length - 2) == 0) return place;
      }
    }
  }
#endif
  // The places too near the end for a whole block (or every place without SSE2).
  return static_cast<const char*>(memmem(data + start, size - start, needle.data(), length));
}

const std::vector<Format>& formats() {
  static const std::vector<Format> kCompiled = [] {
    std::vector<Format> out;
    for (const PronomFormat& f : pronomFormats()) {
      Format c{&f, {}};
      for (const auto& signature : f.signatures) {
        c.signatures.emplace_back();
        for (const PronomPart& p : signature) c.signatures.back().push_back(compile(p));
      }
      out.push_back(std::move(c));
    }
    return out;
  }();
  return kCompiled;
}

// The indices of formats() in the order identifyPronom tries them: a format before every format
// it has priority over (the table's order otherwise; should priorities ever form a cycle, its
// formats come last, in the table's order, which changes nothing but the time taken).
const std::vector<std::size_t>& matchOrder() {
  static const std::vector<std::size_t> kOrder = [] {
    const std::vector<Format>& all = formats();
    std::unordered_map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < all.size(); ++i) index.emplace(all[i].source->puid, i);
    std::vector<int> winners(all.size(), 0);  // formats with priority over each, not yet placed
    for (const Format& f : all)
      for (const char* loser : f.source->priorityOver)
        if (auto it = index.find(loser); it != index.end()) ++winners[it->second];
    std::vector<std::size_t> order;
    std::vector<bool> placed(all.size(), false);
    for (bool progress = true; progress;) {
      progress = false;
      for (std::size_t i = 0; i < all.size(); ++i) {
        if (placed[i] || winners[i] != 0) continue;
        placed[i] = true;
        progress = true;
        order.push_back(i);
        for (const char* loser : all[i].source->priorityOver)
          if (auto it = index.find(loser); it != index.end()) --winners[it->second];
        break;  // the first format free to go, in the table's order
      }
    }
    for (std::size_t i = 0; i < all.size(); ++i)
      if (!placed[i]) order.push_back(i);
    return order;
  }();
  return kOrder;
}

using OnEnd = std::function<bool(std::int64_t)>;

// The bytes of one file, and what is known of where each exact byte string sought in them
// occurs. A string sought after a gap is sought again from every place the part before it
// matches; without this memory a file made of that part (2 MB of Nikon's "7C92") took 7 s,
// each match reading the next 35 KB again. With it the bytes after `from` are read once per
// string, however many times it is sought.
class Bytes {
 public:
  static constexpr std::int64_t kNone = INT64_MAX;

  explicit Bytes(std::string_view data) : data_(data) {}
  std::string_view view() const { return data_; }
  std::int64_t size() const { return static_cast<std::int64_t>(data_.size()); }

  // The first occurrence of `needle` starting in [from, last]; kNone when there is none.
  std::int64_t next(const std::string& needle, std::int64_t from, std::int64_t last) {
    const auto length = static_cast<std::int64_t>(needle.size());
    last = std::min(last, size() - length);
    if (from > last) return kNone;
    Known& k = known_[&needle];
    std::int64_t start = from;
    if (k.from >= 0 && from >= k.from) {
      if (k.at != kNone && from <= k.at) return k.at <= last ? k.at : kNone;
      if (k.at == kNone) {
        if (last < k.searchedTo) return kNone;
        start = std::max(from, k.searchedTo);
      }
    }
    const char* hit = find(data_.data() + start, static_cast<std::size_t>(last + length - start), needle);
    k.from = from;
    k.at = hit ? hit - data_.data() : kNone;
    k.searchedTo = hit ? k.at : last + 1;
    return k.at;
  }

 private:
  // No occurrence starts in [from, searchedTo); `at` is the one at searchedTo, or kNone when
  // the search stopped there.
  struct Known {
    std::int64_t from = -1, searchedTo = -1, at = kNone;
  };
  std::string_view data_;
  std::unordered_map<const std::string*, Known> known_;
};

// Calls onEnd with each position where elements[i...] placed at `at` end, until it returns true.
bool matchElements(Bytes& bytes, const std::vector<Element>& elements, std::size_t i, std::int64_t at,
                   const OnEnd& onEnd) {
  const std::string_view d = bytes.view();
  const std::int64_t n = bytes.size();
  if (i == elements.size()) return onEnd(at);
  const Element& e = elements[i];
  if (e.gap) {
    const std::int64_t first = at + e.gapMin, last = std::min(at + e.gapMax, n);
    if (first > n) return false;
    if (i + 1 < elements.size() && elements[i + 1].isExact()) {
      // Jump from one occurrence of the bytes after the gap to the next.
      const std::string& next = elements[i + 1].exact;
      for (std::int64_t p = bytes.next(next, first, last); p != Bytes::kNone; p = bytes.next(next, p + 1, last))
        if (matchElements(bytes, elements, i + 1, p, onEnd)) return true;
      return false;
    }
    for (std::int64_t p = first; p <= last; ++p)
      if (matchElements(bytes, elements, i + 1, p, onEnd)) return true;
    return false;
  }
  for (const auto& alternative : e.alternatives) {
    const auto length = static_cast<std::int64_t>(alternative.size());
    if (at + length > n) continue;
    bool same = true;
    for (std::int64_t k = 0; same && k < length; ++k) {
      const auto b = static_cast<unsigned char>(d[static_cast<std::size_t>(at + k)]);
      same = b >= alternative[static_cast<std::size_t>(k)].lo && b <= alternative[static_cast<std::size_t>(k)].hi;
    }
    if (same && matchElements(bytes, elements, i + 1, at + length, onEnd)) return true;
  }
  return false;
}

// Tries the part at every start in [first, last] (clamped to the data), in order.
bool matchStarts(Bytes& bytes, const Part& part, std::int64_t first, std::int64_t last, const OnEnd& onEnd) {
  first = std::max<std::int64_t>(first, 0);
  last = std::min(last, bytes.size() - part.minLength);
  if (first > last) return false;
  if (!part.elements.empty() && part.elements[0].isExact()) {
    const std::string& head = part.elements[0].exact;
    for (std::int64_t s = bytes.next(head, first, last); s != Bytes::kNone; s = bytes.next(head, s + 1, last))
      if (matchElements(bytes, part.elements, 0, s, onEnd)) return true;
    return false;
  }
  for (std::int64_t s = first; s <= last; ++s)
    if (matchElements(bytes, part.elements, 0, s, onEnd)) return true;
  return false;
}

// Whether parts[k...] match, the part before having ended at previousEnd.
bool matchParts(Bytes& bytes, const std::vector<Part>& parts, std::size_t k, std::int64_t previousEnd) {
  if (k == parts.size()) return true;
  const Part& part = parts[k];
  const std::int64_t n = bytes.size();
  const OnEnd next = [&](std::int64_t end) { return matchParts(bytes, parts, k + 1, end); };
  switch (part.anchor) {
    case PronomAnchor::Bof:
      return matchStarts(bytes, part, part.min, part.max < 0 ? n : part.max, next);
    case PronomAnchor::AfterPrevious:
      return matchStarts(bytes, part, previousEnd + part.min, part.max < 0 ? n : previousEnd + part.max, next);
    case PronomAnchor::Eof: {
      const std::int64_t lastEnd = n - part.min, firstEnd = n - part.max;
      const OnEnd fromEnd = [&](std::int64_t end) { return end >= firstEnd && end <= lastEnd && next(end); };
      return matchStarts(bytes, part, firstEnd - part.maxLength, lastEnd - part.minLength, fromEnd);
    }
  }
  return false;
}

}  // namespace

std::string PronomIdentity::describe() const {
  if (identified() && fromText)
    return name + " (" + puid + ", named from its text" + (puid == "x-fmt/111" ? "" : " and its name's extension") +
           " as Siegfried and fido name it: PRONOM gives it no signature)";
  if (identified()) return name + (version.empty() ? "" : " " + version) + " (" + puid + ")";
  if (matches.empty()) return "no PRONOM signature matches";
  std::string list;
  for (const std::string& m : matches) list += (list.empty() ? "" : ", ") + m;
  return "PRONOM signatures of several formats match: " + list;
}

PronomIdentity identifyPronom(std::string_view data) {
  Bytes bytes(data);
  const std::vector<Format>& all = formats();
  // A format need not be matched when a format already matched has priority over it and over
  // every format it has priority over: matching or not, it is set aside and sets aside nothing
  // more, so the identification is the same. Formats are tried winners first (matchOrder) so
  // that a PNG 1.2's iTXt match spares the whole-file searches for the chunks of PNG 1.1.
  std::set<std::string> setAside;
  std::vector<bool> matched(all.size(), false);
  for (const std::size_t i : matchOrder()) {
    const Format& f = all[i];
    const auto isSetAside = [&](const char* puid) { return setAside.count(puid) != 0; };
    if (isSetAside(f.source->puid) &&
        std::all_of(f.source->priorityOver.begin(), f.source->priorityOver.end(), isSetAside))
      continue;
    for (const auto& signature : f.signatures)
      if (matchParts(bytes, signature, 0, 0)) {
        matched[i] = true;
        for (const char* loser : f.source->priorityOver) setAside.insert(loser);
        break;
      }
  }
  PronomIdentity id;
  const PronomFormat* only = nullptr;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const PronomFormat* f = all[i].source;
    if (!matched[i] || setAside.count(f->puid)) continue;
    id.matches.push_back(f->puid);
    only = f;
  }
  if (id.matches.size() == 1) {
    id.puid = only->puid;
    id.name = only->name;
    id.version = only->version;
  }
  return id;
}

bool isPlainText(std::string_view bytes) {
  if (bytes.empty()) return false;
  for (const char ch : bytes) {
    const auto b = static_cast<unsigned char>(ch);
    if ((b < 0x20 && b != '\t' && b != '\n' && b != '\r' && b != '\v' && b != '\f') || b == 0x7f) return false;
  }
  return isValidUtf8(std::string(bytes));
}

PronomIdentity identifyPronomNamed(std::string_view bytes, const std::string& fileName) {
  PronomIdentity id = identifyPronom(bytes);
  // Several matching formats stay ambiguous; text is only the answer when no signature matches.
  if (!id.matches.empty() || !isPlainText(bytes)) return id;
  const std::string lower = lowerCase(fileName);
  auto endsWith = [&](const std::string& tail) {
    return lower.size() > tail.size() && lower.compare(lower.size() - tail.size(), tail.size(), tail) == 0;
  };
  id.fromText = true;
  if (endsWith(".json")) {
    id.puid = "fmt/817";
    id.name = "JSON Data Interchange Format";
  } else if (endsWith(".js")) {
    id.puid = "x-fmt/423";
    id.name = "JavaScript file";
  } else {
    id.puid = "x-fmt/111";
    id.name = "Plain Text File";
  }
  id.matches = {id.puid};
  return id;
}

PronomIdentity identifyPronomFile(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw Error(ErrorKind::Input, file.string(), kStep, std::string("cannot be opened: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int code = errno;
    ::close(fd);
    throw Error(ErrorKind::Input, file.string(), kStep, std::string("cannot be read: ") + std::strerror(code));
  }
  if (st.st_size == 0) {
    ::close(fd);
    return identifyPronomNamed({}, file.filename().string());
  }
  void* mapped = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
  const int code = errno;
  ::close(fd);
  if (mapped == MAP_FAILED)
    throw Error(ErrorKind::Input, file.string(), kStep, std::string("cannot be read: ") + std::strerror(code));
  struct Unmap {
    void* p;
    std::size_t n;
    ~Unmap() { ::munmap(p, n); }
  } unmap{mapped, static_cast<std::size_t>(st.st_size)};
  return identifyPronomNamed(std::string_view(static_cast<const char*>(mapped), unmap.n), file.filename().string());
}

std::string pronomRelease() { return kPronomRelease; }

}  // namespace surrogate::formats
