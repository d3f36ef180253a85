#include "verify/verify.h"

#include <set>

#include "capture/capture.h"
#include "core/error.h"
#include "verify/checks.h"
#include "verify/eark_checks.h"
#include "verify/ocfl_checks.h"

namespace surrogate::verify {

int Report::exitCode() const {
  bool fixity = false, invalid = false, notReproduced = false;
  for (const Check& c : checks) {
    if (c.passed) continue;
    fixity |= c.severity == Severity::Fixity;
    invalid |= c.severity == Severity::Invalid;
    notReproduced |= c.severity == Severity::NotReproduced;
  }
  if (fixity) return static_cast<int>(Severity::Fixity);
  if (invalid) return static_cast<int>(Severity::Invalid);
  if (notReproduced) return static_cast<int>(Severity::NotReproduced);
  return 0;
}

std::size_t Report::failures() const {
  std::size_t n = 0;
  for (const Check& c : checks) n += !c.passed;
  return n;
}

bool Check::aboutBagIt() const {
  return name.compare(0, 6, "bagit.") == 0 || name == "package.read" || name == "package.reread";
}

bool Report::bagitValid() const {
  for (const Check& c : checks)
    if (c.aboutBagIt() && !c.passed) return false;
  return true;
}

bool Report::packageSound() const {
  // A package that is not a valid bag is never sound, whatever its own checks say.
  for (const Check& c : checks)
    if (!c.passed) return false;
  return surrogatePackage;
}

namespace {

// The inventory, read a second time when the bag has manifests in algorithms other than
// SHA-256 and SHA-512 (md5, sha1, sha224, ...), all of them computed in that one second read:
// a bag made by another tool pays for its other algorithms, a Surrogate package never does.
Inventory readInventory(const std::filesystem::path& package, const VerifyOptions& options) {
  Inventory inventory = readPackage(package, options.limits, options.progress);
  if (const std::vector<std::string> other = otherDigestsNeeded(inventory); !other.empty())
    inventory = readPackage(package, options.limits, options.progress, other);
  return inventory;
}

// Unlisted operating-system files (VerifyOptions::strict): taken out of the inventory, one
// warning each with the command that removes it. A file a manifest names stays, whatever its
// name: it is payload. The manifests are read as the checks read them (archive::parseManifest,
// paths decoded); when one cannot be read cleanly nothing is set aside, and the checks judge
// the bag as it is.
void setAsideSystemFiles(const std::filesystem::path& package, Inventory& inventory,
                         std::vector<std::string>& warnings) {
  std::vector<std::string> candidates;
  for (const auto& [path, file] : inventory.files) {
    const auto slash = path.rfind('/');
    if (capture::isSystemFile(slash == std::string::npos ? path : path.substr(slash + 1))) candidates.push_back(path);
  }
  if (candidates.empty()) return;
  std::set<std::string> listed;
  for (const auto& [path, file] : inventory.files) {
    const auto name = manifestName(path);
    if (!name) continue;
    const std::size_t hexLength = digestHexLength(name->second);
    if (!file.content || hexLength == 0) return;
    const Manifest m = parseManifest(*file.content, name->second, hexLength);
    if (!m.problems.empty()) return;
    for (const ManifestEntry& e : m.entries) listed.insert(e.path);
  }
  for (const std::string& path : candidates) {
    if (listed.count(path)) continue;
    std::string printable = path;
    for (char& ch : printable)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '?';
    std::string quoted;  // for a POSIX shell, inside single quotes
    for (char ch : (package / printable).string()) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    warnings.push_back(printable + ": a file the operating system left, in no manifest; set aside (--strict " +
                       "counts it as a fixity failure)" +
                       (inventory.kind == "directory"
                            ? "; remove it with: rm '" + quoted + "'"
                            : std::string("; the archive would have to be repacked without it")));
    const auto it = inventory.files.find(path);
    inventory.totalBytes -= it->second.size;
    inventory.setAside.insert(path);
    inventory.files.erase(it);
  }
}

}  // namespace

Report verifyPackage(const std::filesystem::path& package, const VerifyOptions& options) {
  if (isOcflObject(package)) return verifyOcflObject(package, options);
  if (isEarkSip(package)) return verifyEarkSip(package, options);
  return verifyBag(package, options);
}

Report verifyBag(const std::filesystem::path& package, const VerifyOptions& options) {
  Report report;
  report.package = package.string();
  Inventory inventory;
  try {
    inventory = readInventory(package, options);
  } catch (const Error& e) {
    if (e.kind() == ErrorKind::Input || e.kind() == ErrorKind::Internal) throw;
    Check c;
    c.name = "package.read";
    c.passed = false;
    c.severity = e.kind() == ErrorKind::Fixity ? Severity::Fixity : Severity::Invalid;
    c.what = e.kind() == ErrorKind::Fixity ? "the package cannot be read to its end"
                                           : "the package was refused";
    c.where.push_back(e.text());
    report.checks.push_back(c);
    return report;
  }
  report.kind = inventory.kind;
  if (!options.strict) setAsideSystemFiles(package, inventory, report.warnings);
  report.checks.push_back(makeCheck(
      "package.read", Severity::Invalid,
      "read " + std::to_string(inventory.files.size()) + " files (" +
          std::to_string(inventory.totalBytes) + " bytes) from the " + inventory.kind +
          "; no unsafe entries",
      "", {}));

  report.surrogatePackage = isSurrogatePackage(inventory);
  checkBag(inventory, report.surrogatePackage, report.checks, report.warnings);
  if (!report.surrogatePackage) {
    // A bag another tool made: its BagIt validity is the whole verdict.
    if (options.reexecute)
      report.warnings.push_back("not re-executed: the bag is not a Surrogate package, so it "
                                "records no steps to run again");
    return report;
  }
  checkCompleteness(inventory, report.checks);
  for (std::string& w : documentWarnings(inventory)) report.warnings.push_back(std::move(w));
  std::optional<carrier::Carrier> recorded = checkCarrier(inventory, report.checks);
  const bool runnable = recorded && checkSteps(*recorded, report.checks);
  checkPackageInfo(inventory, recorded, report.checks, report.holderFields);
  if (recorded) checkReadme(inventory, *recorded, report.checks);
  const auto carrierFile = inventory.files.find(kCarrierPath);
  const std::string* carrierXml =
      recorded && carrierFile != inventory.files.end() && carrierFile->second.content
          ? &*carrierFile->second.content
          : nullptr;
  // Only re-execution needs the parsed carrier again: free it before the metadata are derived
  // (for a package of 100 000 files it is about 200 MB, beside the stylesheets' trees).
  if (!options.reexecute) recorded.reset();
  try {
    // Before checkMetadata, which may let the payload's entries go.
    if (carrierXml) checkRoCrate(package, inventory, *carrierXml, options.limits, report.checks);
    checkMetadata(package, inventory, carrierXml, options.limits, report.checks, !options.reexecute);
  } catch (const Error& e) {
    // The package changed or vanished while it was being verified.
    if (e.kind() != ErrorKind::Fixity) throw;
    report.checks.push_back(makeCheck("package.reread", Severity::Fixity, "",
                                                "the package changed while it was being verified",
                                                {e.text()}));
  }

  if (options.reexecute) {
    if (!recorded) {
      report.checks.push_back(makeCheck(
          "reexecute.run", Severity::NotReproduced, "", "there is no valid carrier to re-execute",
          {std::string(kCarrierPath) + ": see carrier.schema"}));
    } else if (!runnable) {
      // A step that cannot run as recorded would fail for that reason, not for its results.
      report.checks.push_back(makeCheck(
          "reexecute.run", Severity::Invalid, "",
          "not re-executed: the carrier records steps this build cannot run (see carrier.steps)",
          {"re-execution runs valid carriers only"}));
    } else if (report.exitCode() == static_cast<int>(Severity::Fixity)) {
      // Re-running on files known to have changed would only repeat the fixity failure.
      report.checks.push_back(makeCheck(
          "reexecute.run", Severity::NotReproduced, "",
          "not re-executed: files of the package changed (see the fixity checks)",
          {"fix the package first; re-execution runs on verified originals only"}));
    } else {
      try {
        checkReexecution(package, inventory, *recorded, options, report);
      } catch (const Error& e) {
        if (e.kind() == ErrorKind::Internal) throw;
        Check c;
        c.name = "reexecute.extract";
        c.passed = false;
        c.severity = e.kind() == ErrorKind::Fixity ? Severity::Fixity : Severity::Invalid;
        c.what = "the package could not be extracted for re-execution";
        c.where.push_back(e.text());
        report.checks.push_back(c);
      }
    }
  }
  return report;
}

}  // namespace surrogate::verify
