// The names a capture's package can hold: the one rule that `run` and `pack` apply before
// anything is processed or written, and that `verify` applies to every path of a package
// (archive/bag_text.h, archive/entry_checks.cpp), so that what pack writes verify accepts.
//
// A package is opened on Windows and macOS as well as Linux. There, two names that differ only
// in letter case ("IMG_0001.DNG", "img_0001.dng") or only in how an accent is encoded (Unicode
// NFC "é", as Linux and Windows write it, and NFD "e" + U+0301, as macOS writes it) are one
// name: unpacked, one file overwrites the other. A name in NFD alone does not come back from a
// .tar or .zip as it went in (libarchive composes it, archive/archive_source.cpp). A backslash is a folder separator on Windows;
// a control character (a line feed, U+0001) breaks the manifests' one path per line and every
// listing; bytes that are not UTF-8 cannot be recorded as text.
//
//   NameProblems p = findNameProblems({"notes/a.txt", "Notes/b.txt", "x\\y.txt"});
//   if (!p.empty()) throw Error(ErrorKind::Input, capture, "capture ingest",
//                               p.describe("the capture", "then run again"));
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace surrogate {

// The longest path a package entry may have, in bytes (the verifier's limit: a longer one is
// refused as hostile, archive/package_reader.h).
inline constexpr std::size_t kMaxPackagePathBytes = 1024;

// What in `name` no package can hold: "contains a control character", "contains a backslash
// (a Windows path)" or "is not valid UTF-8"; empty when nothing. Bytes only: no Unicode tables.
std::string unholdableCharacters(const std::string& name);

// The key two names share when they would be one name on a case-insensitive or normalising
// file system (Windows, macOS): Unicode NFC, then Unicode case folding (ICU). ASCII names fold
// as std::tolower does; text that is not UTF-8 folds its ASCII letters only.
std::string caseFoldKey(const std::string& name);

// `name` as a message shows it: control characters and bytes that are not UTF-8 as \xNN, so
// that no raw control byte reaches a terminal; everything else as it is.
std::string shownName(const std::string& name);

// What findNameProblems found. Names are relative paths, '/' separated, of files or folders.
struct NameProblems {
  // Names that would be one name on Windows or macOS, each group sorted; only where they part
  // (siblings in one folder): "Notes" and "notes" are reported, not every file inside them.
  std::vector<std::vector<std::string>> collisions;
  // A name holding what no package can (unholdableCharacters), or in NFD (not colliding: a
  // collision says it), with the reason; a folder is reported once, not with every file in it.
  std::vector<std::pair<std::string, std::string>> unholdable;
  // Paths longer than the package can hold (with the bytes the package adds in front).
  std::vector<std::string> tooLong;

  bool empty() const { return collisions.empty() && unholdable.empty() && tooLong.empty(); }
  std::size_t count() const;  // offending names, a collision counting each of its names
  // The message of the refusal: every name grouped by problem (escaped with shownName), then
  // what to do. `whose`: "of the capture", "the carrier records"; `then`: "then run again".
  std::string describe(const std::string& whose, const std::string& then) const;
};

// Judges every name in `paths` (files; their folders are judged too). `prefixBytes`: what the
// package puts before each path ("data/", or "STEM/data/" in a .tar or .zip), counted against
// kMaxPackagePathBytes.
NameProblems findNameProblems(const std::vector<std::string>& paths, std::size_t prefixBytes);

}  // namespace surrogate
