// Prior work: files in a capture's assembly-files/ and finished-files/ that Surrogate did not
// write, such as the .lp, log XML and .ptm/.rti that RTIBuilder, relight or a dome's software
// left there. They are recorded (role "prior", with what they are and what they say of their
// making), bagged and checked like originals, and never modified, moved or written over.
//
// Which files of those folders are prior work only the capture's carrier can tell:
//   - a capture never processed (no carrier): every one of them;
//   - later: the files the carrier records as prior, and every file it does not record, except
//     one at a path the planned run writes (a leftover of an interrupted run of Surrogate's,
//     which the run replaces). Files it records as Surrogate's results stay Surrogate's.
//
//   const auto planned = plannedOutputs(plan);
//   refuseOutputsOverPriorWork(files, previous, planned);  // before anything runs
//   if (isPriorWork(path, previous, planned)) record(describePriorFile(abs));
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "carrier/carrier.h"

namespace surrogate::stages {

// What a prior file's own bytes say. `kind` comes from its name (.lp; .ptm or .rti; .xml or
// .log; anything else "other"); `madeBy`, `format` and `mediaType` from its content where it
// can be read: a PTM's version and format lines ("PTM_1.2 PTM_FORMAT_LRGB"), an .rti's first
// comment line ("HSH1.2"), a log XML's root element with its attributes
// (RTIBuilder's: "XMLCarrier schemaLocation=\"http://alba.di.uminho.pt/XMLCarrier
// lptracker.xsd\""; audit/rtibuilder_log.h reads the whole log); an .lp says nothing of the tool that made it. A file
// that cannot be read as what its name says is still prior work: `warning` says why nothing
// more is known.
struct PriorFile {
  std::string kind;  // lp, rti, log, other
  std::string madeBy;
  std::string format;     // the carrier's format name: LP, PTM_FORMAT_..., RTI_HSH, XML, ...
  std::string mediaType;  // empty when unknown
  std::string warning;
};
PriorFile describePriorFile(const std::filesystem::path& file, const std::string& relativePath);

// The capture-relative paths the steps of `plan` will write (pipeline::StageInfo::outputs, a '*'
// standing for any text), with the carrier and the report, which every run writes.
std::vector<std::string> plannedOutputs(const carrier::Carrier& plan);

// Whether `path` is one of `planned` (matching '*' in them).
bool isPlannedOutput(const std::string& path, const std::vector<std::string>& planned);

// Whether `path`, a file of assembly-files/ or finished-files/ (capture::CaptureLayout::
// outputFolderFiles), is prior work by the rule above; `previous` is the capture's carrier,
// null when it has none.
bool isPriorWork(const std::string& path, const carrier::Carrier* previous,
                 const std::vector<std::string>& planned);

// Throws Error(Usage) naming the first prior file among `outputFolderFiles` that the planned
// run would write over, saying what to do.
void refuseOutputsOverPriorWork(const std::vector<std::string>& outputFolderFiles,
                                const carrier::Carrier* previous,
                                const std::vector<std::string>& planned);

}  // namespace surrogate::stages
