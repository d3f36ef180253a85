// How a person names a sphere on the command line: "sphere1" is the first sphere, counted
// from 1 as the overview files (highlights-sphere1.png), the report, the review page and the
// messages count them. A bare number is the index from 0 that the options have always taken
// (kept so that existing scripts and recorded commands mean what they meant); the carrier
// records that index.
//
//   sphereIndexOfReference("sphere2") == 1;  sphereIndexOfReference("1") == 1;
//   sphereIndexOfReference("sphere0") == std::nullopt;  sphereReference(0) == "sphere1"
//   sphereNumberText("0") == "1";  personsSphereTarget("IMG_0003:0") == "IMG_0003:sphere1"
#pragma once

#include <optional>
#include <string>

namespace surrogate {

// A bare index from 0 ("0", "12", at most 6 digits); nullopt for anything else.
inline std::optional<int> bareSphereIndex(const std::string& text) {
  if (text.empty() || text.size() > 6 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stoi(text);
}

// The index from 0 of "sphereN" (N from 1) or of a bare index; nullopt for anything else.
inline std::optional<int> sphereIndexOfReference(const std::string& text) {
  if (text.rfind("sphere", 0) != 0) return bareSphereIndex(text);
  const std::optional<int> n = bareSphereIndex(text.substr(6));
  if (!n || *n < 1) return std::nullopt;
  return *n - 1;
}

// The name a person types for the sphere of this index: "sphere1" for 0.
inline std::string sphereReference(int index) { return "sphere" + std::to_string(index + 1); }

// A recorded index as people count: "0" gives "1"; text that is no index, as it is.
inline std::string sphereNumberText(const std::string& index) {
  const std::optional<int> k = bareSphereIndex(index);
  return k ? std::to_string(*k + 1) : index;
}

// A recorded sphere target ("0") or highlight target ("IMG_0003:0") as a person types it
// ("sphere1", "IMG_0003:sphere1"); anything else as it is.
inline std::string personsSphereTarget(const std::string& target) {
  const auto colon = target.rfind(':');
  const std::string head = colon == std::string::npos ? "" : target.substr(0, colon + 1);
  const std::optional<int> k = bareSphereIndex(colon == std::string::npos ? target : target.substr(colon + 1));
  return k ? head + sphereReference(*k) : target;
}

}  // namespace surrogate
