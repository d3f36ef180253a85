// Light position files (.lp): which photograph was lit from which direction.
//
//     3
//     IMG_0001.JPG 0.500000 0.500000 0.707107
//     my photo 2.jpg -0.5 0.5 0.707107
//     ...
//
// Line 1 is the number of lights N (1..1000). Each further line is a file name followed by
// the three components of the light direction (lx, ly, lz): x to the right of the image, y to
// its TOP, z towards the camera (shared/spec/formats.md sections 3 and 5). Tokens are
// separated by any whitespace; when a line has more than four tokens the leading ones are
// joined with single spaces into a file name that contains spaces. '\r\n' line ends and a
// UTF-8 byte-order mark are accepted; blank lines are ignored.
//
//   std::vector<LightEntry> lights = readLp("capture/assembly-files/lights.lp");
//   for (const LightEntry& l : lights) use(l.filename, l.x, l.y, l.z);  // unit vectors
//   writeLp("out.lp", lights);
#pragma once

#include <filesystem>
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

// Reads and validates a .lp file. Directions are normalised to unit length (the file may hold
// any length). Throws Error(Input) naming the file and the line when: the count is not an
// integer in 1..1000, a line has fewer than 4 tokens or a non-numeric component, a direction
// is shorter than 1e-4, or the number of light lines differs from the count.
std::vector<LightEntry> readLp(const std::filesystem::path& path);

// The same, from text already in memory; `name` is used in error messages.
std::vector<LightEntry> parseLp(const std::string& text, const std::string& name);

// Writes "N\n" then "<filename> %.6f %.6f %.6f\n" per light, atomically (a temporary file
// renamed into place). Throws Error(Input) when a filename is empty, contains a tab or a line
// break, or starts/ends with a space (it would not read back), or a component is not finite.
void writeLp(const std::filesystem::path& path, const std::vector<LightEntry>& entries);
std::string formatLp(const std::vector<LightEntry>& entries, const std::string& name);

}  // namespace surrogate::formats
