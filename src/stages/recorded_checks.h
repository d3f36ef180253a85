// Plausibility checks as a stage records them (hrti/light_checks.h): the same for the checks
// on the lights (LightDirections) and on each fit (RtiFit).
//
// Each check becomes a `check` item of the step's result: passed, failed, or accepted when an
// accept-check intervention of the step names it (`--accept NAME --reason`, logged with who
// and why, and the failure kept as a warning). Failed checks that are not accepted stop the
// run: Error(Input) listing each with its figures, what to do (`fixFor`) and the --accept that
// overrides it.
//
//   recordChecks(step, ctx, result, hrti::checkLights(input), {"light checks",
//                "the light directions", "they cannot be trusted"}, fix);
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "hrti/light_checks.h"
#include "pipeline/context.h"

namespace surrogate::stages {

// The intervention that accepts a failed check by name (--accept CHECK).
inline constexpr const char* kAcceptCheck = "accept-check";

// How a stop is worded: "a check on SUBJECT failed, so CONSEQUENCE:", the error's step.
struct CheckWording {
  std::string step, subject, consequence;
};

void recordChecks(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result,
                  const std::vector<hrti::LightCheck>& checks, const CheckWording& wording,
                  const std::function<std::string(const hrti::LightCheck&)>& fixFor);

// "leave the image(s) out: --exclude A --reason \"...\"; --exclude B --reason \"...\"", for the
// images a check names (`names`: every image's, as the user names it).
std::string excludeImagesFix(const hrti::LightCheck& check, const std::vector<std::string>& names);

}  // namespace surrogate::stages
