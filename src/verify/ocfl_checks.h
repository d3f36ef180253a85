// Private to src/verify: a package in the OCFL layout (pack --layout ocfl), verified as an
// OCFL 1.1 object and then as the bag its head version holds.
#pragma once

#include <filesystem>

#include "verify/verify.h"

namespace surrogate::verify {

// What verifyPackage does for a bag (a folder, .tar or .zip), without looking for an OCFL
// object or E-ARK SIP: the bag held in one is verified with it, whatever files its root holds.
Report verifyBag(const std::filesystem::path& package, const VerifyOptions& options);

// Whether `package` is a folder holding an OCFL object's declaration ("0=ocfl_object_1.x").
bool isOcflObject(const std::filesystem::path& package);

// The ocfl.* checks (ocfl_checks.cpp says each), then the head version's state put together
// in a private temporary folder (hard links where the file system allows, copies otherwise)
// and verified as a bag folder by verifyBag, its checks appended after the object's.
Report verifyOcflObject(const std::filesystem::path& object, const VerifyOptions& options);

// The head version's bag of `object` put together in the folder `into` (made here), for a
// reader that shows it (held_bag.h); returns the head's name ("v2"). Error(Usage) naming the
// object when its declaration or root inventory cannot be used: verify says what is wrong.
std::string assembleOcflHead(const std::filesystem::path& object, const std::filesystem::path& into);

}  // namespace surrogate::verify
