// Private to src/publish: a web layout's info.json read with OpenCV's cv::FileStorage (its JSON
// reader). A JsonValue is a handle on a node of the document FileStorage holds, so that OpenCV
// stays inside info_json.cpp and a relight info.json of megabytes of basis numbers is not
// copied. Surrogate writes JSON with core/json.h and reads it only here, for `surrogate info`.
//
//   JsonValue info = readJsonObject(text, "web/info.json");
//   if (std::optional<JsonValue> width = info.find("width")) use(width->number());
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::publish {

class JsonValue {
 public:
  // FileStorage reads true and false as the numbers 1 and 0 (and refuses null).
  enum class Kind { Null, Number, String, Array, Object };

  JsonValue();
  Kind kind() const;
  double number() const;       // a Number's value, else 0
  std::string text() const;    // a String's UTF-8 bytes, else ""
  std::size_t size() const;    // the items of an Array, the members of an Object, else 0
  JsonValue item(std::size_t i) const;     // an Array's item i; Null when there is none
  std::vector<JsonValue> items() const;    // an Array's items in order; ask size() first
  // The member `key` of an Object; nullopt when absent or when this is not an Object.
  std::optional<JsonValue> find(const std::string& key) const;

  struct Node;  // info_json.cpp: the FileStorage (shared) and a cv::FileNode in it

 private:
  explicit JsonValue(std::shared_ptr<const Node> node) : node_(std::move(node)) {}
  std::shared_ptr<const Node> node_;
  friend JsonValue readJsonObject(const std::string& text, const std::string& file);
};

// Limits: the text's nesting depth; a deeper document is refused as malformed (FileStorage
// itself recurses once per level with no limit and overflows the stack at some 50 000).
constexpr int kMaxJsonDepth = 64;

// `text` must be one JSON object, the only top level FileStorage reads. Throws Error(Input)
// naming `file` and saying what is not JSON (with the byte or line where it is): text that is
// not an object, not UTF-8, unclosed or too deeply nested, a NUL byte, text after the object, a number
// outside JSON's syntax or a whole number beyond +-2147483647 (FileStorage would misread
// them), a key given twice, a number too large for a double, an escape JSON does not have, a
// malformed or unpaired \u escape, \u0000, a key holding an escaped quotation mark or control
// character, and whatever FileStorage refuses (null, strings of 4096 bytes or more, 1E5 with a
// capital E). JSON's \/ and \uXXXX escapes (surrogate pairs too), which FileStorage refuses,
// are read as the characters they stand for. Never lets a cv::Exception out.
JsonValue readJsonObject(const std::string& text, const std::string& file);

}  // namespace surrogate::publish
