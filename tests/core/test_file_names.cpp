// The names a package can hold (core/file_names.h): the one rule of the capture scan, pack and
// verify. Names are written out byte by byte: "\xC3\xA9" is é composed (NFC), "e\xCC\x81" is e
// followed by the combining acute accent (NFD, as macOS writes names).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/file_names.h"

using namespace surrogate;

namespace {

const std::string kComposed = "caf\xC3\xA9.txt";     // café, NFC
const std::string kDecomposed = "cafe\xCC\x81.txt";  // café, NFD

}  // namespace

TEST_CASE("case folding keys: letter case and Unicode normalisation collide", "[core][names]") {
  CHECK(caseFoldKey("data/IMG_0001.DNG") == caseFoldKey("data/img_0001.dng"));
  // precomposed U+00C4, decomposed A + U+0308 (as macOS writes it), lower-case U+00E4
  CHECK(caseFoldKey("data/\xC3\x84.dng") == caseFoldKey("data/A\xCC\x88.dng"));
  CHECK(caseFoldKey("data/\xC3\x84.dng") == caseFoldKey("data/\xC3\xA4.DNG"));
  CHECK(caseFoldKey(kComposed) == caseFoldKey(kDecomposed));
  CHECK(caseFoldKey("data/a.dng") != caseFoldKey("data/b.dng"));
  // Greek capital sigma folds to small sigma; the Kelvin sign K (U+212A) to k.
  CHECK(caseFoldKey("\xCE\xA3.txt") == caseFoldKey("\xCF\x83.txt"));
  CHECK(caseFoldKey("\xE2\x84\xAA.txt") == caseFoldKey("k.txt"));
  CHECK(caseFoldKey(std::string("\xFF\xFE bad utf-8")) == std::string("\xFF\xFE bad utf-8"));
}

TEST_CASE("the characters no package can hold", "[core][names]") {
  CHECK(unholdableCharacters("original-captures/IMG_0001.dng").empty());
  CHECK(unholdableCharacters("notes/a b 'c' \"d\" 100%.txt").empty());
  CHECK(unholdableCharacters(kComposed).empty());
  CHECK(unholdableCharacters("a\\b.txt") == "contains a backslash (a Windows path)");
  CHECK(unholdableCharacters("a\nb.txt") == "contains a control character");
  CHECK(unholdableCharacters(std::string("a\x01" "b.txt")) == "contains a control character");
  CHECK(unholdableCharacters(std::string("a\x7F" "b.txt")) == "contains a control character");
  CHECK(unholdableCharacters(std::string("IMG_\xE9t\xE9.dng")) == "is not valid UTF-8");
}

TEST_CASE("names are shown with control characters and stray bytes escaped", "[core][names]") {
  CHECK(shownName("a\nb") == "a\\x0Ab");
  CHECK(shownName(std::string("x\x01y")) == "x\\x01y");
  CHECK(shownName(std::string("IMG_\xE9t\xE9")) == "IMG_\\xE9t\\xE9");
  CHECK(shownName(kComposed) == kComposed);  // text stays text
  CHECK(shownName("a\\b") == "a\\b");
}

TEST_CASE("names a package can hold pass", "[core][names]") {
  const std::vector<std::string> names = {
      "original-captures/IMG_0001.dng", "jpeg-exports/IMG_0001.jpg", "notes/a b 'c' \"d\".txt",
      "notes/" + kComposed, "notes/na\xC3\xAFve 100%25 x%0A.txt", "notes/" + std::string(250, 'L') + ".txt",
      "notes/IMG_0001.txt", "other/img_0001.txt",  // the same name in two folders is no collision
      "assembly-files/carrier.xml"};
  const NameProblems p = findNameProblems(names, 5);
  CHECK(p.empty());
  CHECK(p.count() == 0);
}

TEST_CASE("names that differ only in case or normalisation are grouped where they part", "[core][names]") {
  const NameProblems p = findNameProblems(
      {"notes/README.txt", "notes/Readme.txt", "notes/readme.TXT", "notes/" + kComposed,
       "notes/" + kDecomposed, "Notes/x.txt", "Notes/y.txt", "original-captures/a.dng"},
      5);
  REQUIRE(p.collisions.size() == 3);
  // "Notes" and "notes" collide as folders; the files inside them are not listed again.
  CHECK(p.collisions[0] == std::vector<std::string>{"Notes", "notes"});
  CHECK(p.collisions[1] == std::vector<std::string>{"notes/README.txt", "notes/Readme.txt", "notes/readme.TXT"});
  CHECK(p.collisions[2].size() == 2);
  CHECK(p.unholdable.empty());  // the decomposed name is said with its collision, once
  CHECK(p.count() == 7);
  const std::string text = p.describe("of the capture", "then run again");
  CHECK(text.find("7 name(s) of the capture") == 0);
  CHECK(text.find("notes/README.txt  and  notes/Readme.txt  and  notes/readme.TXT") != std::string::npos);
  CHECK(text.find("(accents decomposed, as macOS writes them)") != std::string::npos);
  CHECK(text.find("rename them") != std::string::npos);
  CHECK(text.find("then run again") != std::string::npos);
}

TEST_CASE("a collision inside folders that collide is still found", "[core][names]") {
  const NameProblems p = findNameProblems({"A/x.txt", "a/x.txt", "a/X.txt"}, 5);
  REQUIRE(p.collisions.size() == 2);
  CHECK(p.collisions[0] == std::vector<std::string>{"A", "a"});
  CHECK(p.collisions[1] == std::vector<std::string>{"a/X.txt", "a/x.txt"});
}

TEST_CASE("backslashes, control characters, other encodings, NFD and long paths are listed", "[core][names]") {
  const std::string longName = "notes/" + std::string(1100, 'x');
  const NameProblems p = findNameProblems(
      {"notes/a\\b.txt", "notes/line\nbreak.txt", std::string("bad\x01" "dir/one.txt"),
       std::string("bad\x01" "dir/two.txt"), std::string("IMG_\xE9t\xE9.txt"), "notes/" + kDecomposed,
       longName},
      5);
  CHECK(p.collisions.empty());
  REQUIRE(p.unholdable.size() == 5);  // the folder with a control character once, not its files
  CHECK(p.unholdable[0].first == std::string("IMG_\xE9t\xE9.txt"));
  CHECK(p.unholdable[1].first == std::string("bad\x01" "dir"));
  CHECK(p.tooLong == std::vector<std::string>{longName});
  const std::string text = p.describe("of the capture", "then run again");
  CHECK(text.find("notes/a\\b.txt") != std::string::npos);
  CHECK(text.find("notes/line\\x0Abreak.txt") != std::string::npos);
  CHECK(text.find("bad\\x01dir") != std::string::npos);
  CHECK(text.find("IMG_\\xE9t\\xE9.txt") != std::string::npos);
  CHECK(text.find("decomposed (Unicode NFD") != std::string::npos);
  CHECK(text.find("longer than the 1024 bytes") != std::string::npos);
  // No raw control byte reaches a terminal.
  for (char c : text) CHECK((static_cast<unsigned char>(c) >= 0x20 || c == '\n'));
}

TEST_CASE("the path limit counts what the package puts in front", "[core][names]") {
  const std::string path = "notes/" + std::string(kMaxPackagePathBytes - 5 - 6, 'x');
  CHECK(findNameProblems({path}, 5).empty());                        // data/ + path: the limit
  CHECK(findNameProblems({path}, 5 + 4).tooLong.size() == 1);         // stem/data/ + path: over
}
