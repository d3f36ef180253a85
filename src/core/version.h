// The version of Surrogate itself, recorded in every carrier and package.
#pragma once

namespace surrogate {
const char* surrogateVersion();
}  // namespace surrogate
