// The evidence of an audit: another tool's work (a capture folder as RTIBuilder leaves it, or
// a package) copied byte for byte into the audit's own work folder, without writing anything
// into it. `surrogate audit PRIOR` audits the copy; PRIOR stays as it was, to the byte and to
// the timestamp, and may be read-only.
//
//   WorkFolder w = prepareWorkFolder("/archive/stela12", std::nullopt, progress);
//   // w.folder: /archive/stela12-audit, a capture of its own; w.copied: the record of what was
//   // copied from where (carrier::Header::audited), to give the first run of the folder.
//
// What is evidence: every regular file of PRIOR but Surrogate's own working files (.surrogate/,
// superseded-files/, interrupted writes in the output folders), files operating systems leave
// (capture::isSystemFile) and, when PRIOR was itself processed by Surrogate, the results its
// carrier records as Surrogate's (roles assembly and result, the carrier, the report). Each
// copy keeps its path relative to the capture, and PRIOR's modification time.
//
// PRIOR's files and folders, and a package file, are opened with O_NOATIME where the system
// allows it (the owner, or root), so that not even their access times change (a bag folder's
// own folders are listed by archive's reader, which does not). Symbolic links and special files
// in PRIOR are refused as a capture's scan refuses them; PRIOR itself may be a link to a folder
// or a package, audited as what it points to, and "inside PRIOR" is judged with every link
// followed, so that no work folder reached through a link lands in it.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "carrier/carrier.h"

namespace surrogate::evidence {

// Progress: (label, fraction 0..1).
using Progress = std::function<void(const std::string&, double)>;

// What PRIOR is (a link followed), judged from its names and its listing, read as above.
enum class SourceKind {
  Folder,      // a capture folder (original-captures/, raw-images/ or jpeg-exports/)
  Package,     // a .zip or .tar file, or a bag folder (bagit.txt)
  WorkFolder,  // the work folder of an earlier audit: audited in place
};
SourceKind sourceKind(const std::filesystem::path& prior);

// The default work folder: beside PRIOR, named after it with "-audit" ("stela12" ->
// "stela12-audit", "stela12.zip" -> "stela12-audit").
std::filesystem::path defaultWorkFolder(const std::filesystem::path& prior);

struct WorkFolder {
  std::filesystem::path folder;  // absolute
  // Set when this call copied the evidence (a new work folder, or an unfinished one made
  // again): the record the folder's first run writes into its carrier's header.
  std::optional<carrier::AuditedSource> copied;
  bool reused = false;  // an earlier audit's folder of the same, unchanged PRIOR
};

// Makes or finds the work folder of auditing `prior` (`work`: the -o given, else the default):
//   - PRIOR an audit's work folder: itself (Error(Usage) when `work` names another folder);
//   - no folder at `work`: a new one, filled under a temporary name and renamed when complete;
//   - the work folder of an earlier audit of the same PRIOR (its carrier's audited source):
//     reused when every file of PRIOR is still what it copied (same paths, sizes, SHA-256),
//     else Error(Input) naming what changed and what to do;
//   - a folder this function began and never ran (no carrier yet): made again;
//   - anything else: Error(Usage) saying to give another -o.
// `work` inside PRIOR is refused: the audit never writes into PRIOR.
WorkFolder prepareWorkFolder(const std::filesystem::path& prior,
                             const std::optional<std::filesystem::path>& work, const Progress& progress);

// The first difference between two records of the same PRIOR ("jpeg-exports/IMG_3.jpg changed
// (SHA-256 ...)", "... is new", "... is gone"), with how many more there are; empty when the
// files are the same.
std::string evidenceDifference(const carrier::AuditedSource& recorded, const carrier::AuditedSource& now);

}  // namespace surrogate::evidence
