// A capture folder packed as an archival package: a BagIt bag (bag.h) whose payload is the
// capture (originals, exports, assembly files with the carrier, finished files) and whose tag
// files carry the standard metadata derived from the carrier (metadata/crm.rdf, mets.xml) and
// the stylesheets, schemas and mapping tables that derive and explain it.
//
//   Bag layout (docs/package.md, "What is in the bag"):
//     data/original-captures/...   data/jpeg-exports/...   data/<name>.lp
//     data/assembly-files/carrier.xml, lights.lp, overlays
//     data/finished-files/...      (.ptm, .rti, normals, previews, report.html, ...)
//     metadata/crm.rdf  metadata/mets.xml
//     metadata/xslt/*.xsl  metadata/xsd/*.xsd  metadata/mappings/*.md
//
//   CarrierState s = checkCarrier(capture);       // cheap: no file is hashed
//   if (!s.complete) runThePipeline();
//   PackResult r = packCapture(capture, "stela.zip", {});
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "archive/bag.h"

namespace surrogate::carrier {
struct Carrier;
}

namespace surrogate::archive {

// Whether a capture has a carrier that can be packed as it is: assembly-files/carrier.xml
// exists and is valid, every step has a completed result, every recorded file exists with its
// recorded size, and every file of the capture is recorded. (Hashes are compared while
// packing, where every file is read anyway.)
//
// The files of a capture are every file under its folder except Surrogate's working area
// (.surrogate/), superseded-files/ (results of earlier runs, moved aside) and the files
// operating systems leave (capture::isSystemFile: .DS_Store, Thumbs.db, ...): the rule run,
// pack and verify share. finished-files/report.html is the one file not recorded (a view of
// the carrier, not a result).
struct CarrierState {
  bool complete = false;
  std::string reason;  // why not, in a sentence
  // An original, export, sidecar, dome .lp or prior file that is missing or changed size:
  // evidence that no run may re-record (a fixity failure), in a sentence naming the file; empty when none.
  std::string inputProblem;
  std::string inputPath;  // the file inputProblem names, as the carrier records it
  // Files in assembly-files/ or finished-files/ that the carrier does not describe (not
  // written by Surrogate, or left by a run that was not recorded): never bagged. The next
  // `surrogate run` records them as prior work, or replaces them when they lie where it
  // writes (stages/prior_work.h).
  std::vector<std::string> unrecordedOutputs;
};
CarrierState checkCarrier(const std::filesystem::path& capture);

// The payload of a capture: the carrier's files (with their SHA-256 as the expected digest)
// and finished-files/report.html when present. Throws Error(Input) listing any other file of
// the capture (see CarrierState): nothing is bagged that the carrier does not describe.
std::vector<PayloadSource> capturePayload(const std::filesystem::path& capture);

// The bag-info.txt labels of a package of carrier `c`, after the ones writeBag computes
// (Bag-Software-Agent, Bagging-Date, Bag-Size, Payload-Oxum): `user`, the carrier's header
// metadata in its order, then External-Description (the carrier's, else "Highlight-RTI
// capture: <title>"); `own`, Surrogate-Package-Identifier (packageId) and
// Surrogate-Packaging-Time. packCapture writes them; the verifier compares a bag's bag-info.txt
// with them, so that one of them edited, removed or repeated after packing is found (any other
// label is the holder's: isSurrogateLabel, holderFieldProblem).
// `own` also holds Surrogate-Capture-Identifier (captureIdentifier(c)), and when given,
// Surrogate-Previous-Package-Identifier and Surrogate-Base-URI (pack --base-uri).
struct PackageInfo {
  std::vector<std::pair<std::string, std::string>> user, own;
};
PackageInfo packageInfo(const carrier::Carrier& c, const std::string& packageId,
                        const std::string& packagingTime, const std::string& previousPackageId = "",
                        const std::string& baseUri = "");

// The identifiers (docs/package.md, "Identifiers"):
// "urn:sha256:<SHA-256 of the carrier's bytes, lower-case hex>": the package identifier, one
// per state of the capture's record.
std::string packageIdentifier(const std::string& carrierSha256);
// "urn:surrogate:capture:<SHA-256 of the carrier's first file>" (the first photograph, which
// no run changes): the capture identifier, the same for every state and package of the
// capture; "urn:surrogate:capture:unidentified" for a carrier without files. The stylesheets
// compute the same string.
std::string captureIdentifier(const carrier::Carrier& c);
// Whether `id` has the form of a package identifier.
bool isPackageIdentifier(const std::string& id);
// Why `uri` cannot be a base for crm.rdf's node URIs (pack --base-uri), or "" when it can: an
// absolute URI (a scheme, ':', no white space or characters IRIs exclude) ending in "/" or "#",
// so that the names added to it stay apart.
std::string baseUriProblem(const std::string& uri);

// The packages made of a capture, as `pack` records them in the capture's working area
// (.surrogate/packages: one "<package id> <packaging time>" line per pack, oldest first). The
// record stays with the capture folder, not with its carrier: a package is made of the
// carrier, and writing into it would change the identifier of the very package it names.
std::vector<std::string> packagesMade(const std::filesystem::path& capture);
// The package this one revises: the last package made of the capture whose identifier is not
// `packageId` (an earlier state of its record), or "" when there is none.
std::string previousPackage(const std::filesystem::path& capture, const std::string& packageId);

// The tag files packCapture writes in metadata/: crm.rdf, mets.xml, metadata/<resource> for
// each of mapping::packagedResources() (stylesheets, schemas, mapping tables) and of
// bundledDocuments() (package_readme.h), sorted. Besides them it writes bagit.txt,
// bag-info.txt, the manifests, the tag manifests and README.txt (kReadmePath).
std::vector<std::string> packageMetadataFiles();

// Why `label: value` cannot be a holder's field of a package of carrier `c` (pack
// --bag-info), or "" when it can: the label follows bagInfoLabelProblem, does not start with
// "Surrogate-" (Surrogate's own labels), and is none of the labels packageInfo gives for `c`
// (its header metadata, External-Description: those are Surrogate's, re-derived by verify);
// the value holds no line break or other control character. Without a carrier (`c` null)
// only the label's form and the value are judged.
std::string holderFieldProblem(const std::string& label, const std::string& value,
                               const carrier::Carrier* c = nullptr);

// Whether a bag-info label is one of Surrogate's (written by packing, any case): the computed
// ones, Surrogate-*, and those of packageInfo for `c`.
bool isSurrogateLabel(const std::string& label, const PackageInfo& info);

struct PackOptions {
  std::function<void(std::uint64_t, std::uint64_t)> progress;  // payload bytes done, in all
  // Holder's fields (pack --bag-info LABEL=VALUE), written after Surrogate's in the given
  // order. They are not recorded in the carrier (which stays the capture's provenance and
  // keeps the package identifier): verify lists them as added by the holder, with any field a
  // holder adds later. Each is checked with holderFieldProblem (Error(Usage)).
  std::vector<std::pair<std::string, std::string>> bagInfo;
  bool replace = false;  // an existing package of that name may be replaced (pack --force)
  // Where crm.rdf mints its node URIs (pack --base-uri; baseUriProblem), recorded in bag-info
  // as Surrogate-Base-URI so that verify derives the same crm.rdf. Empty: the capture identifier.
  std::string baseUri;
};

struct PackResult {
  BagResult bag;
  std::string packageId;      // "urn:sha256:<SHA-256 of the carrier>"
  std::string captureId;      // "urn:surrogate:capture:<SHA-256 of the first file>"
  std::string previousPackageId;  // the package this one revises (previousPackage), or ""
  std::string packagingTime;  // xs:dateTime
};

// Packs the capture into `out` (folder, .tar or .zip by its name). Throws PayloadChanged if a
// file no longer matches the carrier (run the pipeline again), Error otherwise.
PackResult packCapture(const std::filesystem::path& capture, const std::filesystem::path& out,
                       const PackOptions& options = {});

// The version of libarchive in use (the library linked, not the headers), e.g. "3.6.2": it
// writes and reads every .tar and .zip package, so runs record it with the other libraries.
std::string libarchiveVersion();

}  // namespace surrogate::archive
