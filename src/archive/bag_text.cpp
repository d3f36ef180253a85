#include "archive/bag_text.h"

#include <iconv.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <map>

#include "core/digest.h"
#include "core/file_names.h"
#include "core/text.h"

namespace surrogate::archive {

namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return s.substr(b, e - b);
}

}  // namespace

std::optional<std::string> safeBagPath(const std::string& raw, std::string* why,
                                       std::size_t maxLength) {
  auto fail = [&](const std::string& reason) -> std::optional<std::string> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (raw.empty()) return fail("the path is empty");
  if (raw.size() > maxLength)
    return fail("the path is longer than " + std::to_string(maxLength) + " bytes");
  // The characters no package can hold: the rule the capture scan and pack apply too.
  if (const std::string what = unholdableCharacters(raw); !what.empty()) return fail("the path " + what);
  if (raw[0] == '/') return fail("the path is absolute");
  if (raw[0] == '~') return fail("the path starts with '~' (a home directory)");
  if (raw.size() >= 2 && std::isalpha(static_cast<unsigned char>(raw[0])) && raw[1] == ':')
    return fail("the path starts with a drive letter");
  std::string path = raw;
  while (path.size() >= 2 && path.compare(0, 2, "./") == 0) path.erase(0, 2);
  if (path.empty()) return fail("the path names the bag itself");
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const std::string segment =
        path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (segment == "..") return fail("the path contains \"..\" (it would leave the bag)");
    if (segment == ".") return fail("the path contains a \".\" segment");
    if (segment.empty()) return fail("the path contains an empty segment (\"//\")");
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return path;
}

std::string percentDecode(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      const std::string code = lowerCase(text.substr(i + 1, 2));
      if (code == "0d") { out += '\r'; i += 2; continue; }
      if (code == "0a") { out += '\n'; i += 2; continue; }
      if (code == "25") { out += '%'; i += 2; continue; }
    }
    out += text[i];
  }
  return out;
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::string current;
  bool pending = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n' || c == '\r') {
      lines.push_back(current);
      current.clear();
      pending = false;
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    } else {
      current += c;
      pending = true;
    }
  }
  if (pending) lines.push_back(current);
  return lines;
}

Declaration parseDeclaration(const std::string& text) {
  Declaration d;
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0)
    d.problems.push_back("starts with a byte-order mark, which RFC 8493 forbids");
  const std::vector<std::string> lines = splitLines(text);
  if (lines.size() != 2) {
    d.problems.push_back("must have exactly two lines (BagIt-Version and "
                         "Tag-File-Character-Encoding), has " + std::to_string(lines.size()));
  }
  if (!isValidUtf8(text)) d.problems.push_back("is not valid UTF-8 (RFC 8493 requires it)");
  if (!lines.empty()) {
    const std::string prefix = "BagIt-Version: ";
    if (lines[0].compare(0, prefix.size(), prefix) != 0)
      d.problems.push_back("line 1 must be \"BagIt-Version: 1.0\"");
    else
      d.version = lines[0].substr(prefix.size());
    // 1.0 is RFC 8493; 0.93 to 0.97 are the drafts before it, which bags made years ago
    // declare (their older bag-info.txt is package-info.txt, a tag file like any other here).
    const bool known = d.version == "1.0" || d.version == "0.97" || d.version == "0.96" ||
                       d.version == "0.95" || d.version == "0.94" || d.version == "0.93";
    if (!d.version.empty() && !known)
      d.problems.push_back("BagIt-Version " + d.version.substr(0, 40) +
                           " is not 1.0 (or one of the drafts 0.93 to 0.97)");
  }
  if (lines.size() >= 2) {
    const std::string prefix = "Tag-File-Character-Encoding: ";
    if (lines[1].compare(0, prefix.size(), prefix) != 0)
      d.problems.push_back("line 2 must be \"Tag-File-Character-Encoding: UTF-8\"");
    else
      d.encoding = lines[1].substr(prefix.size());
    if (!d.encoding.empty() && !tagEncodingSupported(d.encoding))
      d.problems.push_back("tag files are declared as " + d.encoding.substr(0, 60) +
                           ", an encoding this verifier cannot read (UTF-8, UTF-16, "
                           "ISO-8859-1 and the others iconv knows)");
  }
  return d;
}

namespace {

bool isUtf8Name(const std::string& encoding) {
  const std::string e = lowerCase(encoding);
  return e == "utf-8" || e == "utf8";
}

// An iconv descriptor from `encoding` to UTF-8, closed on scope exit.
struct Converter {
  iconv_t cd;
  explicit Converter(const std::string& encoding)
      : cd(iconv_open("UTF-8", encoding.c_str())) {}
  ~Converter() {
    if (ok()) iconv_close(cd);
  }
  Converter(const Converter&) = delete;
  Converter& operator=(const Converter&) = delete;
  bool ok() const { return cd != reinterpret_cast<iconv_t>(-1); }
};

// Encoding names are short words; anything else is refused before iconv sees it.
bool plausibleEncodingName(const std::string& encoding) {
  if (encoding.empty() || encoding.size() > 40) return false;
  return std::all_of(encoding.begin(), encoding.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ||
           c == ':';
  });
}

}  // namespace

bool tagEncodingSupported(const std::string& encoding) {
  if (isUtf8Name(encoding)) return true;
  if (!plausibleEncodingName(encoding)) return false;
  return Converter(encoding).ok();
}

std::optional<std::string> decodeTagText(const std::string& bytes, const std::string& encoding,
                                         std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<std::string> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (isUtf8Name(encoding)) return bytes;
  if (!plausibleEncodingName(encoding)) return fail("the encoding "" + encoding.substr(0, 60) + "" is unknown");
  Converter converter(encoding);
  if (!converter.ok()) return fail("the encoding " + encoding + " is unknown to iconv");
  std::string out;
  out.resize(bytes.size() * 2 + 16);
  char* in = const_cast<char*>(bytes.data());
  std::size_t inLeft = bytes.size();
  std::size_t done = 0;
  while (true) {
    char* outPtr = out.data() + done;
    std::size_t outLeft = out.size() - done;
    const std::size_t r = iconv(converter.cd, inLeft ? &in : nullptr, &inLeft, &outPtr, &outLeft);
    done = out.size() - outLeft;
    if (r != static_cast<std::size_t>(-1)) {
      if (inLeft == 0) break;
      continue;
    }
    if (errno == E2BIG) {
      out.resize(out.size() * 2);
      continue;
    }
    const std::size_t at = bytes.size() - inLeft;
    return fail((errno == EINVAL ? "ends in the middle of a character" : "is not valid " + encoding) +
                std::string(" (byte ") + std::to_string(at) + ")");
  }
  out.resize(done);
  // A UTF-8 byte-order mark is what iconv writes for a BOM it was not asked to consume.
  if (out.compare(0, 3, "\xEF\xBB\xBF") == 0) out.erase(0, 3);
  return out;
}

std::vector<std::string> BagInfo::values(const std::string& label) const {
  std::vector<std::string> out;
  for (const auto& [k, v] : fields)
    if (lowerCase(k) == lowerCase(label)) out.push_back(v);
  return out;
}

BagInfo parseBagInfo(const std::string& text) {
  BagInfo info;
  if (!isValidUtf8(text)) info.problems.push_back("is not valid UTF-8");
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0)
    info.problems.push_back("starts with a byte-order mark");
  int number = 0;
  for (const std::string& line : splitLines(text)) {
    ++number;
    if (line.empty()) continue;
    if (line[0] == ' ' || line[0] == '\t') {
      if (info.fields.empty()) {
        info.problems.push_back("line " + std::to_string(number) +
                                ": a continuation line with no label before it");
        continue;
      }
      info.fields.back().second += " " + trim(line);
      continue;
    }
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos || colon == 0) {
      info.problems.push_back("line " + std::to_string(number) + ": not \"Label: value\"");
      continue;
    }
    const std::string label = line.substr(0, colon);
    if (trim(label) != label) {
      info.departures.push_back("line " + std::to_string(number) + ": whitespace around the "
                                "label \"" + trim(label) + "\" (RFC 8493 writes \"Label: value\"; "
                                "read as \"" + trim(label) + "\")");
    }
    info.fields.emplace_back(trim(label), trim(line.substr(colon + 1)));
  }
  // RFC 8493 section 2.2.2: each of these SHOULD NOT be repeated.
  for (const char* once :
       {"Payload-Oxum", "Bagging-Date", "Bag-Size", "Bag-Count", "Bag-Group-Identifier"}) {
    if (info.values(once).size() > 1)
      info.departures.push_back(std::string(once) + " is repeated (" +
                                std::to_string(info.values(once).size()) +
                                " times); RFC 8493 says it should be given once");
  }
  return info;
}

std::optional<std::pair<std::uint64_t, std::uint64_t>> parseOxum(const std::string& value) {
  const std::size_t dot = value.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 >= value.size()) return std::nullopt;
  auto number = [](const std::string& s) -> std::optional<std::uint64_t> {
    if (s.empty() || s.size() > 19) return std::nullopt;
    std::uint64_t n = 0;
    for (char c : s) {
      if (c < '0' || c > '9') return std::nullopt;
      n = n * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return n;
  };
  const auto octets = number(value.substr(0, dot));
  const auto streams = number(value.substr(dot + 1));
  if (!octets || !streams) return std::nullopt;
  return std::make_pair(*octets, *streams);
}

Manifest parseManifest(const std::string& text, const std::string& algorithm,
                       std::size_t hexLength) {
  Manifest m;
  m.algorithm = algorithm;
  if (!isValidUtf8(text)) m.problems.push_back("is not valid UTF-8");
  std::map<std::string, std::pair<std::string, int>> seen;  // path -> checksum, line
  int number = 0;
  for (const std::string& line : splitLines(text)) {
    ++number;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (trim(line).empty()) continue;
    std::size_t gap = 0;
    while (gap < line.size() && line[gap] != ' ' && line[gap] != '\t') ++gap;
    std::size_t pathStart = gap;
    while (pathStart < line.size() && (line[pathStart] == ' ' || line[pathStart] == '\t'))
      ++pathStart;
    if (gap == line.size() || pathStart == line.size()) {
      m.problems.push_back(where + "not \"<checksum> <path>\"");
      continue;
    }
    std::string checksum = lowerCase(line.substr(0, gap));
    const bool hex = std::all_of(checksum.begin(), checksum.end(), [](char c) {
      return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
    });
    if (!hex || (hexLength != 0 && checksum.size() != hexLength)) {
      m.problems.push_back(where + "\"" + checksum.substr(0, 140) + "\" is not a " +
                           algorithm + " checksum");
      continue;
    }
    // md5sum's binary-mode marker: exactly one space, then '*' before the path.
    if (pathStart == gap + 1 && line[gap] == ' ' && line[pathStart] == '*' &&
        pathStart + 1 < line.size()) {
      ++pathStart;
      m.departures.push_back(where + "\"*" + line.substr(pathStart, 200) + "\": the '*' is md5sum's "
                             "binary-mode marker, read as " + line.substr(pathStart, 200));
    }
    std::string why;
    const std::string decoded = percentDecode(line.substr(pathStart));
    const auto path = safeBagPath(decoded, &why);
    if (!path) {
      m.problems.push_back(where + "\"" + decoded.substr(0, 200) + "\": " + why);
      continue;
    }
    const auto [earlier, first] = seen.emplace(*path, std::make_pair(checksum, number));
    if (!first) {
      const std::string before = "line " + std::to_string(earlier->second.second);
      if (earlier->second.first == checksum)
        m.repeats.push_back(where + *path + " is listed again with the same checksum (" + before + ")");
      else
        m.problems.push_back(where + *path + " is listed twice with different checksums (" +
                             before + ")");
      continue;
    }
    m.entries.push_back({checksum, *path, number});
  }
  return m;
}

std::optional<std::pair<std::string, std::string>> manifestName(const std::string& path) {
  for (const std::string kind : {"tagmanifest", "manifest"}) {
    const std::string prefix = kind + "-";
    if (path.size() > prefix.size() + 4 && path.compare(0, prefix.size(), prefix) == 0 &&
        path.compare(path.size() - 4, 4, ".txt") == 0 && path.find('/') == std::string::npos) {
      return std::make_pair(kind, path.substr(prefix.size(), path.size() - prefix.size() - 4));
    }
  }
  return std::nullopt;
}

std::size_t digestHexLength(const std::string& algorithm) {
  if (algorithm == "sha256") return 64;
  if (algorithm == "sha512") return 128;
  return 2 * namedDigestSize(algorithm);
}

bool isLegacyAlgorithm(const std::string& algorithm) {
  for (const char* weak : {"md5", "sha1", "md4", "md5-sha1", "md5_sha1", "ripemd160", "rmd160", "mdc2"})
    if (algorithm == weak) return true;
  return false;
}

Fetch parseFetch(const std::string& text) {
  Fetch f;
  if (!isValidUtf8(text)) f.problems.push_back("is not valid UTF-8");
  auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
  int number = 0;
  for (const std::string& line : splitLines(text)) {
    ++number;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (trim(line).empty()) continue;
    // Two words, then the rest of the line: the path may hold spaces.
    std::size_t i = 0;
    std::string words[2];
    for (std::string& word : words) {
      while (i < line.size() && isSpace(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !isSpace(line[i])) ++i;
      word = line.substr(start, i - start);
    }
    while (i < line.size() && isSpace(line[i])) ++i;
    if (words[1].empty() || i == line.size()) {
      f.problems.push_back(where + "not \"<url> <length or -> <path>\"");
      continue;
    }
    FetchEntry e;
    e.url = words[0];
    e.line = number;
    if (e.url.find(':') == std::string::npos) {
      f.problems.push_back(where + "\"" + e.url.substr(0, 200) + "\" is not an absolute URL");
      continue;
    }
    if (words[1] != "-") {
      e.length = std::nullopt;
      const bool digits = words[1].size() <= 19 &&
          std::all_of(words[1].begin(), words[1].end(), [](char c) { return c >= '0' && c <= '9'; });
      if (!digits) {
        f.problems.push_back(where + "length \"" + words[1].substr(0, 40) +
                             "\" is neither a number of bytes nor \"-\"");
        continue;
      }
      e.length = std::stoull(words[1]);
    }
    std::string why;
    const std::string decoded = percentDecode(line.substr(i));
    const auto path = safeBagPath(decoded, &why);
    if (!path) {
      f.problems.push_back(where + "\"" + decoded.substr(0, 200) + "\": " + why);
      continue;
    }
    e.path = *path;
    f.entries.push_back(std::move(e));
  }
  return f;
}

}  // namespace surrogate::archive
