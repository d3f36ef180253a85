#include "capture/capture.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <system_error>

#include "core/error.h"
#include "core/file_names.h"
#include "core/parallel.h"
#include "core/text.h"
#include "formats/lp.h"
#include "image/decode.h"

namespace surrogate::capture {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = kCaptureCheckStep;

void refuseSymlink(const fs::path& p, const fs::path& root) {
  if (!fs::is_symlink(p)) return;
  throwInputError(p.lexically_relative(root).generic_string(), kStep,
                  "is a symbolic link; Surrogate records and packs a file's own bytes, and a "
                  "link's target can change or lie outside the capture: replace the link by a "
                  "copy of the file (cp -L), then run again");
}

std::string relativeTo(const fs::path& p, const fs::path& root) {
  return p.lexically_relative(root).generic_string();
}

// A name as a message can show it (core/file_names.h).
std::string escapedName(const std::string& name) { return shownName(name); }

// The names a package cannot hold (core/file_names.h: the rule pack and verify apply too),
// every one of them in one refusal, before any file is read.
void refuseUnholdableNames(const fs::path& root, std::vector<std::string> paths) {
  const NameProblems problems = findNameProblems(paths, std::string("data/").size());
  if (!problems.empty())
    throwInputError(escapedName(root.string()), kStep, problems.describe("of the capture", "then run (or pack) again"));
}

// The entries of a folder, sorted: the carrier lists files in a fixed order.
std::vector<fs::path> sortedEntries(const fs::path& dir, const fs::path& root) {
  std::vector<fs::path> entries;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) entries.push_back(it->path());
  if (ec)
    throwInputError(escapedName(dir == root ? dir.string() : relativeTo(dir, root)), kStep,
                    "cannot be read (" + ec.message() + "); check that the folder exists and that "
                    "you may read it");
  std::sort(entries.begin(), entries.end());
  return entries;
}

// A capture folder that must be a real folder (original-captures/, raw-images/,
// jpeg-exports/): refused when it is a symbolic link (even one that loops); true when it is a
// folder, false when absent or another kind of file.
bool isCaptureFolder(const fs::path& p, const fs::path& root) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (ec || !fs::exists(st)) return false;
  refuseSymlink(p, root);
  return fs::is_directory(st);
}

void collectOthers(const fs::path& dir, CaptureLayout& layout);

// What every entry of a capture's input folders goes through first: a link or a special file
// is refused, a system file set aside, a folder taken whole as other files. True when `p` was
// handled here; regular files are left to the caller.
bool handleNonRegular(const fs::path& p, CaptureLayout& layout) {
  const std::string rel = relativeTo(p, layout.root);
  refuseSymlink(p, layout.root);
  if (isSystemFile(p.filename().string())) {
    layout.systemFiles.push_back(rel);
    return true;
  }
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (ec) throwInputError(rel, kStep, "cannot be read (" + ec.message() + "); check your permissions");
  if (fs::is_directory(st)) {
    collectOthers(p, layout);
    return true;
  }
  if (!fs::is_regular_file(st))
    throwInputError(rel, kStep, "is not a regular file (a device, pipe or socket); remove it from the capture");
  return false;
}

// Every file under `dir` (recursively) as "other" files of the capture.
void collectOthers(const fs::path& dir, CaptureLayout& layout) {
  for (const fs::path& p : sortedEntries(dir, layout.root))
    if (!handleNonRegular(p, layout)) layout.others.push_back(relativeTo(p, layout.root));
}

// Every file under `dir` (recursively) into the layout's outputFolderFiles, less Surrogate's
// carrier (whose presence is what makes the other files Surrogate's or not) and interrupted
// writes. Links and special files are refused as in the input folders.
void collectOutputFolder(const fs::path& dir, CaptureLayout& layout) {
  for (const fs::path& p : sortedEntries(dir, layout.root)) {
    const std::string rel = relativeTo(p, layout.root);
    refuseSymlink(p, layout.root);
    if (isSystemFile(p.filename().string())) {
      layout.systemFiles.push_back(rel);
      continue;
    }
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    if (ec) throwInputError(rel, kStep, "cannot be read (" + ec.message() + "); check your permissions");
    if (fs::is_directory(st)) {
      collectOutputFolder(p, layout);
      continue;
    }
    if (!fs::is_regular_file(st))
      throwInputError(rel, kStep, "is not a regular file (a device, pipe or socket); remove it from the capture");
    if (rel == kCarrierPath || isInterruptedWrite(p.filename().string())) continue;
    layout.outputFolderFiles.push_back(rel);
  }
}

// The outputFolderFiles of the capture at `root` (absolute), names not yet judged.
std::vector<std::string> outputFolderFilesOf(const fs::path& root) {
  CaptureLayout layout;
  layout.root = root;
  for (const char* dir : {kAssemblyDir, kFinishedDir})
    if (isCaptureFolder(layout.root / dir, layout.root)) collectOutputFolder(layout.root / dir, layout);
  return layout.outputFolderFiles;
}

bool looksLikeImage(const fs::path& p) {
  static const char* kExtensions[] = {".jpg", ".jpeg", ".tif", ".tiff", ".png"};
  const std::string ext = lowerCase(p.extension().string());
  for (const char* e : kExtensions)
    if (ext == e) return true;
  return image::isCameraRawExtension(p);
}

const char* formatName(image::SourceKind kind, const fs::path& p) {
  switch (kind) {
    case image::SourceKind::CameraRaw:
      return lowerCase(p.extension().string()) == ".dng" ? "DNG" : "camera raw";
    case image::SourceKind::Jpeg: return "JPEG";
    case image::SourceKind::Tiff: return "TIFF";
    case image::SourceKind::Png: return "PNG";
  }
  return "image";
}

struct FolderScan {
  std::vector<fs::path> images;  // absolute
};

// Lists the image files of one folder, sorted, refusing two files with the same stem.
FolderScan scanFolder(const fs::path& dir, CaptureLayout& layout) {
  FolderScan scan;
  std::map<std::string, fs::path> byStem;
  for (const fs::path& p : sortedEntries(dir, layout.root)) {
    if (handleNonRegular(p, layout)) continue;
    const std::string rel = relativeTo(p, layout.root);
    if (lowerCase(p.extension().string()) == ".xmp") {
      layout.sidecars.push_back(rel);
      continue;
    }
    if (!looksLikeImage(p)) {
      layout.others.push_back(rel);
      continue;
    }
    const std::string stem = p.stem().string();
    if (auto it = byStem.find(stem); it != byStem.end()) {
      throwInputError(rel, kStep,
                      "has the same name as " + relativeTo(it->second, layout.root) +
                          " (file stem \"" + stem + "\"): one shot can have only one file per "
                          "folder; move the extra file (e.g. a camera's RAW+JPEG twin) out of the "
                          "capture");
    }
    byStem[stem] = p;
    scan.images.push_back(p);
  }
  return scan;
}

// Reads the header of every image (in parallel) and fills in format and size.
std::vector<ImageFile> probeAll(const std::vector<fs::path>& files, const fs::path& root,
                                int threads) {
  std::vector<ImageFile> out(files.size());
  parallelFor(files.size(), 1, threads, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      const image::ImageProbe probe = image::probeImage(files[i]);
      ImageFile& f = out[i];
      // Lexically: the file is root/folder/name and neither is a link (refused by the scan), so
      // this is fs::relative's answer without its resolving of every folder above (a readlink
      // per component, 20 a file).
      f.relativePath = relativeTo(files[i], root);
      f.format = formatName(probe.kind, files[i]);
      f.cameraRaw = probe.kind == image::SourceKind::CameraRaw;
      f.width = probe.width;
      f.height = probe.height;
    }
  });
  return out;
}

void requireSameSize(const std::vector<ImageFile>& set, const std::string& folder) {
  for (const ImageFile& f : set) {
    if (f.width != set[0].width || f.height != set[0].height) {
      throwInputError(f.relativePath, kStep,
                      "is " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                          " pixels but " + set[0].relativePath + " is " +
                          std::to_string(set[0].width) + "x" + std::to_string(set[0].height) +
                          ": all images in " + folder + "/ must have the same size (the camera "
                          "must not move or change settings during an RTI capture)");
    }
  }
}

std::string baseName(const std::string& name) {
  // .lp files often hold Windows paths from RTIBuilder: split on both separators.
  const auto slash = name.find_last_of("/\\");
  return slash == std::string::npos ? name : name.substr(slash + 1);
}

}  // namespace

bool isSystemFile(const std::string& name) {
  static const char* kNames[] = {".DS_Store", "Thumbs.db", "ehthumbs.db", "ehthumbs_vista.db",
                                 "desktop.ini", "Desktop.ini", ".Spotlight-V100", ".Trashes",
                                 ".fseventsd", ".TemporaryItems", ".DocumentRevisions-V100",
                                 "$RECYCLE.BIN", "System Volume Information", ".directory"};
  for (const char* n : kNames)
    if (name == n) return true;
  return name.rfind("._", 0) == 0;  // AppleDouble: resource forks macOS writes on FAT cards
}

bool hasSourceFolder(const fs::path& folder) {
  std::error_code ec;  // an unreadable folder is not a capture: no exception
  for (const char* source : kSourceFolders)
    if (fs::is_directory(folder / source, ec)) return true;
  return false;
}

bool isInterruptedWrite(const std::string& name) {
  return !name.empty() && name[0] == '.' && name.find(".part-") != std::string::npos;
}

std::pair<int, int> CaptureLayout::frameSize() const {
  for (const Shot& s : shots)
    if (hasOriginals() && s.original) return {s.original->width, s.original->height};
  for (const Shot& s : shots)
    if (s.exported) return {s.exported->width, s.exported->height};
  return {0, 0};
}

bool CaptureLayout::hasExports() const {
  for (const Shot& s : shots)
    if (s.exported) return true;
  return false;
}

std::optional<std::string> findShotStem(const CaptureLayout& layout, const std::string& name) {
  const std::string base = baseName(name);
  const std::string stem = fs::path(base).stem().string();
  for (const Shot& s : layout.shots) {
    if (s.stem == base || s.stem == stem) return s.stem;
  }
  return std::nullopt;
}

void requireCaptureFolder(const fs::path& root) {
  std::error_code ec;
  if (!fs::is_directory(fs::status(root, ec))) return;  // the lock and scanCapture say what it is
  std::string present;  // the input folders the folder has, "original-captures/ and ..."
  for (const char* dir : kSourceFolders) {
    if (!fs::is_directory(fs::status(root / dir, ec))) continue;
    present += (present.empty() ? "" : " and ") + std::string(dir) + "/";
    fs::directory_iterator it(root / dir, ec), end;
    for (; !ec && it != end; it.increment(ec))
      if (looksLikeImage(it->path()) && !isSystemFile(it->path().filename().string())) return;
  }
  std::size_t loose = 0;  // images lying in the folder itself
  fs::directory_iterator it(root, ec), end;
  for (; !ec && it != end; it.increment(ec))
    loose += looksLikeImage(it->path()) && fs::is_regular_file(it->status(ec));
  std::string what = present.empty() ? "has no original-captures/ (or raw-images/) and no jpeg-exports/ folder"
                                     : "has " + present + " but no images in " +
                                           (present.find(" and ") == std::string::npos ? "it" : "them");
  if (loose > 0) what += ", and its " + std::to_string(loose) + " image(s) lie in the folder itself";
  throwInputError(escapedName(root.string()), kStep,
                  "is not a capture folder: it " + what + ". A capture folder holds the camera files "
                  "in original-captures/ (or raw-images/) and, optionally, JPEG exports of the same "
                  "shots in jpeg-exports/; Surrogate writes assembly-files/ and finished-files/ beside "
                  "them. Put the camera files in original-captures/, then run again");
}

CaptureLayout scanCapture(const fs::path& root, int threads, const std::string& domeLp) {
  std::error_code ec;
  const fs::file_status rootStatus = fs::status(root, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    throwInputError(escapedName(root.string()), kStep,
                    ec == std::errc::too_many_symbolic_link_levels
                        ? "is a loop of symbolic links, not a folder; give the capture folder itself"
                        : "cannot be read (" + ec.message() + "); check the path and your permissions");
  }
  if (!fs::exists(rootStatus)) throwInputError(escapedName(root.string()), kStep, "the capture folder does not exist");
  if (!fs::is_directory(rootStatus))
    throwInputError(escapedName(root.string()), kStep, "is not a folder; give the capture folder");
  CaptureLayout layout;
  layout.root = fs::absolute(root).lexically_normal();
  // The capture folder's own name titles the project unless --title says otherwise, and is
  // shown in every record and message: UTF-8 text like every name in it.
  if (const std::string name = layout.root.filename().string(); !isValidUtf8(name))
    throwInputError(escapedName(root.string()), kStep,
                    "the capture folder's name is not UTF-8 text (the bytes that are not are shown as "
                    "\\xNN; it was probably written in another encoding, such as Latin-1): the carrier "
                    "records the project's title, by default this name, as UTF-8 text; rename the "
                    "folder, then run again");

  for (const char* candidate : {"original-captures", "raw-images"}) {
    if (isCaptureFolder(layout.root / candidate, layout.root)) {
      if (!layout.originalsDir.empty()) {
        throwInputError(root.string(), kStep,
                        "has both original-captures/ and raw-images/; keep the originals in one "
                        "of them");
      }
      layout.originalsDir = candidate;
    }
  }
  const bool exportsDir = isCaptureFolder(layout.root / kExportsDir, layout.root);
  if (layout.originalsDir.empty() && !exportsDir) {
    throwInputError(root.string(), kStep,
                    "has no original-captures/ (or raw-images/) and no jpeg-exports/ folder; put "
                    "the camera files in original-captures/");
  }

  // Names first, every file and folder of the capture listed; images are read only once every
  // name is one the package can hold.
  FolderScan originalsScan, exportsScan;
  if (!layout.originalsDir.empty()) {
    originalsScan = scanFolder(layout.root / layout.originalsDir, layout);
    if (originalsScan.images.empty())
      throwInputError((layout.root / layout.originalsDir).string(), kStep,
                      "contains no images; copy the camera files of the capture into it");
  }
  if (exportsDir) {
    exportsScan = scanFolder(layout.root / kExportsDir, layout);
    if (exportsScan.images.empty() && layout.originalsDir.empty())
      throwInputError((layout.root / kExportsDir).string(), kStep, "contains no images");
  }
  // Everything else at the top of the capture: files (and folders) that are not Surrogate's
  // output folders or its working area are recorded as "other" files.
  for (const fs::path& p : sortedEntries(layout.root, layout.root)) {
    const std::string name = p.filename().string();
    if (name == layout.originalsDir || name == kExportsDir || name == kAssemblyDir ||
        name == kFinishedDir || name == kWorkDir || name == kSupersededDir)
      continue;
    if (!handleNonRegular(p, layout)) layout.others.push_back(name);
  }
  layout.outputFolderFiles = outputFolderFilesOf(layout.root);

  {
    std::vector<std::string> names = layout.others;
    for (const auto* scan : {&originalsScan, &exportsScan})
      for (const fs::path& p : scan->images) names.push_back(relativeTo(p, layout.root));
    names.insert(names.end(), layout.sidecars.begin(), layout.sidecars.end());
    names.insert(names.end(), layout.outputFolderFiles.begin(), layout.outputFolderFiles.end());
    // What Surrogate writes besides: an "Assembly-Files/" of the user's is one with its own.
    names.push_back(kCarrierPath);
    names.push_back(kReportPath);
    refuseUnholdableNames(layout.root, std::move(names));
  }

  std::vector<ImageFile> originals, exports;
  if (!layout.originalsDir.empty()) {
    originals = probeAll(originalsScan.images, layout.root, threads);
    requireSameSize(originals, layout.originalsDir);
  }
  if (exportsDir) {
    exports = probeAll(exportsScan.images, layout.root, threads);
    if (!exports.empty()) requireSameSize(exports, kExportsDir);
  }

  std::map<std::string, Shot> shots;
  for (ImageFile& f : originals) {
    const std::string stem = fs::path(f.relativePath).stem().string();
    shots[stem].stem = stem;
    shots[stem].original = std::move(f);
  }
  for (ImageFile& f : exports) {
    const std::string stem = fs::path(f.relativePath).stem().string();
    shots[stem].stem = stem;
    shots[stem].exported = std::move(f);
  }
  for (auto& [stem, shot] : shots) layout.shots.push_back(std::move(shot));

  if (!domeLp.empty()) {
    const auto it = std::find(layout.others.begin(), layout.others.end(), domeLp);
    if (it == layout.others.end())
      throw Error(ErrorKind::Usage, "--lp " + domeLp, kStep,
                  "is not a file of the capture outside its folders of images and of Surrogate's "
                  "outputs; copy the dome's .lp file into the capture folder (e.g. " +
                      root.string() + "/dome.lp) and give its name");
    layout.others.erase(it);
    layout.lp = domeLp;
    // The same pairing as the LightsFromFile stage (formats::matchLpLines): it refuses a line
    // that could mean two shots, or two lines for one shot.
    const std::vector<formats::LightEntry> lines = formats::readLp(layout.root / domeLp);
    std::vector<std::string> stems;
    for (const Shot& s : layout.shots) stems.push_back(s.stem);
    const formats::LpMatch match = formats::matchLpLines(domeLp, lines, stems);
    for (std::size_t l = 0; l < lines.size(); ++l) {
      if (!match.imageOfLine[l]) {
        throwInputError(domeLp, kStep,
                        "names the image \"" + lines[l].filename + "\", which is not in the capture; "
                        "fix the .lp file or add the missing image");
      }
    }
  }
  return layout;
}

std::vector<std::string> listOutputFolderFiles(const fs::path& root) {
  const fs::path absolute = fs::absolute(root).lexically_normal();
  std::vector<std::string> files = outputFolderFilesOf(absolute);
  refuseUnholdableNames(absolute, files);
  return files;
}

Source parseSource(const std::string& text) {
  if (text == "auto") return Source::Auto;
  if (text == "original" || text == "raw") return Source::Original;
  if (text == "export" || text == "jpeg") return Source::Export;
  throw Error(ErrorKind::Usage, "--source", "options",
              "unknown image source \"" + text + "\"; use auto, original or export");
}

const char* sourceName(Source source) {
  switch (source) {
    case Source::Auto: return "auto";
    case Source::Original: return "original";
    case Source::Export: return "export";
  }
  return "auto";
}

std::vector<ImageFile> selectImages(const CaptureLayout& layout, Source source) {
  if (source == Source::Auto) {
    const bool allOriginals = std::all_of(layout.shots.begin(), layout.shots.end(),
                                          [](const Shot& s) { return s.original.has_value(); });
    source = allOriginals ? Source::Original : Source::Export;
  }
  std::vector<ImageFile> out;
  for (const Shot& s : layout.shots) {
    const auto& chosen = source == Source::Original ? s.original : s.exported;
    if (!chosen) {
      const auto& other = source == Source::Original ? s.exported : s.original;
      throwInputError(other ? other->relativePath : s.stem, kStep,
                      std::string("has no ") +
                          (source == Source::Original ? "original in " + layout.originalsDir + "/"
                                                      : std::string("export in jpeg-exports/")) +
                          " with the same name; every shot needs one, or choose the other "
                          "source with --source");
    }
    out.push_back(*chosen);
  }
  return out;
}

}  // namespace surrogate::capture
