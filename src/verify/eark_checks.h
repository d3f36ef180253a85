// Private to src/verify: a package in the E-ARK SIP layout (pack --layout eark), verified by
// its METS files and then as the bag its files make up again.
#pragma once

#include <filesystem>

#include "verify/verify.h"

namespace surrogate::verify {

// Whether `package` is a folder whose METS.xml declares an E-ARK SIP profile.
bool isEarkSip(const std::filesystem::path& package);

// The eark.* checks (eark_checks.cpp says each), then the bag put together from the SIP's files
// (archive::bagPathOf) in a private temporary folder and verified by verifyBag.
Report verifyEarkSip(const std::filesystem::path& sip, const VerifyOptions& options);

// The bag the SIP's files make up again (archive::bagPathOf), put together in the folder
// `into` (made here): hard links where the file systems allow, copies otherwise.
void assembleSipBag(const std::filesystem::path& sip, const std::filesystem::path& into);

}  // namespace surrogate::verify
