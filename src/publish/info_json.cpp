#include "publish/info_json.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>

#include "core/error.h"

namespace surrogate::publish {

namespace {

[[noreturn]] void notJson(const std::string& file, const std::string& where, const std::string& what) {
  throw Error(ErrorKind::Input, file, "publish", "is not valid JSON" + where + ": " + what);
}

std::string atByte(std::size_t i) { return " at byte " + std::to_string(i); }

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool endsLiteral(char c) {
  return isSpace(c) || c == '"' || c == ',' || c == ':' || c == '[' || c == ']' || c == '{' || c == '}';
}

// A literal outside strings: true, false, null or a number in JSON's syntax. FileStorage reads
// a number without fraction or exponent with strtol(base 0) into an int: 010 would be 8, 0x10
// 16 and 4294967300 would be 4, so a whole number must also fit an int.
const char* literalProblem(const std::string& t) {
  if (t == "true" || t == "false" || t == "null") return nullptr;
  static const char* kMalformed = "a value is neither a string, a number, true, false nor null";
  std::size_t i = t.size() > 0 && t[0] == '-' ? 1 : 0;
  const std::size_t intStart = i;
  while (i < t.size() && isDigit(t[i])) ++i;
  const std::size_t intDigits = i - intStart;
  if (intDigits == 0 || (intDigits > 1 && t[intStart] == '0')) return kMalformed;
  bool whole = true;
  if (i < t.size() && t[i] == '.') {
    whole = false;
    const std::size_t start = ++i;
    while (i < t.size() && isDigit(t[i])) ++i;
    if (i == start) return kMalformed;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    whole = false;
    if (++i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    const std::size_t start = i;
    while (i < t.size() && isDigit(t[i])) ++i;
    if (i == start) return kMalformed;
  }
  if (i != t.size()) return kMalformed;
  if (whole) {
    const long long v = intDigits > 10 ? LLONG_MAX : std::strtoll(t.c_str(), nullptr, 10);
    if (v > INT_MAX || v < INT_MIN) return "a whole number is outside -2147483648 to 2147483647";
  }
  return nullptr;
}

// Where `s` stops being UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing past
// U+10FFFF), or npos. JSON text is UTF-8; FileStorage passes any byte through.
std::size_t notUtf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto b = [&](std::size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
    const unsigned c = b(i);
    std::size_t n = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
    if (c < 0x80) n = 0;
    else if (c >= 0xC2 && c <= 0xDF) n = 1;
    else if (c >= 0xE0 && c <= 0xEF) n = 2, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) n = 3, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    else return i;
    for (std::size_t k = 1; k <= n; ++k) {
      const unsigned d = b(i + k);
      if (k == 1 ? (d < lo || d > hi) : (d < 0x80 || d > 0xBF)) return i;
    }
    i += n + 1;
  }
  return std::string::npos;
}

// What FileStorage's JSON reader (OpenCV 4.6) leaves unchecked, checked before it reads: it
// recurses once per nesting level without limit, stops at the first NUL byte, takes any bytes
// in strings, ignores text
// after the top-level object and misreads some numbers (literalProblem). One pass over the
// bytes that skips strings and builds nothing. Returns where the object starts: FileStorage
// does not take space (nor a byte order mark followed by space) before it.
std::size_t checkBeforeFileStorage(const std::string& s, const std::string& file) {
  if (const std::size_t nul = s.find('\0'); nul != std::string::npos) notJson(file, atByte(nul), "it holds a NUL byte");
  if (const std::size_t bad = notUtf8(s); bad != std::string::npos)
    notJson(file, atByte(bad), "it is not UTF-8 text (a byte sequence no UTF-8 character has)");
  std::size_t i = s.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a UTF-8 byte order mark
  while (i < s.size() && isSpace(s[i])) ++i;
  if (i == s.size()) notJson(file, "", "it is empty");
  if (s[i] != '{') notJson(file, atByte(i), "it is not a JSON object");
  const std::size_t object = i;
  int depth = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (c == '"') {
      const std::size_t start = i++;
      while (i < s.size() && s[i] != '"') {
        if (static_cast<unsigned char>(s[i]) < 0x20) notJson(file, atByte(i), "a string holds a control character");
        i += s[i] == '\\' ? 2 : 1;
      }
      if (i >= s.size()) notJson(file, atByte(start), "a string is not closed");
      ++i;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth)
        notJson(file, atByte(i), "it is nested too deeply (more than " + std::to_string(kMaxJsonDepth) + " levels)");
      ++i;
    } else if (c == '}' || c == ']') {
      ++i;
      if (--depth == 0) break;
    } else if (isSpace(c) || c == ',' || c == ':') {
      ++i;
    } else {
      const std::size_t start = i;
      while (i < s.size() && !endsLiteral(s[i])) ++i;
      if (const char* problem = literalProblem(s.substr(start, i - start))) notJson(file, atByte(start), problem);
    }
  }
  if (depth != 0) notJson(file, atByte(s.size()), "it ends before its brackets close");
  while (i < s.size() && isSpace(s[i])) ++i;
  if (i != s.size()) notJson(file, atByte(i), "there is more text after the JSON object");
  return object;
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void appendUtf8(std::string& out, unsigned cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// The code point of the escape "\uXXXX" at s[i] (a surrogate pair read as one character, six
// more bytes consumed, in *length); a malformed escape or an unpaired surrogate is refused.
unsigned unicodeEscape(const std::string& s, std::size_t i, std::size_t* length, const std::string& file) {
  auto four = [&](std::size_t at) -> long {
    if (at + 6 > s.size() || s[at] != '\\' || s[at + 1] != 'u') return -1;
    long v = 0;
    for (std::size_t k = at + 2; k < at + 6; ++k) {
      const int h = hexValue(s[k]);
      if (h < 0) return -1;
      v = v * 16 + h;
    }
    return v;
  };
  const long first = four(i);
  if (first < 0) notJson(file, atByte(i), "a \\u escape is not followed by four hexadecimal digits");
  *length = 6;
  if (first >= 0xDC00 && first <= 0xDFFF)
    notJson(file, atByte(i), "the escape " + s.substr(i, 6) + " is the second half of a UTF-16 surrogate pair without its first");
  if (first < 0xD800 || first > 0xDBFF) return static_cast<unsigned>(first);
  const long second = four(i + 6);
  if (second < 0xDC00 || second > 0xDFFF)
    notJson(file, atByte(i), "the escape " + s.substr(i, 6) + " is the first half of a UTF-16 surrogate pair without its second");
  *length = 12;
  return 0x10000 + ((static_cast<unsigned>(first) - 0xD800) << 10) + (static_cast<unsigned>(second) - 0xDC00);
}

// JSON's escapes as FileStorage reads them. FileStorage (OpenCV 4.6) takes \" \\ \b \f \n \r \t
// in a value and refuses \/ and \uXXXX ("currently not supported"), which JSON allows and other
// tools write; it reads a key's bytes as they are, escapes included. So, inside strings, \/
// becomes '/' and \uXXXX (a surrogate pair as one character) its UTF-8 bytes, or in a value
// the short escape FileStorage reads for '"', '\\' and the five control characters that have
// one; in a key every escape becomes its character. Refused, naming the byte: an escape JSON
// does not have, a malformed or unpaired \u, \u0000 (FileStorage's strings end at a NUL), and a
// key holding a quotation mark or a control character (FileStorage ends a key at the first
// '"'). `s` has passed checkBeforeFileStorage: every string is closed.
// Returns the text from `from` on, or nullopt when it holds no escape (nothing to change).
std::optional<std::string> withEscapesFileStorageReads(const std::string& s, std::size_t from, const std::string& file) {
  if (s.find('\\', from) == std::string::npos) return std::nullopt;
  std::string out;
  out.reserve(s.size() - from);
  std::size_t i = from;
  while (i < s.size()) {
    if (s[i] != '"') {
      out += s[i++];
      continue;
    }
    std::size_t end = i + 1;
    while (s[end] != '"') end += s[end] == '\\' ? 2 : 1;
    std::size_t after = end + 1;
    while (after < s.size() && isSpace(s[after])) ++after;
    const bool key = after < s.size() && s[after] == ':';
    out += '"';
    for (std::size_t k = i + 1; k < end;) {
      if (s[k] != '\\') {
        out += s[k++];
        continue;
      }
      const char e = s[k + 1];
      unsigned cp = 0;
      std::size_t length = 2;
      switch (e) {
        case '"': cp = '"'; break;
        case '\\': cp = '\\'; break;
        case '/': cp = '/'; break;
        case 'b': cp = '\b'; break;
        case 'f': cp = '\f'; break;
        case 'n': cp = '\n'; break;
        case 'r': cp = '\r'; break;
        case 't': cp = '\t'; break;
        case 'u': cp = unicodeEscape(s, k, &length, file); break;
        default:
          notJson(file, atByte(k), std::string("a string holds the escape \\") + e + ", which JSON does not have");
      }
      if (cp == 0) notJson(file, atByte(k), "a string holds \\u0000, a NUL character, which this reader cannot hold");
      if (key && (cp == '"' || cp < 0x20))
        notJson(file, atByte(k), "a key holds an escaped quotation mark or control character, which this reader "
                                 "cannot hold in a key");
      if (key || cp == '/' || (cp >= 0x20 && cp != '"' && cp != '\\')) {
        appendUtf8(out, cp);
      } else {
        static const char kShort[] = {'"', '"', '\\', '\\', '\b', 'b', '\f', 'f', '\n', 'n', '\r', 'r', '\t', 't'};
        std::size_t m = 0;
        while (m < sizeof kShort && kShort[m] != static_cast<char>(cp)) m += 2;
        if (m < sizeof kShort) out += '\\', out += kShort[m + 1];
        else out += static_cast<char>(cp);  // another control character: FileStorage takes it as it is
      }
      k += length;
    }
    out += '"';
    i = end + 1;
  }
  return out;
}

// A parse error's cv::Exception::func reads "(<line>): <what>", after the whole text when
// that is one line (FileStorage then names its source by its contents); other errors say
// what in cv::Exception::err. `skippedLines`: those before the text FileStorage was given.
void rethrow(const cv::Exception& e, const std::string& text, std::size_t skippedLines, const std::string& file) {
  std::string where, what = e.err;
  std::string rest = e.func;
  if (rest.size() > text.size() && rest.compare(0, text.size(), text) == 0) rest.erase(0, text.size());
  const std::size_t close = rest.find("): ");
  if (rest.size() > 1 && rest[0] == '(' && close != std::string::npos && close > 1 &&
      rest.find_first_not_of("0123456789", 1) == close) {
    where = " at line " + std::to_string(std::stoul(rest.substr(1, close - 1)) + skippedLines);
    what = rest.substr(close + 3);
  }
  if (what.size() > 200) what.resize(200);
  if (where.empty()) notJson(file, "", "OpenCV's FileStorage cannot read it (" + what + ")");
  notJson(file, where, what + " (OpenCV's FileStorage)");
}

// What FileStorage reads without complaint but JSON or a reader of numbers cannot take: a key
// given twice (FileStorage keeps both, find() would see the first) and a number beyond a
// double (1e999, read as infinity). Walks the document once, copying nothing.
void checkAfterFileStorage(const cv::FileNode& n, int depth, const std::string& file) {
  if (depth > kMaxJsonDepth) notJson(file, "", "it is nested too deeply");
  if (n.isReal() && !std::isfinite(static_cast<double>(n))) notJson(file, "", "a number is too large for a double");
  if (!n.isSeq() && !n.isMap()) return;
  std::set<std::string> keys;
  for (cv::FileNodeIterator it = n.begin(); it != n.end(); ++it) {
    const cv::FileNode child = *it;
    if (n.isMap() && !keys.insert(child.name()).second)
      notJson(file, "", "the key \"" + child.name() + "\" is given twice");
    checkAfterFileStorage(child, depth + 1, file);
  }
}

}  // namespace

struct JsonValue::Node {
  std::shared_ptr<const cv::FileStorage> storage;  // the document, kept while a node of it is
  cv::FileNode node;
};

JsonValue::JsonValue() = default;

JsonValue::Kind JsonValue::kind() const {
  if (!node_) return Kind::Null;
  const cv::FileNode& n = node_->node;
  if (n.isInt() || n.isReal()) return Kind::Number;
  if (n.isString()) return Kind::String;
  if (n.isSeq()) return Kind::Array;
  if (n.isMap()) return Kind::Object;
  return Kind::Null;
}

double JsonValue::number() const {
  if (kind() != Kind::Number) return 0;
  const cv::FileNode& n = node_->node;
  return n.isInt() ? static_cast<double>(static_cast<int>(n)) : static_cast<double>(n);
}

std::string JsonValue::text() const { return kind() == Kind::String ? node_->node.string() : std::string(); }

std::size_t JsonValue::size() const {
  const Kind k = kind();
  return k == Kind::Array || k == Kind::Object ? node_->node.size() : 0;
}

// FileNode::operator[](int) steps from the first item: size() first, and items() to go through.
JsonValue JsonValue::item(std::size_t i) const {
  if (kind() != Kind::Array || i >= size()) return JsonValue();
  return JsonValue(std::make_shared<const Node>(Node{node_->storage, node_->node[static_cast<int>(i)]}));
}

std::vector<JsonValue> JsonValue::items() const {
  std::vector<JsonValue> out;
  if (kind() != Kind::Array) return out;
  out.reserve(size());
  for (cv::FileNodeIterator it = node_->node.begin(); it != node_->node.end(); ++it)
    out.push_back(JsonValue(std::make_shared<const Node>(Node{node_->storage, *it})));
  return out;
}

std::optional<JsonValue> JsonValue::find(const std::string& key) const {
  if (kind() != Kind::Object) return std::nullopt;
  cv::FileNode member = node_->node[key];
  if (member.empty()) return std::nullopt;
  return JsonValue(std::make_shared<const Node>(Node{node_->storage, member}));
}

JsonValue readJsonObject(const std::string& text, const std::string& file) {
  const std::size_t start = checkBeforeFileStorage(text, file);
  // Only the object is given to FileStorage, its escapes as FileStorage reads them.
  const std::optional<std::string> rewritten = withEscapesFileStorageReads(text, start, file);
  const std::string object = rewritten || start == 0 ? std::string() : text.substr(start);
  const std::string& given = rewritten ? *rewritten : start == 0 ? text : object;
  try {
    auto storage = std::make_shared<cv::FileStorage>(
        given, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_JSON);
    if (!storage->isOpened()) notJson(file, "", "OpenCV's FileStorage could not read it");
    const cv::FileNode root = storage->root();
    if (!root.isMap()) notJson(file, "", "it is not a JSON object");
    checkAfterFileStorage(root, 1, file);
    return JsonValue(std::make_shared<const JsonValue::Node>(JsonValue::Node{storage, root}));
  } catch (const cv::Exception& e) {
    rethrow(e, given, static_cast<std::size_t>(std::count(text.begin(), text.begin() + start, '\n')), file);
  }
  return {};
}

}  // namespace surrogate::publish
