// The verifier: is an archival package (a BagIt bag as a directory, .tar or .zip) sound?
//
// Its verdict has two parts: "BagIt: valid/invalid" for any bag (package.read and bagit.*
// checks), and for a Surrogate package "Surrogate package: sound/not sound" (every other
// check). A bag another tool made is checked as a bag only: manifests in any digest OpenSSL
// offers (md5 and sha1 with a warning), what RFC 8493 tolerates with a warning (md5sum's '*'
// marker, a 0.97 path listed twice with the same checksum, a repeated Bagging-Date), tag files
// read in the encoding bagit.txt names, and its exit code is its BagIt verdict (0 valid).
//
// It answers with a list of checks, each passed or failed with what was found and where:
//   package.read the package read to its end, safely: no hostile entry, a .tar that ends with
//                its end-of-archive marker and nothing after it but zero padding, a .zip whose
//                end record ends the file
//   bagit.*      the bag itself (RFC 8493): bagit.txt, manifests, tagmanifests, fetch.txt,
//                Payload-Oxum, every payload file listed, every listed file present and
//                matching
//   package.*    for a Surrogate package (bag-info has Surrogate-Package-Identifier, or the bag
//                has data/assembly-files/carrier.xml): every file `surrogate pack` writes is
//                present (complete), every tag file is in every tagmanifest (tags-listed),
//                metadata/'s stylesheets, schemas and tables are byte-identical to this
//                verifier's and nothing else is there (bundled), and the fields of
//                bag-info.txt that Surrogate writes are what packing the carrier gives (info;
//                any other field is listed as the holder's, Report::holderFields)
//   carrier.*    data/assembly-files/carrier.xml validates against xsd/carrier.xsd, every
//                file it lists is in the bag with the same size and SHA-256, and every step
//                it records can run in this build as recorded (steps)
//   metadata.*   metadata/mets.xml validates (METS + PREMIS), metadata/crm.rdf is well-formed,
//                and both equal what the bundled stylesheets derive from the carrier (compared
//                by digest while the derivation is written out: neither their text nor their
//                result tree is ever held whole, see mapping.h)
//   reexecute.*  (with `reexecute`) the recorded process list, run again on the bagged
//                originals with the recorded parameters and interventions, gives the recorded
//                results: numbers exactly (or within `tolerance`), files by hash, and when a
//                file differs, by how much (max/RMS coefficient difference, PSNR of renders)
//
//   VerifyOptions options;
//   options.reexecute = true;
//   Report report = verifyPackage("stela.tar", options);
//   return report.exitCode();   // 0 sound, 2 invalid, 3 fixity, 4 not reproduced
//
// Exit codes (the CLI's contract): 0 every check passed (for a bag that is not a Surrogate
// package: it is a valid bag); 3 a fixity failure (a file changed,
// is missing or unlisted, the package is incomplete, the archive is truncated or has data after
// its end); 2 an invalid or refused package (bad bagit.txt, schema failure, hostile entries,
// resources of another version, bag-info or metadata that do not match the carrier, steps that
// cannot run); 4 re-execution did not reproduce the recorded results. A carrier whose steps
// cannot run is never re-executed. When several kinds fail, fixity
// wins over invalid, which wins over not reproduced: a changed file explains the rest.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "archive/package_reader.h"

namespace surrogate::verify {

// The package reader (src/archive) gives the inventory the checks work on; its limits and
// progress callback are part of the verifier's options.
using archive::Inventory;
using archive::InventoryFile;
using archive::Limits;
using archive::Progress;

// What kind of failure a check reports, and so the exit code it leads to.
enum class Severity { Invalid = 2, Fixity = 3, NotReproduced = 4 };

struct Check {
  std::string name;    // e.g. "bagit.manifest-sha256", "reexecute.s5.PtmFit"
  bool passed = true;
  Severity severity = Severity::Invalid;  // what a failure means
  std::string what;    // one sentence: what was checked, or what is wrong
  std::vector<std::string> where;  // files, lines or values at fault (capped)

  // Whether the check is about the bag as BagIt defines it (package.read, package.reread,
  // bagit.*), rather than about what a Surrogate package holds.
  bool aboutBagIt() const;
};

struct Report {
  std::string package;
  std::string kind;  // directory, tar, zip
  std::vector<Check> checks;
  // Whether the bag is a Surrogate package (bag-info.txt has Surrogate-Package-Identifier, or
  // the bag has data/assembly-files/carrier.xml); false too when it could not be read.
  bool surrogatePackage = false;
  // What does not fail the bag but a preservation officer should know (md5 or sha1 manifests,
  // --reexecute on a bag that is not a Surrogate package).
  std::vector<std::string> warnings;
  // bag-info.txt fields of a Surrogate package that packing the carrier does not give (label,
  // value; in the file's order): added by the holder (RFC 8493 lets a bag's holder add
  // fields; pack --bag-info writes such fields too). Listed, never checked against the
  // carrier; bag-info.txt's digest in the tag manifests still covers them.
  std::vector<std::pair<std::string, std::string>> holderFields;
  bool reexecuted = false;
  // Software that differs between the carrier's header and this build ("LibRaw 0.20.2 ->
  // 0.21.1"), filled by re-execution.
  std::vector<std::string> softwareDifferences;

  bool sound() const { return exitCode() == 0; }
  int exitCode() const;
  std::size_t failures() const;
  // The two parts of the verdict: every BagIt check passed; the bag is a Surrogate package
  // and every check passed (a package that is not a valid bag is not sound).
  bool bagitValid() const;
  bool packageSound() const;
};

struct VerifyOptions {
  bool reexecute = false;
  // Relative tolerance for recorded numbers; 0 = exactly equal (the default: Surrogate's
  // results are deterministic for the same software, at any thread count).
  double tolerance = 0;
  int threads = 0;  // for re-execution; 0 = all cores
  // Files operating systems leave (capture::isSystemFile: .DS_Store, Thumbs.db, ._*) that no
  // manifest lists are set aside with a warning and the command to remove them, as run and
  // pack ignore them; with `strict` they are left in and fail the fixity checks like any other
  // unlisted file.
  bool strict = false;
  Limits limits;
  Progress progress;
};

// Never throws for a bad package: a refused or unreadable one gives a report with one failed
// check ("package.read"). Throws Error(Input) when `package` does not exist, Error(Internal)
// for environment failures (no temporary space, missing schemas).
Report verifyPackage(const std::filesystem::path& package, const VerifyOptions& options);

}  // namespace surrogate::verify
