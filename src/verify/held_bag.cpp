#include "verify/held_bag.h"

#include "verify/eark_checks.h"
#include "verify/ocfl_checks.h"

namespace surrogate::verify {

bool holdsBagInLayout(const std::filesystem::path& package) {
  return isOcflObject(package) || isEarkSip(package);
}

std::unique_ptr<HeldBag> openHeldBag(const std::filesystem::path& package) {
  const bool ocfl = isOcflObject(package);
  if (!ocfl && !isEarkSip(package)) return nullptr;
  auto held = std::make_unique<HeldBag>();
  held->temp = std::make_unique<TempDir>(ocfl ? "ocfl-head" : "eark-bag");
  // Named as the package is, so that what a reader shows of the bag's root reads as the package.
  std::filesystem::path name = std::filesystem::absolute(package).lexically_normal();
  if (!name.has_filename()) name = name.parent_path();  // "object/"
  held->bag = held->temp->path() / (name.filename().empty() ? std::filesystem::path("bag") : name.filename());
  held->format = ocfl ? "ocfl" : "eark";
  if (ocfl) held->layout = "OCFL object, head version " + assembleOcflHead(package, held->bag);
  else {
    assembleSipBag(package, held->bag);
    held->layout = "E-ARK SIP";
  }
  return held;
}

}  // namespace surrogate::verify
