// The text formats of a BagIt bag (RFC 8493), parsed from untrusted bytes with no trust in
// any path: bagit.txt, bag-info.txt and manifest lines, and the rules for paths inside a bag.
//
//   std::string why;
//   auto path = safeBagPath("data/a%25b.dng", &why);        // "data/a%b.dng" once decoded
//   auto lines = parseManifest(text, "manifest-sha256.txt"); // entries + problems, no throw
//
// These functions never throw on bad input: they return what was wrong, so the verifier can
// report each problem as a failed check. They are the fuzzing targets (fuzz/).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace surrogate::archive {

// A path inside a bag or archive, checked: relative, '/' separated, no "..", no "." or empty
// segments (a leading "./" is tolerated and removed), no backslash, drive letter, "~", control
// characters, or invalid UTF-8 (core/file_names.h: unholdableCharacters), at most `maxLength`
// bytes. Returns the normalised path, or
// nullopt with the reason in `why`.
std::optional<std::string> safeBagPath(const std::string& raw, std::string* why,
                                       std::size_t maxLength = 1024);

// Decodes the manifest escapes %0D, %0A and %25 (case-insensitive hex); any other '%' is kept
// as it is (RFC 8493 section 2.1.3).
std::string percentDecode(const std::string& text);

// The key two names share when they would collide on a case-insensitive or normalising file
// system (Windows, macOS) is core/file_names.h's caseFoldKey, shared with the capture scan.

// Splits text into lines at LF, CRLF or CR.
std::vector<std::string> splitLines(const std::string& text);

// bagit.txt: exactly two lines, "BagIt-Version: 1.0" (or a draft, 0.93 to 0.97) and
// "Tag-File-Character-Encoding: ENCODING", in UTF-8 without a byte-order mark. ENCODING is
// UTF-8 for every bag Surrogate writes; older bags name UTF-16, ISO-8859-1 and others, which
// are accepted when decodeTagText can read them (iconv knows the name).
struct Declaration {
  std::string version, encoding;
  std::vector<std::string> problems;  // empty when valid
};
Declaration parseDeclaration(const std::string& text);

// A tag file's bytes (bag-info.txt, manifests, tagmanifests, fetch.txt) decoded from the
// encoding bagit.txt names into UTF-8 (glibc's iconv; a UTF-16 byte-order mark is honoured and
// removed). UTF-8 text is returned as it is, so its own checks (valid UTF-8, no BOM) still
// apply. nullopt with the reason in `why` when the bytes are not valid in that encoding or
// the encoding is unknown.
std::optional<std::string> decodeTagText(const std::string& bytes, const std::string& encoding,
                                         std::string* why);

// Whether decodeTagText can read `encoding`.
bool tagEncodingSupported(const std::string& encoding);

// bag-info.txt: "Label: value" lines, continuation lines start with a space or tab.
struct BagInfo {
  std::vector<std::pair<std::string, std::string>> fields;  // in order, labels as written
  std::vector<std::string> problems;
  // What RFC 8493 allows or advises against without forbidding, and bagit-python accepts:
  // whitespace before the colon ("Label : value"), a reserved label that SHOULD NOT be
  // repeated (Bagging-Date, Payload-Oxum, ...) given twice. A warning in a bag another tool
  // made; a Surrogate package is held to what `pack` writes, where each is a problem.
  std::vector<std::string> departures;
  // Values of a label (case-insensitive).
  std::vector<std::string> values(const std::string& label) const;
};
BagInfo parseBagInfo(const std::string& text);

// Payload-Oxum "<octets>.<streams>".
std::optional<std::pair<std::uint64_t, std::uint64_t>> parseOxum(const std::string& value);

// One manifest: checksum + path per line; paths decoded and checked with safeBagPath.
struct ManifestEntry {
  std::string checksum;  // lower-case hex
  std::string path;      // decoded, normalised
  int line = 0;
};
struct Manifest {
  std::string algorithm;  // "sha256", from the file name
  std::vector<ManifestEntry> entries;
  // "line 3: ..." for malformed lines, a path listed twice with different checksums, bad paths
  std::vector<std::string> problems;
  // A path listed again with the same checksum (kept once in `entries`): BagIt 0.97 tools
  // wrote such manifests and bagit-python accepts them; RFC 8493 (1.0) does not.
  std::vector<std::string> repeats;
  // md5sum's binary-mode marker, "<checksum> *<path>", read as the path without the '*': a
  // manifest written by md5sum or sha256sum -b. Accepted with a warning in a bag another tool
  // made, a problem in a Surrogate package.
  std::vector<std::string> departures;
};
// `hexLength` is the expected digest length in hex characters (64 for sha256).
Manifest parseManifest(const std::string& text, const std::string& algorithm,
                       std::size_t hexLength);

// "manifest-sha256.txt" -> {"manifest", "sha256"}; "tagmanifest-sha512.txt" -> {"tagmanifest",
// "sha512"}; nullopt for other names.
std::optional<std::pair<std::string, std::string>> manifestName(const std::string& path);

// Hex digest length of a manifest's algorithm, by its BagIt name (sha256: 64, sha512: 128,
// sha224: 56, md5: 32, ...): any digest OpenSSL offers (core/digest.h, namedDigestSize); 0 if
// it offers none of that name.
std::size_t digestHexLength(const std::string& algorithm);

// md5, sha1 and the like: accepted in bags made by other tools (RFC 8493 section 2.4 keeps
// them for existing bags), with a warning, since they no longer resist a deliberate change.
bool isLegacyAlgorithm(const std::string& algorithm);

// fetch.txt (RFC 8493 section 2.2.3): "<url> <length or -> <path>" per line, separated by
// spaces or tabs; the path is the rest of the line (it may hold spaces) and is decoded and
// checked as in a manifest.
struct FetchEntry {
  std::string url;
  std::optional<std::uint64_t> length;  // nullopt for "-"
  std::string path;                     // decoded, normalised
  int line = 0;
};
struct Fetch {
  std::vector<FetchEntry> entries;
  std::vector<std::string> problems;  // "line 2: ..."
};
Fetch parseFetch(const std::string& text);

}  // namespace surrogate::archive
