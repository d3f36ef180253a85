// The capture folder: what a photographer brings (RTIBuilder / CHI convention).
//
//   CAPTURE/original-captures/  (or raw-images/)  untouched camera files: raw, DNG, JPEG, TIFF
//   CAPTURE/jpeg-exports/       optional exports of the same shots (paired by file stem)
//   CAPTURE/*.lp                optional known light directions (dome captures)
//   CAPTURE/assembly-files/     written by Surrogate (and files of another tool: prior work)
//   CAPTURE/finished-files/     written by Surrogate (and files of another tool: prior work)
//
// scanCapture() reads only names and headers: it finds the shots, pairs originals with their
// exports, and refuses a capture Surrogate cannot process faithfully, naming the file and the
// problem: an empty folder, two files of one shot in the same folder (duplicate stems),
// unreadable or truncated images, images of different sizes within one set, a .lp file that
// names images that are not there.
//
//   CaptureLayout layout = scanCapture("/data/stela12", threads);
//   for (const Shot& s : layout.shots) ... s.original->relativePath ...
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::capture {

inline constexpr const char* kAssemblyDir = "assembly-files";
inline constexpr const char* kFinishedDir = "finished-files";
inline constexpr const char* kExportsDir = "jpeg-exports";
// The folders a photographer brings, in the order Surrogate looks for them: the originals
// (under either name) and their exports. A folder with none of them is not a capture.
inline constexpr std::array<const char*, 3> kSourceFolders = {"original-captures", "raw-images", kExportsDir};
// The record and its view, relative to the capture: the carrier (the provenance document) and
// the HTML report made from it (never listed in the carrier: it holds the time it was made).
inline constexpr const char* kCarrierPath = "assembly-files/carrier.xml";
inline constexpr const char* kReportPath = "finished-files/report.html";
// Surrogate's own working area inside a capture: the lock that lets one process at a time work
// on it and the staging folder of a run in progress. Never recorded, never bagged.
inline constexpr const char* kWorkDir = ".surrogate";
// Results of earlier runs that a later run no longer produces, moved aside (the move is
// recorded in the carrier's run history). Never recorded as files, never bagged.
inline constexpr const char* kSupersededDir = "superseded-files";

// Files that operating systems and file managers leave in folders and on cards (.DS_Store,
// Thumbs.db, desktop.ini, AppleDouble "._" files, Spotlight/Trash folders): not part of a
// capture, never recorded, never bagged. The one rule run, pack and verify share.
bool isSystemFile(const std::string& fileName);

// The step an Error names when the folder given is not a capture Surrogate can take (missing,
// not a folder, no source folder, unreadable).
inline constexpr const char* kCaptureCheckStep = "capture ingest";

// True when `folder` holds one of kSourceFolders: what every command that writes into a capture
// checks first, so that nothing is written into a folder that is not one.
bool hasSourceFolder(const std::filesystem::path& folder);

// The name of a file Surrogate was writing when it was interrupted (".NAME.part-PID-N", see
// core/atomic_file.h). Inside assembly-files/ and finished-files/ such a file is Surrogate's
// leftover: never prior work, never bagged. (In the input folders the same name is a file the
// photographer brought, and is recorded like any other.)
bool isInterruptedWrite(const std::string& fileName);

struct ImageFile {
  std::string relativePath;  // to the capture root, '/' separated
  std::string format;        // "camera raw", "DNG", "JPEG", "TIFF", "PNG" (see image/)
  bool cameraRaw = false;
  int width = 0, height = 0;
};

// One photograph of the capture: its original and/or its export.
struct Shot {
  std::string stem;  // file name without extension: the pairing key
  std::optional<ImageFile> original;
  std::optional<ImageFile> exported;
};

struct CaptureLayout {
  std::filesystem::path root;
  std::string originalsDir;        // "original-captures", "raw-images", or "" (exports only)
  std::vector<Shot> shots;         // sorted by stem
  std::optional<std::string> lp;   // the .lp chosen for a dome capture (relative path)
  std::vector<std::string> sidecars;  // .xmp files next to originals
  // Every other file the capture brings (notes, files in sub-folders, .lp files not chosen):
  // recorded with role "other" and bagged, not used by the pipeline. Outside assembly-files/
  // and finished-files/, which hold what Surrogate wrote and prior work (outputFolderFiles).
  std::vector<std::string> others;
  std::vector<std::string> systemFiles;  // left out by isSystemFile(), for the log
  // Every file under assembly-files/ and finished-files/ (sorted), less the carrier and
  // interrupted writes: Surrogate's results of earlier runs (and its report) or prior work made
  // by another tool (RTIBuilder's .lp, .ptm, log). Which is which only the carrier can tell
  // (stages/prior_work.h).
  std::vector<std::string> outputFolderFiles;

  bool hasOriginals() const { return !originalsDir.empty(); }
  bool hasExports() const;
  // Width and height of the images the pipeline reads (the originals', else the exports').
  std::pair<int, int> frameSize() const;
};

// Scans and checks a capture folder; `threads` bounds the parallel header reads. `domeLp`, when
// not empty, is the capture-relative path of the .lp file that gives the lights (dome capture,
// `--lp`): it must be a regular file inside the capture and name only its images. Symbolic
// links anywhere in the capture's input folders are refused (loops too): the record holds a
// file's bytes, and a link's target can change or lie outside the capture. Before any image is
// read, every name is judged by the rule pack and verify apply (core/file_names.h): names that
// differ only in letter case or Unicode normalisation, names holding a backslash or a control
// character, names that are not UTF-8 text and paths too long for a package are refused
// together, in one Error(Input) listing every one of them (escaped, \xNN) and what to do.
CaptureLayout scanCapture(const std::filesystem::path& root, int threads,
                          const std::string& domeLp = "");

// Only the outputFolderFiles of scanCapture (names and links checked the same way), without
// reading any image: what a run compares with its plan once an interrupted commit is finished.
std::vector<std::string> listOutputFolderFiles(const std::filesystem::path& root);

// Refuses (Error(Input), naming the folder and saying what a capture folder holds) a folder
// that is not a capture: no original-captures/, raw-images/ or jpeg-exports/ with an image in
// it (judged by file names). Reads names only and writes nothing: `run` calls it before it
// creates anything in the folder, its lock included.
void requireCaptureFolder(const std::filesystem::path& root);

// Which images the pipeline decodes.
enum class Source {
  Auto,      // originals when every shot has one (raw first, as RTIBuilder), else exports
  Original,  // the files in original-captures/ (or raw-images/)
  Export,    // the files in jpeg-exports/
};
Source parseSource(const std::string& text);  // "auto", "original", "export"
const char* sourceName(Source source);

// The image of each shot that `source` selects, in shot order. Throws Error(Input) naming the
// shot when one lacks the requested image.
std::vector<ImageFile> selectImages(const CaptureLayout& layout, Source source);

// The shot a name refers to: a stem ("IMG_0003"), a file name or a relative path, as users
// write in --exclude and as .lp files list them (matched by base name). Empty if none.
std::optional<std::string> findShotStem(const CaptureLayout& layout, const std::string& name);

}  // namespace surrogate::capture
