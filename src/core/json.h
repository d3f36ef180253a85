// A minimal JSON writer for --json output (objects, arrays, strings, numbers, booleans).
// Output only: the one JSON Surrogate reads, a web layout's info.json, is read with OpenCV's
// FileStorage (publish/info_json.h).
//
//   JsonWriter j;
//   j.beginObject().key("images").value(24).key("title").value("Stela").endObject();
//   std::cout << j.str() << "\n";
#pragma once

#include <string>
#include <vector>

namespace surrogate {

class JsonWriter {
 public:
  JsonWriter& beginObject();
  JsonWriter& endObject();
  JsonWriter& beginArray();
  JsonWriter& endArray();
  JsonWriter& key(const std::string& name);
  JsonWriter& value(const std::string& text);
  JsonWriter& value(const char* text) { return value(std::string(text)); }
  JsonWriter& value(double number);
  JsonWriter& value(int number);
  JsonWriter& value(long long number);
  JsonWriter& value(unsigned long long number);
  JsonWriter& value(bool flag);
  JsonWriter& null();
  const std::string& str() const { return out_; }

  static std::string quote(const std::string& text);

 private:
  void separate();
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool afterKey_ = false;
};

}  // namespace surrogate
