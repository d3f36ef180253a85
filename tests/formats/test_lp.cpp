#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "formats/lp.h"
#include "fuzz_support.h"

using namespace surrogate;
using namespace surrogate::formats;
namespace fs = std::filesystem;

namespace {
std::string errorOf(const std::string& text) {
  try {
    parseLp(text, "lights.lp");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == "lights.lp");
    return e.message();
  }
  FAIL("no error for: " << text);
  return "";
}
}  // namespace

TEST_CASE("lp: reads names with spaces, CRLF line ends and normalises directions") {
  const auto l = parseLp("\xEF\xBB\xBF" "2\r\nC:\\caps\\my photo 1.jpg 0 0 2\r\n\r\nb.jpg\t3 0 4\r\n",
                         "x.lp");
  REQUIRE(l.size() == 2);
  CHECK(l[0].filename == "C:\\caps\\my photo 1.jpg");
  CHECK(l[0].z == 1.0);
  CHECK(l[1].filename == "b.jpg");
  CHECK(l[1].x == Approx(0.6));
  CHECK(l[1].z == Approx(0.8));
}

TEST_CASE("lp: errors name the file and the line") {
  CHECK_THAT(errorOf("0\n"), Catch::Contains("line 1") && Catch::Contains("between 1 and 1000"));
  CHECK_THAT(errorOf("1001\n"), Catch::Contains("between 1 and 1000"));
  CHECK_THAT(errorOf("two\na 0 0 1\n"), Catch::Contains("line 1"));
  CHECK_THAT(errorOf("2\na 0 0 1\n"), Catch::Contains("announces 2") && Catch::Contains("lists 1"));
  CHECK_THAT(errorOf("1\na 0 0 1\nb 0 0 1\n"), Catch::Contains("line 3"));
  CHECK_THAT(errorOf("2\na 0 0 1\nb 0 0.00001 0\n"), Catch::Contains("line 3") &&
                                                        Catch::Contains("zero length"));
  CHECK_THAT(errorOf("1\na 0 x 1\n"), Catch::Contains("line 2") && Catch::Contains("not a number"));
  CHECK_THAT(errorOf("1\na 0 1\n"), Catch::Contains("line 2"));
  CHECK_THAT(errorOf(""), Catch::Contains("empty"));
  CHECK_THAT(errorOf("1\na nan 0 1\n"), Catch::Contains("not a number"));
}

TEST_CASE("lp: write then read round trips, and the text is exactly the spec's layout") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-lp";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<LightEntry> in = {{"IMG 0001.JPG", 0.6, 0.0, 0.8}, {"b.jpg", -0.5, 0.5, std::sqrt(0.5)}};
  writeLp(dir / "a.lp", in);
  // Each component is the shortest text that reads back as the same double (core/text.h).
  CHECK(readFile(dir / "a.lp", "t") ==
        "2\nIMG 0001.JPG 0.6 0 0.8\nb.jpg -0.5 0.5 0.7071067811865476\n");
  const auto out = readLp(dir / "a.lp");
  REQUIRE(out.size() == 2);
  for (int i = 0; i < 2; ++i) {
    CHECK(out[i].filename == in[i].filename);
    // The reader normalises each direction, which may move a component by a rounding step.
    CHECK(out[i].x == Approx(in[i].x).epsilon(1e-15).margin(1e-15));
    CHECK(out[i].z == Approx(in[i].z).epsilon(1e-15).margin(1e-15));
  }
  writeLp(dir / "b.lp", out);  // a second generation is byte-identical
  CHECK(readFile(dir / "b.lp", "t") == readFile(dir / "a.lp", "t"));
  CHECK_THROWS_AS(writeLp(dir / "c.lp", {{"bad\tname", 0, 0, 1}}), Error);
  CHECK_THROWS_AS(writeLp(dir / "c.lp", {}), Error);
  CHECK_FALSE(fs::exists(dir / "c.lp"));
  fs::remove_all(dir);
}

TEST_CASE("lp: every prefix and thousands of mutations parse or throw Error") {
  const std::string valid = "3\na b.jpg 0.1 0.2 0.9\nc.jpg -0.3 0.1 0.8\nd.jpg 0 -0.5 0.5\n";
  auto parse = [](const std::uint8_t* d, std::size_t n) {
    parseLp(std::string(reinterpret_cast<const char*>(d), n), "f.lp");
  };
  for (std::size_t n = 0; n <= valid.size(); ++n) test::parsesOrThrowsError(parse, valid.substr(0, n));
  test::fuzz(parse, valid, 20, 3000, 7);
}

TEST_CASE("lp: image names resolve relative to the .lp, then to the folder above, then by base name") {
  const fs::path root = fs::weakly_canonical(fs::temp_directory_path()) / "surrogate-test-lp-resolve";
  fs::remove_all(root);
  const fs::path capture = root / "stela";
  for (const char* d : {"jpeg-exports", "original-captures", "assembly-files/jpeg-exports", "elsewhere"})
    fs::create_directories(capture / d);
  for (const char* f : {"jpeg-exports/000.jpg", "jpeg-exports/001.jpg", "jpeg-exports/004.jpg",
                        "original-captures/002.dng", "assembly-files/003.jpg",
                        "assembly-files/jpeg-exports/004.jpg", "elsewhere/005.jpg"})
    writeFileAtomically(capture / f, "image");
  // An RTIBuilder-style file from Windows: backslashes, CRLF, names relative to the capture.
  const fs::path lp = capture / "assembly-files" / "rti.lp";
  writeFileAtomically(lp, "7\r\n"
                          "jpeg-exports\\000.jpg 0 0 1\r\n"
                          "..\\jpeg-exports\\001.jpg 0.5 0 0.8\r\n"
                          "C:\\Users\\rti\\stela\\original-captures\\002.dng 0 0.5 0.8\r\n"
                          "D:\\old\\003.jpg -0.5 0 0.8\r\n"
                          "jpeg-exports\\004.jpg 0 -0.5 0.8\r\n" +
                              (capture / "elsewhere/005.jpg").string() + " 0.3 0.3 0.9\r\n"
                          "/no/such/folder/006.jpg 0 0 1\r\n");
  const auto entries = readLp(lp);
  REQUIRE(entries.size() == 7);
  CHECK(entries[0].filename == "jpeg-exports\\000.jpg");
  auto resolved = [&](std::size_t i) { return resolveLpImage(lp, entries[i].filename); };
  CHECK(resolved(0) == capture / "jpeg-exports/000.jpg");                 // the folder above
  CHECK(resolved(1) == capture / "jpeg-exports/001.jpg");                 // the .lp's folder
  CHECK(resolved(2) == capture / "original-captures/002.dng");            // base name, capture
  CHECK(resolved(3) == capture / "assembly-files/003.jpg");               // base name, beside
  CHECK(resolved(4) == capture / "assembly-files/jpeg-exports/004.jpg");  // .lp's folder first
  CHECK(resolved(5) == capture / "elsewhere/005.jpg");                    // absolute, exists
  CHECK_FALSE(resolved(6).has_value());                                   // nowhere

  // The order, spelled out; an absolute name is tried as it is, never under the folders.
  const fs::path dir = capture / "assembly-files";
  const auto candidates = lpImageCandidates(lp, "sub\\a.jpg");
  REQUIRE(candidates.size() == 9);
  CHECK(candidates[0] == dir / "sub/a.jpg");
  CHECK(candidates[1] == capture / "sub/a.jpg");
  CHECK(candidates[2] == dir / "a.jpg");
  CHECK(candidates[3] == dir / "jpeg-exports/a.jpg");
  CHECK(candidates[6] == capture / "jpeg-exports/a.jpg");
  CHECK(candidates[7] == capture / "original-captures/a.jpg");
  const auto absolute = lpImageCandidates(lp, "/data/a.jpg");
  REQUIRE_FALSE(absolute.empty());
  CHECK(absolute[0] == fs::path("/data/a.jpg"));
  CHECK(absolute[1] == dir / "a.jpg");
  CHECK(lpImageCandidates(lp, "C:\\caps\\a.jpg")[0] == dir / "a.jpg");

  // A relative spelling of the .lp's path resolves the same.
  const fs::path spelled = capture / "elsewhere" / ".." / "assembly-files" / "." / "rti.lp";
  CHECK(resolveLpImage(spelled, entries[0].filename) == capture / "jpeg-exports/000.jpg");
  fs::remove_all(root);
}

TEST_CASE("lp: names are written relative to the .lp's folder, with '/'") {
  const fs::path root = fs::weakly_canonical(fs::temp_directory_path()) / "surrogate-test-lp-name";
  const fs::path image = root / "stela/original-captures/IMG_0001.dng";
  CHECK(lpImageName(root / "stela.lp", image) == "stela/original-captures/IMG_0001.dng");
  CHECK(lpImageName(root / "lights/stela.lp", image) == "../stela/original-captures/IMG_0001.dng");
  CHECK(lpImageName(root / "a/b/stela.lp", image) == "../../stela/original-captures/IMG_0001.dng");
  CHECK(lpImageName(root / "stela/assembly-files/lights.lp", image) == "../original-captures/IMG_0001.dng");
  CHECK(lpImageName(root / "x/../a/./stela.lp", root / "stela/./jpeg-exports/../original-captures/IMG_0001.dng") ==
        "../stela/original-captures/IMG_0001.dng");
}

TEST_CASE("lp: an absurdly long image name is refused with its length, not carried around") {
  // A 20 MB "name" (a damaged file, or a binary file given as .lp) once went into messages and
  // path look-ups whole.
  const std::string longName(20 * 1000 * 1000, 'a');
  const std::string message = errorOf("1\n" + longName + ".jpg 0 0 1\n");
  CHECK_THAT(message, Catch::Contains("line 2"));
  CHECK_THAT(message, Catch::Contains("20000004 bytes"));
  CHECK_THAT(message, Catch::Contains(std::to_string(kMaxImageNameBytes)));
  CHECK(message.size() < 400);
  // The longest name allowed still reads, and writes back.
  const std::string longest(kMaxImageNameBytes, 'b');
  const auto l = parseLp("1\n" + longest + " 0 0 1\n", "x.lp");
  REQUIRE(l.size() == 1);
  CHECK(l[0].filename == longest);
  CHECK(parseLp(formatLp(l, "x.lp"), "x.lp") == l);
  CHECK_THROWS_AS(formatLp({{longest + "b", 0, 0, 1}}, "x.lp"), Error);
}

TEST_CASE("lp: files as other tools leave them: CRLF, blank lines, trailing spaces, tabs, Windows paths") {
  const auto l = parseLp("\r\n3 \r\n\r\n"
                         "C:\\capture\\jpeg-exports\\IMG_0001.JPG 0.5 0.5 0.707107 \r\n"
                         "  \t \r\n"
                         "jpeg-exports\\000.jpg\t-0.5\t0.5\t0.707107\t\r\n"
                         "C:\\My Captures\\IMG 0003.JPG 0 0 1   \r\n\r\n\r\n",
                         "rti.lp");
  REQUIRE(l.size() == 3);
  CHECK(l[0].filename == "C:\\capture\\jpeg-exports\\IMG_0001.JPG");
  CHECK(l[0].z == Approx(0.707107 / std::sqrt(0.25 + 0.25 + 0.707107 * 0.707107)));
  CHECK(l[1].filename == "jpeg-exports\\000.jpg");
  CHECK(l[2].filename == "C:\\My Captures\\IMG 0003.JPG");
  CHECK(l[2].z == 1);
}

TEST_CASE("lp: name ranks: exact, then letter case, then extension, then both") {
  CHECK(lpNameRank("C:\\caps\\IMG_0001.JPG", "IMG_0001.JPG") == 1);
  CHECK(lpNameRank("jpeg-exports\\IMG_0001.JPG", "img_0001.jpg") == 2);
  CHECK(lpNameRank("IMG_0001.JPG", "IMG_0001.CR2") == 3);
  CHECK(lpNameRank("IMG_0001.JPG", "IMG_0001") == 3);   // a shot named without extension
  CHECK(lpNameRank("IMG_0001", "IMG_0001.tif") == 3);
  CHECK(lpNameRank("img_0001.jpg", "IMG_0001.CR2") == 4);
  CHECK(lpNameRank("IMG_0001.JPG", "IMG_00010.JPG") == 0);
  CHECK(lpNameRank("IMG_0001.JPG", "IMG_0002.JPG") == 0);
  CHECK(lpNameRank("a/", "a") == 0);                    // no base name
  CHECK(lpNameRank("\xC3\x89T\xC3\x89.jpg", "\xC3\xA9t\xC3\xA9.jpg") == 0);  // ASCII case only
}

TEST_CASE("lp: lines pair with images unambiguously, or the .lp is refused") {
  const std::vector<LightEntry> lines = {{"C:\\caps\\IMG_0001.JPG", 0, 0, 1},
                                         {"jpeg-exports\\img_0002.jpg", 0.5, 0, 0.8},
                                         {"IMG_0003.tif", 0, 0.5, 0.8},
                                         {"IMG_0009.JPG", 0, 0.5, 0.8}};
  // Shots named by stem (a dome capture), files with other cases and extensions.
  const LpMatch m = matchLpLines("rti.lp", lines, {"IMG_0001", "IMG_0002", "IMG_0003", "IMG_0004"});
  CHECK(m.lineOfImage[0] == std::optional<std::size_t>(0));
  CHECK(m.lineOfImage[1] == std::optional<std::size_t>(1));
  CHECK(m.lineOfImage[2] == std::optional<std::size_t>(2));
  CHECK_FALSE(m.lineOfImage[3].has_value());
  CHECK_FALSE(m.imageOfLine[3].has_value());
  // The better rank wins: the exact name over another case.
  const LpMatch exact = matchLpLines("rti.lp", {{"IMG_1.JPG", 0, 0, 1}}, {"img_1.jpg", "IMG_1.JPG"});
  CHECK(exact.imageOfLine[0] == std::optional<std::size_t>(1));
  // One line, two images of equal rank: refused, naming both.
  try {
    matchLpLines("rti.lp", {{"Img_1.jpg", 0, 0, 1}}, {"img_1.jpg", "IMG_1.JPG"});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.file() == "rti.lp");
    CHECK_THAT(e.message(), Catch::Contains("\"img_1.jpg\"") && Catch::Contains("\"IMG_1.JPG\"") &&
                                Catch::Contains("Img_1.jpg"));
  }
  CHECK_THROWS_WITH(matchLpLines("rti.lp", {{"IMG_1.JPG", 0, 0, 1}}, {"IMG_1.CR2", "IMG_1.tif"}),
                    Catch::Contains("differ only by letter case or extension"));
  // Two lines for one shot: refused; of different rank: the better one is taken.
  CHECK_THROWS_WITH(matchLpLines("rti.lp", {{"IMG_1.JPG", 0, 0, 1}, {"IMG_1.CR2", 1, 0, 1}}, {"IMG_1"}),
                    Catch::Contains("both give the light of \"IMG_1\""));
  const LpMatch better = matchLpLines("rti.lp", {{"IMG_1.CR2", 1, 0, 1}, {"IMG_1.JPG", 0, 0, 1}}, {"IMG_1.JPG"});
  CHECK(better.lineOfImage[0] == std::optional<std::size_t>(1));
}

TEST_CASE("lp: images are found under another letter case or extension, never ambiguously") {
  const fs::path root = fs::weakly_canonical(fs::temp_directory_path()) / "surrogate-test-lp-lenient";
  fs::remove_all(root);
  const fs::path capture = root / "stela";
  for (const char* d : {"jpeg-exports", "original-captures", "assembly-files"}) fs::create_directories(capture / d);
  for (const char* f : {"jpeg-exports/img_0001.jpg", "original-captures/IMG_0002.CR2",
                        "jpeg-exports/IMG_0003.JPG", "jpeg-exports/IMG_0003.TIF",
                        "jpeg-exports/IMG_0004.JPG", "jpeg-exports/img_0004.jpg",
                        "jpeg-exports/IMG_0005.JPG", "original-captures/IMG_0002.xmp"})
    writeFileAtomically(capture / f, "image");
  const fs::path lp = capture / "assembly-files" / "rti.lp";
  writeFileAtomically(lp, "6\r\n"
                          "C:\\capture\\jpeg-exports\\IMG_0001.JPG 0 0 1\r\n"
                          "jpeg-exports\\IMG_0002.jpg 0.5 0 0.8\r\n"
                          "jpeg-exports\\IMG_0003.jpeg 0 0.5 0.8 \r\n"
                          "\r\n"
                          "jpeg-exports\\Img_0004.jpg -0.5 0 0.8\r\n"
                          "jpeg-exports\\IMG_0004.JPG -0.5 0 0.8\r\n"
                          "C:\\capture\\jpeg-exports\\IMG_0005.JPG 0 -0.5 0.8\r\n");
  const auto e = readLp(lp);
  REQUIRE(e.size() == 6);
  CHECK(resolveLpImage(lp, e[0].filename) == capture / "jpeg-exports/img_0001.jpg");    // case
  CHECK(resolveLpImage(lp, e[1].filename) == capture / "original-captures/IMG_0002.CR2");  // extension,
                                                                                         // not the .xmp
  CHECK_THROWS_WITH(resolveLpImage(lp, e[2].filename),                                 // .JPG or .TIF?
                    Catch::Contains("IMG_0003.JPG") && Catch::Contains("IMG_0003.TIF"));
  CHECK_THROWS_WITH(resolveLpImage(lp, e[3].filename),                                 // two cases
                    Catch::Contains("differ only by letter case"));
  CHECK(resolveLpImage(lp, e[4].filename) == capture / "jpeg-exports/IMG_0004.JPG");   // exact wins
  CHECK(resolveLpImage(lp, e[5].filename) == capture / "jpeg-exports/IMG_0005.JPG");   // Windows path
  CHECK_FALSE(resolveLpImage(lp, "IMG_0099.JPG").has_value());
  fs::remove_all(root);
}
