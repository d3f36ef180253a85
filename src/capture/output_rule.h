// The one rule for every path a command writes (`run`'s captures aside, every `-o`): a
// command never writes over a capture's evidence or its record, never into a device, and never
// replaces a file it was not told it may replace.
//
//   capture::checkOutputTarget(*out, "-o", capture::ExistingOutput::ReplaceOutput);
//
// Refused, each with Error(Input) (exit 1) naming the option, the path and what to do:
//   - a path inside a folder named original-captures/, raw-images/ or jpeg-exports/ (the
//     untouched originals of a capture, whichever capture it is);
//   - a path inside the folders Surrogate manages in a capture (assembly-files/,
//     finished-files/, .surrogate/, superseded-files/), where an unrecorded file would make the
//     capture's record incomplete; with OutputPlace::OutsideCaptures, anywhere in a capture;
//   - a file that a capture's carrier records (an original, export, sidecar, prior work, the
//     carrier itself), by path or as the same file under another name (a hard link);
//   - anything at the path that is not a regular file: a symbolic link, a device such as
//     /dev/full, a FIFO, a socket (replacing it would destroy it, or write through it);
//   - a path inside a package folder: a bag (a folder holding bagit.txt), an OCFL object (its
//     0=ocfl_object_... file), an E-ARK package (METS.xml beside representations/):
//     a file added or replaced there makes the package invalid;
//   - an existing file with other names (more than one hard link): it may be an original, a
//     package or a recorded file reached under a name no carrier gives, which the rule cannot
//     find from the path (a ledger appends in place, through every name);
//   - with ExistingOutput::ReplaceOutput, an existing ZIP or tar archive: no command but `pack`
//     writes one, so it is a package or someone's archive, never an earlier output;
//   - with ExistingOutput::Refuse, an existing file at all (`pack` without --force).
// The checks follow symbolic links in the folders above the path, so that a link to a
// capture's folder is the folder. A capture is a folder holding assembly-files/carrier.xml or
// one of the originals' folders.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>

namespace surrogate::capture {

// What may happen to a regular file already at the output path.
enum class ExistingOutput {
  ReplaceOutput,  // documented: a render, report, fit, .lp or ledger written again over (or
                  // appended to) the last one; never a package or any other archive
  Replace,        // `pack --force` and the layouts' folders: a package over the last package
  Refuse,         // `pack` without --force: a package is never replaced silently
};

// Where the output may lie with respect to captures.
enum class OutputPlace {
  OutsideManagedFolders,  // anywhere but the originals' and Surrogate's folders of a capture
  OutsideCaptures,        // not inside any capture at all (a package would be bagged next time)
};

// Throws Error(Input) (exit 1) when the rule above forbids writing `output`; `option` names the
// command-line option in the message ("-o"); `refuseHint` is what to do about an existing
// file under ExistingOutput::Refuse ("give --force to replace it").
void checkOutputTarget(const std::filesystem::path& output, const std::string& option,
                       ExistingOutput existing, OutputPlace place = OutputPlace::OutsideManagedFolders,
                       const std::string& refuseHint = "");

// What a file of type `mode` (stat's st_mode) is, in a user's words, when it is not a regular
// file: "a symbolic link", "a device", "a FIFO (named pipe)", "a socket", "a folder"; "" for a
// regular file. The words of the rule's refusals, and of the ledger's (batch/ledger.h).
std::string fileTypeName(mode_t mode);

}  // namespace surrogate::capture
