#include "formats/lp.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text.h"
#include "formats/text_parse.h"
#include "image/source_kind.h"

namespace surrogate::formats {

namespace {
const char* const kReadStep = "read light positions";
const char* const kWriteStep = "write light positions";
constexpr long long kMaxLights = 1000;  // relight's limit (docs/formats.md, ".lp")
}  // namespace

std::vector<LightEntry> parseLp(const std::string& text, const std::string& name) {
  std::size_t pos = 0;
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) pos = 3;  // UTF-8 BOM from Windows editors
  int lineNumber = 0;
  auto fail = [&](const std::string& message) {
    throw Error(ErrorKind::Input, name, kReadStep,
                "line " + std::to_string(lineNumber) + ": " + message);
  };
  // Next non-blank line, or false at the end of the text.
  auto nextLine = [&](std::string_view* line) {
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      ++lineNumber;
      *line = std::string_view(text).substr(pos, end - pos);
      pos = end + 1;
      if (!trim(*line).empty()) return true;
    }
    return false;
  };

  std::string_view line;
  if (!nextLine(&line)) {
    throw Error(ErrorKind::Input, name, kReadStep,
                "the file is empty; a .lp file starts with the number of lights");
  }
  long long count = 0;
  const auto head = tokens(line);
  if (head.size() != 1 || !parseInt(head[0], &count)) {
    fail("expected the number of lights alone on the first line, found \"" +
         std::string(trim(line).substr(0, 60)) + "\"");
  }
  if (count < 1 || count > kMaxLights) {
    fail("the number of lights must be between 1 and " + std::to_string(kMaxLights) +
         ", found " + std::to_string(count));
  }

  std::vector<LightEntry> out;
  out.reserve(static_cast<std::size_t>(count));
  while (nextLine(&line)) {
    if (static_cast<long long>(out.size()) == count) {
      fail("the file announces " + std::to_string(count) +
           " lights on line 1 but has more light lines; fix the count or remove the extra lines");
    }
    const auto t = tokens(line);
    if (t.size() < 4) {
      fail("expected \"<image file> <x> <y> <z>\", found only " + std::to_string(t.size()) +
           " item(s)");
    }
    LightEntry e;
    double v[3];
    for (int k = 0; k < 3; ++k) {
      if (!parseDouble(t[t.size() - 3 + k], &v[k])) {
        fail("the light direction component \"" + std::string(t[t.size() - 3 + k].substr(0, 40)) +
             "\" is not a number");
      }
    }
    for (std::size_t k = 0; k + 3 < t.size(); ++k) {
      if (k) e.filename += ' ';
      e.filename.append(t[k].data(), t[k].size());
    }
    if (e.filename.size() > kMaxImageNameBytes) {
      fail("the image name is " + std::to_string(e.filename.size()) + " bytes long (it starts \"" +
           e.filename.substr(0, 40) + "...\"); a path has at most " + std::to_string(kMaxImageNameBytes) +
           " bytes: the file is damaged or not a light file");
    }
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    // Components near the largest double (1e308) overflow the length to infinity: divided by it,
    // the direction would be (0, 0, 0), passed on as if read.
    if (!std::isfinite(norm)) {
      fail("the light direction of \"" + e.filename +
           "\" is too large to be a direction (its length overflows); the file is damaged");
    }
    if (!(norm >= 1e-4)) {
      fail("the light direction of \"" + e.filename +
           "\" has (almost) zero length; it cannot be a direction");
    }
    e.x = v[0] / norm;
    e.y = v[1] / norm;
    e.z = v[2] / norm;
    out.push_back(std::move(e));
  }
  if (static_cast<long long>(out.size()) != count) {
    throw Error(ErrorKind::Input, name, kReadStep,
                "line 1 announces " + std::to_string(count) + " lights but the file lists " +
                    std::to_string(out.size()) + "; the file is truncated or the count is wrong");
  }
  return out;
}

std::vector<LightEntry> readLp(const std::filesystem::path& path) {
  return parseLp(readFile(path, kReadStep), path.string());
}

std::string formatLp(const std::vector<LightEntry>& entries, const std::string& name) {
  auto fail = [&](const std::string& message) {
    throw Error(ErrorKind::Input, name, kWriteStep, message);
  };
  if (entries.empty() || static_cast<long long>(entries.size()) > kMaxLights) {
    fail("a .lp file holds 1 to " + std::to_string(kMaxLights) + " lights, not " +
         std::to_string(entries.size()));
  }
  std::string out = std::to_string(entries.size()) + "\n";
  for (const LightEntry& e : entries) {
    const std::string& f = e.filename;
    if (f.size() > kMaxImageNameBytes) {
      fail("an image name of " + std::to_string(f.size()) + " bytes cannot be written; a path has at most " +
           std::to_string(kMaxImageNameBytes) + " bytes");
    }
    if (f.empty() || f.find_first_of("\t\r\n") != std::string::npos || f.front() == ' ' ||
        f.back() == ' ' || f.find("  ") != std::string::npos) {
      fail("the image name \"" + f +
           "\" cannot be written to a .lp file (empty, or with tabs, line breaks, or leading, "
           "trailing or doubled spaces)");
    }
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.z)) {
      fail("the light direction of \"" + f + "\" is not a finite vector");
    }
    out += f + ' ' + formatNumber(e.x) + ' ' + formatNumber(e.y) + ' ' + formatNumber(e.z) + '\n';
  }
  return out;
}

void writeLp(const std::filesystem::path& path, const std::vector<LightEntry>& entries) {
  writeFileAtomically(path, formatLp(entries, path.string()));
}

namespace {
namespace fs = std::filesystem;

// The folder of an .lp file, absolute and weakly canonical (symbolic links of the folders
// resolved, so that ".." means what the system makes of it).
fs::path lpFolder(const fs::path& lpFile) {
  return fs::weakly_canonical(fs::absolute(lpFile).parent_path());
}

// "C:\x", "C:/x", "\\server\x", "/x": absolute on Windows or POSIX, whatever this system is.
bool isAbsoluteName(const std::string& name) {
  if (!name.empty() && (name[0] == '/' || name[0] == '\\')) return true;
  return name.size() >= 3 && std::isalpha(static_cast<unsigned char>(name[0])) && name[1] == ':' &&
         (name[2] == '/' || name[2] == '\\');
}
}  // namespace

std::string lpImageName(const fs::path& lpFile, const fs::path& image) {
  const fs::path target = fs::weakly_canonical(fs::absolute(image));
  const fs::path relative = target.lexically_relative(lpFolder(lpFile));
  return (relative.empty() ? target : relative).generic_string();
}

std::vector<fs::path> lpImageCandidates(const fs::path& lpFile, const std::string& name) {
  std::string generic = name;
  for (char& c : generic)
    if (c == '\\') c = '/';
  const std::string base = generic.substr(generic.find_last_of('/') + 1);
  const fs::path dir = lpFolder(lpFile);
  const fs::path parent = dir.parent_path();

  std::vector<fs::path> out;
  auto add = [&out](const fs::path& p) {
    const fs::path n = p.lexically_normal();
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  };
  if (isAbsoluteName(name)) {
    if (fs::path(generic).is_absolute()) add(generic);
  } else if (!generic.empty()) {
    add(dir / generic);
    add(parent / generic);
  }
  if (base.empty()) return out;
  add(dir / base);
  for (const fs::path& capture : {dir, parent})
    for (const char* folder : {"jpeg-exports", "original-captures", "raw-images"})
      add(capture / folder / base);
  return out;
}

namespace {
std::string baseOf(const std::string& name) {
  return name.substr(name.find_last_of("/\\") + 1);
}

std::string stemOf(const std::string& base) { return fs::path(base).stem().string(); }

std::string asciiLower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

bool sameButExtension(const std::string& a, const std::string& b) {
  const std::string sa = stemOf(a), sb = stemOf(b);
  return sa == sb || a == sb || sa == b;
}

// An image by its extension: a sidecar (IMG_0001.xmp) or a log beside the images must never
// be taken for one under "another extension".
bool isImageName(const fs::path& name) {
  const std::string ext = asciiLower(name.extension().string());
  return ext == ".jpg" || ext == ".jpeg" || ext == ".jpe" || ext == ".tif" || ext == ".tiff" ||
         ext == ".png" || image::isCameraRawExtension(name);
}

std::string describeLine(const std::vector<LightEntry>& lines, std::size_t l) {
  return "the line naming \"" + lines[l].filename + "\"";
}
}  // namespace

int lpNameRank(const std::string& lpName, const std::string& imageName) {
  const std::string a = baseOf(lpName), b = baseOf(imageName);
  if (a.empty() || b.empty()) return 0;
  if (a == b) return 1;
  const std::string la = asciiLower(a), lb = asciiLower(b);
  if (la == lb) return 2;
  if (sameButExtension(a, b)) return 3;
  if (sameButExtension(la, lb)) return 4;
  return 0;
}

LpMatch matchLpLines(const std::string& lpFile, const std::vector<LightEntry>& lines,
                     const std::vector<std::string>& images) {
  const char* const step = "match light positions";
  LpMatch m;
  m.lineOfImage.assign(images.size(), std::nullopt);
  m.imageOfLine.assign(lines.size(), std::nullopt);
  std::vector<int> rankOfLine(lines.size(), 0);
  std::vector<int> ranks(images.size());
  for (std::size_t l = 0; l < lines.size(); ++l) {
    for (std::size_t i = 0; i < images.size(); ++i) {
      ranks[i] = lpNameRank(lines[l].filename, images[i]);
      if (ranks[i] != 0 && (rankOfLine[l] == 0 || ranks[i] < rankOfLine[l])) {
        rankOfLine[l] = ranks[i];
        m.imageOfLine[l] = i;
      }
    }
    for (std::size_t i = 0; rankOfLine[l] != 0 && i < images.size(); ++i) {
      if (ranks[i] == rankOfLine[l] && i != *m.imageOfLine[l]) {
        throw Error(ErrorKind::Input, lpFile, step,
                    describeLine(lines, l) + " could mean \"" + images[*m.imageOfLine[l]] +
                        "\" or \"" + images[i] + "\", whose names differ only by letter case or "
                        "extension; rename one of the images or write the full name in the .lp");
      }
    }
  }
  for (std::size_t l = 0; l < lines.size(); ++l) {
    if (!m.imageOfLine[l]) continue;
    const std::size_t i = *m.imageOfLine[l];
    std::optional<std::size_t>& current = m.lineOfImage[i];
    if (current && rankOfLine[*current] == rankOfLine[l]) {
      throw Error(ErrorKind::Input, lpFile, step,
                  describeLine(lines, *current) + " and " + describeLine(lines, l) +
                      " both give the light of \"" + images[i] +
                      "\"; remove the line that does not belong to it");
    }
    if (!current || rankOfLine[l] < rankOfLine[*current]) current = l;
  }
  return m;
}

std::optional<fs::path> resolveLpImage(const fs::path& lpFile, const std::string& name) {
  const std::vector<fs::path> candidates = lpImageCandidates(lpFile, name);
  for (const fs::path& candidate : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  // Another letter case or extension, folder by folder in the same order.
  std::vector<fs::path> searched;
  for (const fs::path& candidate : candidates) {
    const fs::path folder = candidate.parent_path();
    if (std::find(searched.begin(), searched.end(), folder) != searched.end()) continue;
    searched.push_back(folder);
    std::error_code ec;
    std::vector<std::string> files;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      std::error_code fileEc;
      if (it->is_regular_file(fileEc) && isImageName(it->path().filename()) &&
          lpNameRank(name, it->path().filename().string()) != 0)
        files.push_back(it->path().filename().string());
    }
    if (files.empty()) continue;
    std::sort(files.begin(), files.end());  // the same message whatever the listing order
    const std::vector<LightEntry> line = {LightEntry{name, 0, 0, 1}};
    const LpMatch m = matchLpLines(lpFile.string(), line, files);
    if (m.imageOfLine[0]) return folder / files[*m.imageOfLine[0]];
  }
  return std::nullopt;
}

}  // namespace surrogate::formats
