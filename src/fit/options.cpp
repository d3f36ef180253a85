#include "core/error.h"
#include "fit/fit.h"

namespace surrogate::fit {

Parameters FitOptions::toParameters() const { return {{"basis", basisName(basis)}}; }

FitOptions FitOptions::fromParameters(const Parameters& parameters) {
  FitOptions options;
  for (const auto& [name, value] : parameters) {
    if (name == "basis") {
      try {
        options.basis = parseBasis(value);
      } catch (const Error&) {
        throw Error(ErrorKind::Input, "carrier", "fit",
                    "the recorded fit basis \"" + value + "\" is unknown to this version");
      }
    } else {
      throw Error(ErrorKind::Input, "carrier", "fit",
                  "the recorded fit parameter \"" + name + "\" is unknown to this version");
    }
  }
  return options;
}

}  // namespace surrogate::fit
