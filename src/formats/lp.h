// Light position files (.lp): which photograph was lit from which direction.
//
//     3
//     IMG_0001.JPG 0.500000 0.500000 0.707107
//     my photo 2.jpg -0.5 0.5 0.707107
//     ...
//
// Line 1 is the number of lights N (1..1000). Each further line is a file name followed by
// the three components of the light direction (lx, ly, lz): x to the right of the image, y to
// its TOP, z towards the camera (docs/formats.md, ".lp" and "Light directions"). Tokens are
// separated by any whitespace; when a line has more than four tokens the leading ones are
// joined with single spaces into a file name that contains spaces. '\r\n' line ends and a
// UTF-8 byte-order mark are accepted; blank lines are ignored.
//
//   std::vector<LightEntry> lights = readLp("capture/assembly-files/lights.lp");
//   for (const LightEntry& l : lights) use(l.filename, l.x, l.y, l.z);  // unit vectors
//   writeLp("out.lp", lights);
//
// Image names. An .lp names each image by a path relative to the .lp file's own folder, with
// '/' separators, as RTIBuilder and relight expect (lpImageName writes them so); reading, the
// names are resolved by one rule, resolveLpImage (below, and docs/user-guide.md, `fit`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surrogate::formats {

struct LightEntry {
  std::string filename;  // as written in the file (often a path; match by base name)
  double x = 0, y = 0, z = 1;

  bool operator==(const LightEntry& o) const {
    return filename == o.filename && x == o.x && y == o.y && z == o.z;
  }
};

// The longest image name an .lp may hold: PATH_MAX on Linux, longer than any path Windows or
// macOS accept.
inline constexpr std::size_t kMaxImageNameBytes = 4096;

// Reads and validates a .lp file. Directions are normalised to unit length (the file may hold
// any length). Throws Error(Input) naming the file and the line when: the count is not an
// integer in 1..1000, a line has fewer than 4 tokens or a non-numeric component, an image name
// is longer than kMaxImageNameBytes, a direction is shorter than 1e-4, or the number of light
// lines differs from the count.
std::vector<LightEntry> readLp(const std::filesystem::path& path);

// The same, from text already in memory; `name` is used in error messages.
std::vector<LightEntry> parseLp(const std::string& text, const std::string& name);

// Writes "N\n" then "<filename> <x> <y> <z>\n" per light, each component the shortest text that
// reads back as the same double (formatNumber, core/text.h), atomically (a temporary file
// renamed into place). Throws Error(Input) when a filename is empty, contains a tab or a line
// break, or starts/ends with a space (it would not read back), or a component is not finite.
void writeLp(const std::filesystem::path& path, const std::vector<LightEntry>& entries);
std::string formatLp(const std::vector<LightEntry>& entries, const std::string& name);

// The name an .lp file at `lpFile` gives `image`: the image's path relative to the .lp's
// folder, '/'-separated ("stela12/original-captures/IMG_0001.dng",
// "../stela12/jpeg-exports/IMG_0001.jpg"). Both paths are made absolute (against the working
// directory) and weakly canonical first, so the result does not depend on the working
// directory or on how either path was spelled. When no relative path exists (another drive
// on Windows) the image's absolute path is returned.
std::string lpImageName(const std::filesystem::path& lpFile, const std::filesystem::path& image);

// How well an .lp line's image name designates an image file, comparing base names only
// (folders are ignored; '\\' counts as a separator): 1 = the same name, 2 = the same but for
// letter case, 3 = the same but for the extension (or one of the two has none), 4 = the same
// but for the extension and letter case; 0 = another image. Letter case is compared for ASCII
// letters only. Other tools name exports and originals alike ("IMG_0001.JPG" in the .lp,
// "IMG_0001.CR2" or "img_0001.jpg" on disk), hence the leniency.
int lpNameRank(const std::string& lpName, const std::string& imageName);

// Pairs the lines of an .lp with a set of images (file names or shot names), by lpNameRank:
// each line goes to the image it designates best, and each image takes, of the lines that went
// to it, the one that designates it best. Throws Error(Input) naming `lpFile` when that is not
// unambiguous: a line that designates two images equally well ("IMG_1.jpg" with both
// "img_1.JPG" and "IMG_1.JPG" present), or an image that two lines designate equally well
// ("IMG_1.JPG" and "IMG_1.CR2" for the shot IMG_1).
struct LpMatch {
  std::vector<std::optional<std::size_t>> lineOfImage;  // per image: its line, if any
  std::vector<std::optional<std::size_t>> imageOfLine;  // per line: the image it went to, if any
};
LpMatch matchLpLines(const std::string& lpFile, const std::vector<LightEntry>& lines,
                     const std::vector<std::string>& images);

// Where the image that an .lp file at `lpFile` names `name` may be, in the order tried.
// Backslashes in `name` are taken as separators (.lp files from Windows). With DIR the .lp's
// folder (absolute, weakly canonical):
//   1. DIR/name                  (the rule: names are relative to the .lp's folder)
//   2. DIR/../name               (RTIBuilder writes CAPTURE/assembly-files/*.lp naming
//                                 "jpeg-exports\000.jpg" relative to CAPTURE)
//   3. by base name: DIR/BASE, then for CAPTURE = DIR and then DIR/..:
//      CAPTURE/jpeg-exports/BASE, CAPTURE/original-captures/BASE, CAPTURE/raw-images/BASE
// An absolute name ("/data/a.jpg", "C:\caps\a.jpg", "\\server\a.jpg") replaces steps 1 and
// 2 by the name itself (only when it is absolute on this system); step 3 follows. Duplicates
// are listed once.
std::vector<std::filesystem::path> lpImageCandidates(const std::filesystem::path& lpFile,
                                                     const std::string& name);

// The first of lpImageCandidates that is a regular file (an absolute name is thus used as it
// is only if it exists). When none is, the folders of the candidates are searched in the same
// order for an image file (JPEG, TIFF, PNG or camera raw, by its extension: never a sidecar
// such as IMG_0001.xmp) that lpNameRank accepts (another letter case or extension): the first
// folder holding one wins, its best-ranked file is returned, and two files of equal rank there
// are refused (Error(Input) naming `lpFile` and both files). nullopt when nothing fits.
std::optional<std::filesystem::path> resolveLpImage(const std::filesystem::path& lpFile,
                                                    const std::string& name);

}  // namespace surrogate::formats
