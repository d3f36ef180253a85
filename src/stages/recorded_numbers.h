// Private to src/stages: a whole number read from a recorded step parameter, as every stage's
// fromParameters reads one, with one message for a carrier that holds anything else.
//
//   o.quality = recordedInteger("web copy", "quality", value, 1, 100);
#pragma once

#include <string>

#include "core/error.h"

namespace surrogate::stages {

// Error(Input) naming "NAME=VALUE" in `step` ("needs a whole number from LOW to HIGH") for text
// that is not one whole number in [low, high].
Error badParameter(const char* step, const std::string& name, const std::string& value, const std::string& what);
int recordedInteger(const char* step, const std::string& name, const std::string& value, int low, int high);

}  // namespace surrogate::stages
