// The capture folder: what a photographer brings (RTIBuilder / CHI convention).
//
//   CAPTURE/original-captures/  (or raw-images/)  untouched camera files: raw, DNG, JPEG, TIFF
//   CAPTURE/jpeg-exports/       optional exports of the same shots (paired by file stem)
//   CAPTURE/*.lp                optional known light directions (dome captures)
//   CAPTURE/assembly-files/     written by Surrogate
//   CAPTURE/finished-files/     written by Surrogate
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

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::capture {

inline constexpr const char* kAssemblyDir = "assembly-files";
inline constexpr const char* kFinishedDir = "finished-files";
inline constexpr const char* kExportsDir = "jpeg-exports";

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
  std::optional<std::string> lp;   // relative path of the capture's .lp file
  std::vector<std::string> sidecars;  // .xmp files next to originals
  std::vector<std::string> ignored;   // other files that are not images (reported, not used)

  bool hasOriginals() const { return !originalsDir.empty(); }
  bool hasExports() const;
};

// Scans and checks a capture folder; `threads` bounds the parallel header reads.
CaptureLayout scanCapture(const std::filesystem::path& root, int threads);

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
