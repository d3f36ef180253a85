// What the ingest stage hands to the stages after it, through the pipeline context.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/stack.h"

namespace surrogate::stages {

// Blackboard keys.
inline constexpr const char* kInputImages = "input-images";
inline constexpr const char* kRgbStack = "rgb-stack";
// The decoded stack as ImageDecode made it: kRgbStack before any pre-processing step replaced
// it (the Audit compares another tool's result with the whole frames).
inline constexpr const char* kDecodedRgbStack = "decoded-rgb-stack";
inline constexpr const char* kLuminanceStack = "luminance-stack";

// One photograph the pipeline uses (after exclusions), in capture order.
struct InputImage {
  std::string fileId;        // in the carrier's files section
  std::string relativePath;  // to the capture root
  std::string stem;          // the shot's name
};
using InputImages = std::vector<InputImage>;

}  // namespace surrogate::stages
