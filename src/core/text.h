// Small text helpers every library needs; one copy of each.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace surrogate {

// `s` with each byte passed through std::tolower: for file extensions, hash names and other
// ASCII keywords compared without regard to case.
std::string lowerCase(std::string s);

// The one text form of a number that is recorded (carrier attributes and parameters, .lp light
// files, --json output): the shortest decimal that reads back (strtod, from_chars, xs:double) as
// exactly `value`, from std::to_chars, so 0.8 is "0.8", never "0.80000000000000004". Plain
// decimal notation for 1e-6 <= |value| < 1e15 ("0.000125", "250", "123456789012345"), else
// scientific in to_chars' form ("1e-07", "1.5e+21"); -0.0 stays "-0" (it reads back as -0.0).
// Throws Error(Internal) for NaN and infinities: no record holds them (a parameter or result
// that is not finite is refused where it is computed or read), so one here is a bug. The JSON
// writer (core/json.cpp) writes them as null before they reach this function.
std::string formatNumber(double value);

// `v` with exactly `digits` decimals ("%.*f"), for log lines and messages.
std::string fixedDecimals(double v, int digits);

// True when `s` is well-formed UTF-8: no stray continuation bytes, no overlong forms, no
// surrogates (U+D800..U+DFFF), nothing above U+10FFFF.
bool isValidUtf8(const std::string& s);

// Text that came from a file (an EXIF make, an XMP packet, a line of an .lp, a name) as a record
// and a terminal can hold it: valid UTF-8 with no control character. Each byte outside valid
// UTF-8, and each byte of a control character (C0, DEL, C1) or of a code point XML cannot hold
// (U+FFFE, U+FFFF), becomes the four characters \xHH; everything else is kept. With
// `keepLineBreaks`, tab, line feed and carriage return are kept (a packet's lines). Text that
// is already clean comes back unchanged; the raw bytes are for hexBytes to keep.
std::string escapedText(const std::string& bytes, bool keepLineBreaks = false);
// Text as HTML element content or a quoted attribute value: & < > " ' as character
// references, so that no title or file name can open a tag or end an attribute. Other bytes
// (UTF-8 included) pass through. Used by every page Surrogate writes (report, web copy).
std::string escapeHtml(const std::string& text);
// `text` as one word for a POSIX shell, for a command line the user may copy: as it is when it
// holds only characters no shell treats specially, else in single quotes (a quote inside as
// '\''). A word starting with '-' stays an option's word: a path that must not read as an
// option is the caller's to prefix with "./".
std::string shellWord(const std::string& text);
// Whether escapedText would change `bytes`.
bool needsEscaping(const std::string& bytes, bool keepLineBreaks = false);
// The bytes as lowercase hexadecimal, two digits each ("43616e" for "Can").
std::string hexBytes(const std::string& bytes);

// The first `most` items joined by ", ", then " and N more" for the rest: "IMG_0003, IMG_0007
// and 2 more". The way messages list names the reader need not act on one by one.
std::string listedWithMore(const std::vector<std::string>& items, std::size_t most);

// Every item joined by `separator`: how a refusal names the frames it refuses, all of them, since
// the user acts on each ("8 frames and 2 more" left two to guess). The run's note in the carrier
// keeps the whole message too (surrogate info CAPTURE shows it).
std::string listedInFull(const std::vector<std::string>& items, const std::string& separator = ", ");

// The number of single-byte insertions, deletions, substitutions and swaps of two neighbours
// that turn `a` into `b` (the optimal string alignment distance, a restricted
// Damerau-Levenshtein): "verfy" to "verify" is 1, "titel" to "title" is 1 (a swap).
std::size_t editDistance(const std::string& a, const std::string& b);

// The candidate a mistyped `name` most likely meant, for "did you mean ...?": the nearest by
// editDistance when it is at most 2 and at most half of `name`'s length (so that "x" does not
// suggest "o", while "rn" suggests "run"), else one `name` is a prefix of (when only one is); none when nothing is close
// or two are equally near. Candidates are compared as given (case matters).
std::optional<std::string> nearestName(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace surrogate
