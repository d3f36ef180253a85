#include "stages/recorded_numbers.h"

#include <charconv>

namespace surrogate::stages {

Error badParameter(const char* step, const std::string& name, const std::string& value, const std::string& what) {
  return Error(ErrorKind::Input, name + "=" + value, step, what);
}

int recordedInteger(const char* step, const std::string& name, const std::string& value, int low, int high) {
  int v = 0;
  const char* end = value.data() + value.size();
  const auto r = std::from_chars(value.data(), end, v);
  if (r.ec != std::errc() || r.ptr != end || v < low || v > high)
    throw badParameter(step, name, value,
                       "needs a whole number from " + std::to_string(low) + " to " + std::to_string(high));
  return v;
}

}  // namespace surrogate::stages
