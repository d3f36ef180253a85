#include "core/file_names.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include <unicode/unorm2.h>
#include <unicode/ustring.h>

#include "core/text.h"

namespace surrogate {

namespace {

// The reason findNameProblems gives a name in NFD. libarchive, which reads a .tar or .zip for
// `verify` (archive/archive_source.cpp), gives every UTF-8 name back composed (NFC): a
// decomposed name would no longer be the name the manifests and the carrier record.
constexpr const char* kDecomposed = "has its accents decomposed (Unicode NFD)";

bool isControl(unsigned char c) { return c < 0x20 || c == 0x7F; }

bool isAscii(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

// `text` as UTF-16, or false when ICU cannot convert it (not UTF-8).
bool toUtf16(const std::string& text, std::u16string& out) {
  if (text.size() > (1u << 20)) return false;
  UErrorCode status = U_ZERO_ERROR;
  int32_t length = 0;
  u_strFromUTF8(nullptr, 0, &length, text.data(), static_cast<int32_t>(text.size()), &status);
  if (status != U_BUFFER_OVERFLOW_ERROR && U_FAILURE(status)) return false;
  status = U_ZERO_ERROR;
  out.assign(static_cast<std::size_t>(length), u'\0');
  u_strFromUTF8(reinterpret_cast<UChar*>(out.data()), length, nullptr, text.data(),
                static_cast<int32_t>(text.size()), &status);
  return U_SUCCESS(status);
}

// Whether a UTF-8 name is in NFC (as Linux and Windows write names); false for NFD (macOS).
bool isNfc(const std::string& name) {
  if (isAscii(name)) return true;
  UErrorCode status = U_ZERO_ERROR;
  const UNormalizer2* nfc = unorm2_getNFCInstance(&status);
  std::u16string utf16;
  if (U_FAILURE(status) || !toUtf16(name, utf16)) return true;
  const UBool normal = unorm2_isNormalized(nfc, reinterpret_cast<const UChar*>(utf16.data()),
                                           static_cast<int32_t>(utf16.size()), &status);
  return U_FAILURE(status) || normal;
}

std::string parentOf(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

std::string lastSegment(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

std::string unholdableCharacters(const std::string& name) {
  for (char c : name)
    if (isControl(static_cast<unsigned char>(c))) return "contains a control character";
  if (name.find('\\') != std::string::npos) return "contains a backslash (a Windows path)";
  if (!isValidUtf8(name)) return "is not valid UTF-8";
  return {};
}

std::string caseFoldKey(const std::string& path) {
  // NFC then Unicode case folding (ICU): "Ä.DNG" (precomposed), "A\u0308.dng" (decomposed,
  // as macOS writes it) and "ä.dng" share one key. ASCII is its own NFC and folds as tolower
  // (ICU's default folding maps only A-Z among ASCII): the common case skips ICU.
  if (isAscii(path)) return lowerCase(path);
  UErrorCode status = U_ZERO_ERROR;
  const UNormalizer2* nfc = unorm2_getNFCInstance(&status);
  std::u16string utf16;
  if (U_FAILURE(status) || !toUtf16(path, utf16)) return lowerCase(path);
  const int32_t length = static_cast<int32_t>(utf16.size());
  std::u16string normal(utf16.size() * 4 + 16, u'\0');
  const int32_t n = unorm2_normalize(nfc, reinterpret_cast<const UChar*>(utf16.data()), length,
                                     reinterpret_cast<UChar*>(normal.data()),
                                     static_cast<int32_t>(normal.size()), &status);
  if (U_FAILURE(status)) return lowerCase(path);
  std::u16string folded(static_cast<std::size_t>(n) * 3 + 16, u'\0');
  const int32_t f = u_strFoldCase(reinterpret_cast<UChar*>(folded.data()),
                                  static_cast<int32_t>(folded.size()),
                                  reinterpret_cast<const UChar*>(normal.data()), n,
                                  U_FOLD_CASE_DEFAULT, &status);
  if (U_FAILURE(status)) return lowerCase(path);
  std::string out(static_cast<std::size_t>(f) * 3 + 16, '\0');
  int32_t written = 0;
  u_strToUTF8(out.data(), static_cast<int32_t>(out.size()), &written,
              reinterpret_cast<const UChar*>(folded.data()), f, &status);
  if (U_FAILURE(status)) return lowerCase(path);
  out.resize(static_cast<std::size_t>(written));
  return out;
}

std::string shownName(const std::string& name) {
  std::string out;
  std::size_t i = 0;
  while (i < name.size()) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    // The length of a well-formed UTF-8 sequence starting here, or 0.
    std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (n > 1 && (i + n > name.size() || !isValidUtf8(name.substr(i, n)))) n = 0;
    if (n == 0 || (n == 1 && isControl(c))) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
      ++i;
    } else {
      out.append(name, i, n);
      i += n;
    }
  }
  return out;
}

std::size_t NameProblems::count() const {
  std::size_t n = unholdable.size() + tooLong.size();
  for (const auto& group : collisions) n += group.size();
  return n;
}

std::string NameProblems::describe(const std::string& whose, const std::string& then) const {
  std::string text = std::to_string(count()) + " name(s) " + whose +
                     " cannot be held by an archival package, which must unpack to the same files "
                     "on Windows, macOS and Linux (and `surrogate verify` refuses one that would not):";
  if (!collisions.empty()) {
    text += "\n  names that differ only in letter case or in how accents are encoded, which are "
            "one name on Windows and macOS (one file would overwrite the other):";
    for (const auto& group : collisions) {
      std::string line;
      for (const std::string& name : group) {
        line += (line.empty() ? "" : "  and  ") + shownName(name);
        if (!isNfc(name)) line += " (accents decomposed, as macOS writes them)";
      }
      text += "\n    " + line;
    }
  }
  auto listReason = [&](const std::string& reason, const std::string& heading) {
    bool first = true;
    for (const auto& [name, why] : unholdable) {
      if (why != reason) continue;
      if (first) text += "\n  " + heading;
      first = false;
      text += "\n    " + shownName(name);
    }
  };
  listReason("contains a backslash (a Windows path)",
             "names holding a backslash, which Windows reads as a folder separator:");
  listReason("contains a control character",
             "names holding a control character (shown as \\xNN), which no manifest line or "
             "listing can hold:");
  listReason(kDecomposed,
             "names whose accents are decomposed (Unicode NFD, as macOS wrote names on HFS+ disks), "
             "which a .tar or .zip gives back composed (NFC), so that the file would no longer have "
             "its recorded name (`convmv -r -f utf8 -t utf8 --nfc --notest FOLDER` composes every "
             "name in a folder):");
  listReason("is not valid UTF-8",
             "names that are not UTF-8 text (the bytes that are not are shown as \\xNN; probably "
             "written in another encoding, such as Latin-1):");
  if (!tooLong.empty()) {
    text += "\n  paths longer than the " + std::to_string(kMaxPackagePathBytes) +
            " bytes a package entry may have:";
    for (const std::string& name : tooLong) text += "\n    " + shownName(name);
  }
  text += "\nWhat to do: rename them (letters, digits, '-' and '_' are safe everywhere";
  if (!collisions.empty())
    text += "; of names that differ only in case or accents, rename all but one, or move them into "
            "separate folders";
  text += std::string(")") + (tooLong.empty() ? "" : " and shorten the paths that are too long") +
          ", " + then;
  return text;
}

NameProblems findNameProblems(const std::vector<std::string>& paths, std::size_t prefixBytes) {
  // Every name the package holds: each file and each folder above it, once.
  std::unordered_set<std::string> names;
  names.reserve(paths.size() * 2);
  for (const std::string& path : paths) {
    if (!names.insert(path).second) continue;
    for (std::size_t slash = path.rfind('/'); slash != std::string::npos && slash > 0;
         slash = path.rfind('/', slash - 1)) {
      if (!names.insert(path.substr(0, slash)).second) break;  // its folders are in already
    }
  }
  std::vector<std::string> sorted(names.begin(), names.end());
  std::sort(sorted.begin(), sorted.end());

  NameProblems problems;
  std::map<std::string, std::vector<std::string>> byKey;
  std::unordered_set<std::string> badFolders;  // reported: nothing under them is again
  for (const std::string& name : sorted) {
    byKey[caseFoldKey(name)].push_back(name);
    const std::string parent = parentOf(name);
    bool underBad = false;
    for (std::string p = parent; !p.empty(); p = parentOf(p))
      if (badFolders.count(p)) { underBad = true; break; }
    if (underBad) continue;
    std::string why = unholdableCharacters(lastSegment(name));
    if (why.empty() && !isNfc(lastSegment(name))) why = kDecomposed;
    if (!why.empty()) {
      problems.unholdable.emplace_back(name, why);
      badFolders.insert(name);
    }
  }
  for (auto& [key, group] : byKey) {
    if (group.size() < 2) continue;
    // Names in folders that differ collide already in those folders, reported there; names
    // in one folder are reported here.
    std::map<std::string, std::vector<std::string>> byParent;
    for (const std::string& name : group) byParent[parentOf(name)].push_back(name);
    for (auto& [parent, siblings] : byParent)
      if (siblings.size() > 1) problems.collisions.push_back(std::move(siblings));  // sorted
  }
  std::sort(problems.collisions.begin(), problems.collisions.end());
  // A decomposed name that collides with its composed twin is said once, with the collision.
  std::unordered_set<std::string> colliding;
  for (const auto& group : problems.collisions) colliding.insert(group.begin(), group.end());
  problems.unholdable.erase(
      std::remove_if(problems.unholdable.begin(), problems.unholdable.end(),
                     [&](const auto& u) { return u.second == kDecomposed && colliding.count(u.first); }),
      problems.unholdable.end());
  for (const std::string& path : paths)
    if (prefixBytes + path.size() > kMaxPackagePathBytes) problems.tooLong.push_back(path);
  std::sort(problems.tooLong.begin(), problems.tooLong.end());
  problems.tooLong.erase(std::unique(problems.tooLong.begin(), problems.tooLong.end()),
                         problems.tooLong.end());
  return problems;
}

}  // namespace surrogate
