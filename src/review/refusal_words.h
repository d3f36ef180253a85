// The review page's words for a run's refusal: what to do on the page (drag the circle, leave
// the frame out), never the options a command line would take. A refusal the page has no words
// of its own for is given in the run's (Error::text()).
//
// Spheres are numbered from 1 here, as everywhere a person reads (the options name them
// sphere1, sphere2: core/sphere_reference.h); the carrier counts them from 0.
//
//   answer["message"] = pageWords(e);
#pragma once

#include <string>

#include "core/error.h"

namespace surrogate::review {

std::string pageWords(const Error& e);

}  // namespace surrogate::review
