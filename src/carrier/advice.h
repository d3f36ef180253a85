// The carrier's warnings in the words of core/advice.h: what happened, whether the result can
// be used, what to do, the figure as detail. Every warning a stage logs goes through it.
//
//   carrier::addWarning(ctx.carrier, step.id, {what, carrier::Usable::WithCare, why, todo, detail});
#pragma once

#include <string>

#include "carrier/carrier.h"
#include "core/advice.h"

namespace surrogate::carrier {

using surrogate::Advice;
using surrogate::Usable;
using surrogate::adviceText;

// Logs the advice as a warning of `step` (carrier.addLog with level "warning").
void addWarning(Carrier& carrier, const std::string& step, const Advice& advice, const std::string& who = "");

}  // namespace surrogate::carrier
