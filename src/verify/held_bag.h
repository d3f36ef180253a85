// A bag held in another package layout, for the commands that show a package rather than
// verify it (info, report): an OCFL object (pack --layout ocfl) holds its bag as the head
// version's state, an E-ARK SIP (pack --layout eark) as files spread over its representation
// and metadata folders. Either is put together as a bag folder in a private temporary folder
// (hard links where the file systems allow, copies otherwise), removed with the HeldBag.
// Nothing is checked beyond what reading needs: `surrogate verify` gives the verdict.
//
//   if (auto held = verify::openHeldBag(path)) show(held->bag, held->layout);
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "core/temp_dir.h"

namespace surrogate::verify {

struct HeldBag {
  std::unique_ptr<TempDir> temp;  // holds `bag`
  std::filesystem::path bag;      // the bag folder (bagit.txt, data/, ...)
  std::string format;             // "ocfl" or "eark" (pack --layout)
  std::string layout;             // in words: "OCFL object, head version v2" or "E-ARK SIP"
};

// Whether `package` is a folder in one of those layouts (its declaration or METS.xml says so).
bool holdsBagInLayout(const std::filesystem::path& package);

// nullptr when `package` is neither an OCFL object nor an E-ARK SIP folder. Error(Usage)
// naming the package when it is one that cannot be read (an OCFL object without a usable
// root inventory, a link inside), with the verify command that says what is wrong.
std::unique_ptr<HeldBag> openHeldBag(const std::filesystem::path& package);

}  // namespace surrogate::verify
