// The image names in .lp files: `surrogate lights CAPTURE -o X.lp` names the images relative to
// X.lp's own folder (as RTIBuilder and relight expect), whatever the working directory, and
// `surrogate fit --lp X.lp` finds them from any other working directory; the capture's own
// assembly-files/lights.lp names them relative to assembly-files/.
#include <catch2/catch.hpp>

#include <cctype>
#include <fstream>
#include <string>
#include <vector>

#include "e2e_support.h"
#include "formats/lp.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

// `surrogate ARGS` run in the folder `dir`.
e2e::CommandResult surrogateIn(const fs::path& dir, const std::string& args) {
  fs::create_directories(dir);
  return e2e::runShell("cd " + e2e::quote(dir) + " && " + std::string(SURROGATE_EXE) + " " + args);
}

// Every name in the .lp at `lp` starts with `prefix` followed by an image of the capture
// (IMG_*.dng from original-captures/), and the name resolves from the .lp's folder.
void requireNamesRelativeTo(const fs::path& lp, const std::string& prefix, std::size_t images) {
  const auto entries = formats::readLp(lp);
  REQUIRE(entries.size() == images);
  for (const formats::LightEntry& e : entries) {
    INFO(lp.string() << ": " << e.filename);
    CHECK(e.filename.rfind(prefix + "original-captures/IMG_", 0) == 0);
    CHECK(e.filename.find('\\') == std::string::npos);
    CHECK(fs::is_regular_file(lp.parent_path() / e.filename));
  }
}

}  // namespace

TEST_CASE("lights -o X.lp names the images relative to X.lp and fit --lp X.lp works from anywhere") {
  const fs::path base = e2e::freshDir("lp-paths");
  const fs::path capture = e2e::smallCapture(base);  // base/capture, 8 images
  const fs::path inCapture = capture / "assembly-files/lights.lp";

  struct Case {
    std::string what;
    fs::path cwd;            // where `lights` runs
    std::string captureArg;  // the capture as given on the command line
    std::string outArg;      // -o as given on the command line
    fs::path lp;             // the .lp that must be written
    std::string prefix;      // what every name must start with
    std::string fitLp;       // --lp as given to fit, from base/fit-here
  };
  const std::vector<Case> cases = {
      {"beside the capture, relative paths from another folder", base / "elsewhere", "../capture",
       "../capture.lp", base / "capture.lp", "capture/", "../capture.lp"},
      {"in a sibling folder, run from inside the capture", capture / "original-captures", "..",
       "../../lights/x.lp", base / "lights/x.lp", "../capture/", "../lights/x.lp"},
      {"in a nested folder, absolute capture path", base / "elsewhere", e2e::quote(capture),
       "../out/a/b/x.lp", base / "out/a/b/x.lp", "../../../capture/", e2e::quote(base / "out/a/b/x.lp")},
  };
  fs::create_directories(base / "lights");
  fs::create_directories(base / "out/a/b");
  for (const Case& c : cases) {
    INFO(c.what);
    const e2e::CommandResult lights =
        surrogateIn(c.cwd, "lights " + c.captureArg + " -o " + c.outArg + " --quiet");
    INFO(lights.output);
    REQUIRE(lights.exitCode == 0);
    REQUIRE(fs::is_regular_file(c.lp));
    requireNamesRelativeTo(c.lp, c.prefix, 8);
    // The capture's own lights.lp: relative to assembly-files/.
    requireNamesRelativeTo(inCapture, "../", 8);

    const fs::path fitHere = base / "fit-here";
    const e2e::CommandResult fit = surrogateIn(fitHere, "fit --lp " + c.fitLp + " -o out.ptm --quiet");
    INFO(fit.output);
    REQUIRE(fit.exitCode == 0);
    CHECK(fs::file_size(fitHere / "out.ptm") > 1000);
    fs::remove(fitHere / "out.ptm");
  }
}

TEST_CASE("the capture's lights.lp has the same bytes whatever the working directory") {
  const fs::path base = e2e::freshDir("lp-bytes");
  const fs::path capture = e2e::smallCapture(base);
  const fs::path inCapture = capture / "assembly-files/lights.lp";
  REQUIRE(surrogateIn(base, "lights capture -o one.lp --quiet").exitCode == 0);
  const std::string first = e2e::bytesOf(inCapture);
  REQUIRE(surrogateIn(capture / "jpeg-exports", "lights " + e2e::quote(capture) + " -o ../../two.lp --quiet").exitCode == 0);
  CHECK(e2e::bytesOf(inCapture) == first);
  requireNamesRelativeTo(inCapture, "../", 8);
  // Both written files hold the same lights, named relative to the same folder.
  CHECK(formats::readLp(base / "one.lp") == formats::readLp(base / "two.lp"));

  // fit on the capture's own file, by a relative path from inside the capture.
  const e2e::CommandResult fit =
      surrogateIn(capture / "original-captures", "fit --lp ../assembly-files/lights.lp -o " +
                                                     e2e::quote(base / "own.ptm") + " --quiet");
  INFO(fit.output);
  CHECK(fit.exitCode == 0);
  CHECK(fs::exists(base / "own.ptm"));
}

TEST_CASE("fit reads an RTIBuilder-style .lp with backslashes and CRLF naming jpeg-exports from the capture root") {
  const fs::path base = e2e::freshDir("lp-rtibuilder");
  const fs::path capture = e2e::smallCapture(base);
  REQUIRE(surrogateIn(base, "lights capture -o lights.lp --quiet").exitCode == 0);
  // RTIBuilder: CAPTURE/assembly-files/NAME.lp naming jpeg-exports\IMG_0001.jpg (relative to
  // the capture root), Windows line ends; one line by an absolute path from another machine.
  std::string text = "8\r\n";
  int n = 0;
  for (const formats::LightEntry& e : formats::readLp(base / "lights.lp")) {
    const std::string stem = fs::path(e.filename).stem().string();
    const std::string name = n++ == 3 ? "C:\\Users\\rti\\stela\\jpeg-exports\\" + stem + ".jpg"
                                      : "jpeg-exports\\" + stem + ".jpg";
    text += name + " " + std::to_string(e.x) + " " + std::to_string(e.y) + " " + std::to_string(e.z) + "\r\n";
  }
  std::ofstream(capture / "assembly-files/rtibuilder.lp", std::ios::binary) << text;
  const e2e::CommandResult fit =
      surrogateIn(base / "elsewhere", "fit --lp ../capture/assembly-files/rtibuilder.lp -o out.rti --quiet");
  INFO(fit.output);
  CHECK(fit.exitCode == 0);
  CHECK(fs::exists(base / "elsewhere/out.rti"));

  // A name found nowhere is an input error naming the image.
  std::ofstream(base / "missing.lp", std::ios::binary) << "1\r\nno-such-image.jpg 0 0 1\r\n";
  const e2e::CommandResult missing = surrogateIn(base, "fit --lp missing.lp -o out.ptm --quiet");
  CHECK(missing.exitCode == 1);
  CHECK_THAT(missing.output, Catch::Contains("no-such-image.jpg"));
}

TEST_CASE("fit and a dome run read .lp names that differ from the images by letter case or extension, never ambiguously") {
  const fs::path base = e2e::freshDir("lp-lenient");
  const fs::path capture = e2e::smallCapture(base);
  REQUIRE(surrogateIn(base, "lights capture -o lights.lp --quiet").exitCode == 0);
  const auto lights = formats::readLp(base / "lights.lp");
  REQUIRE(lights.size() == 8);
  // As other tools leave them: Windows paths, lower-case names with upper-case extensions, the
  // originals' extension (.CR2) or another one (.TIF) for the exports, CRLF, blank lines and
  // trailing spaces.
  auto lpText = [&](const std::vector<std::string>& names) {
    std::string text = "\r\n8 \r\n";
    for (std::size_t i = 0; i < lights.size(); ++i) {
      text += names[i] + " " + std::to_string(lights[i].x) + " " + std::to_string(lights[i].y) + " " +
              std::to_string(lights[i].z) + " \r\n" + (i == 4 ? "\r\n \r\n" : "");
    }
    return text;
  };
  std::vector<std::string> names;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const std::string stem = fs::path(lights[i].filename).stem().string();  // IMG_0001
    std::string lower = stem;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    names.push_back(i % 3 == 0 ? "C:\\capture\\jpeg-exports\\" + lower + ".JPG"
                    : i % 3 == 1 ? "jpeg-exports\\" + stem + ".CR2" : stem + ".TIF");
  }
  std::ofstream(capture / "assembly-files/lenient.lp", std::ios::binary) << lpText(names);
  const e2e::CommandResult fit =
      surrogateIn(base / "elsewhere", "fit --lp ../capture/assembly-files/lenient.lp -o out.ptm --quiet");
  INFO(fit.output);
  CHECK(fit.exitCode == 0);
  CHECK(fs::exists(base / "elsewhere/out.ptm"));

  // A dome run (on a fresh copy of the capture) pairs the same names with the shots.
  const fs::path domeCapture = e2e::smallCapture(e2e::freshDir("lp-lenient-dome"));
  std::ofstream(domeCapture / "dome.lp", std::ios::binary) << lpText(names);
  const e2e::CommandResult dome = e2e::surrogate("run " + e2e::quote(domeCapture) + " --lp dome.lp --quiet");
  INFO(dome.output);
  CHECK(dome.exitCode == 0);

  // Two lines that name one shot equally well: refused, naming both.
  std::vector<std::string> twice = names;
  twice[1] = fs::path(lights[0].filename).stem().string() + ".DNG";  // IMG_0001 again
  twice[0] = fs::path(lights[0].filename).stem().string() + ".JPG";
  std::ofstream(domeCapture / "twice.lp", std::ios::binary) << lpText(twice);
  const e2e::CommandResult refused = e2e::surrogate("run " + e2e::quote(domeCapture) + " --lp twice.lp --quiet");
  CHECK(refused.exitCode == 1);
  CHECK_THAT(refused.output, Catch::Contains("both give the light of"));

  // An export under two extensions: the line naming neither is refused, naming both.
  const fs::path jpg = capture / "jpeg-exports" / (fs::path(lights[1].filename).stem().string() + ".jpg");
  REQUIRE(fs::exists(jpg));
  fs::copy_file(jpg, fs::path(jpg).replace_extension(".jpeg"));
  const e2e::CommandResult ambiguous =
      surrogateIn(base / "elsewhere", "fit --lp ../capture/assembly-files/lenient.lp -o again.ptm --quiet");
  CHECK(ambiguous.exitCode == 1);
  CHECK_THAT(ambiguous.output, Catch::Contains(".jpeg\"") && Catch::Contains(".jpg\""));
  CHECK_FALSE(fs::exists(base / "elsewhere/again.ptm"));
}
