// Private to src/publish: reading the files of a web layout (info.json, a .dzi, a plane or a
// tile) as they are, never through a symbolic link.
//
// A layout is a folder anyone may have made; a plane that is a link to another file would be
// decoded, and libjpeg's refusal quotes its first bytes ("Not a JPEG file: starts with 0x72
// 0x6f"), so a link is refused, naming it and nothing of its target. The final name is opened
// with O_NOFOLLOW (no window between a check and the open); folders inside the layout
// (plane_N_files/, its levels) are checked with refuseLinkedFolder before a tile is read.
//
//   const std::string bytes = readLayoutFile(folder / "plane_0.jpg", limit, "render");
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace surrogate::publish {

// An info.json is a few kilobytes; relight's PCA bases make it a few megabytes at most.
constexpr std::uintmax_t kMaxInfoJsonBytes = 64u << 20;

// The whole file. Throws Error(Input) naming `file` when it is a symbolic link, is not a
// regular file, is missing or unreadable, or holds more than `maxBytes`.
std::string readLayoutFile(const std::filesystem::path& file, std::uintmax_t maxBytes, const std::string& step);

// Throws Error(Input) naming `folder` when it is a symbolic link.
void refuseLinkedFolder(const std::filesystem::path& folder, const std::string& step);

// Whether anything (a file, a folder, a link, even a dangling one) is at `path`.
bool somethingAt(const std::filesystem::path& path);

}  // namespace surrogate::publish
