// What `surrogate info`, `help` and `run` say to a user (issue 16): camera metadata of real
// files as a photographer reads it, a carrier's decisions with who, when, why and what, a
// capture of exports alone, every command's help, and a folder that is not a capture refused
// before anything is written in it.
//
// The expected camera values are what `exiv2 -pa` / `exiv2 -pv` (0.27.6) print for each file
// of tests/data (quoted beside each check), written the way photographers write them.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "e2e_support.h"

namespace fs = std::filesystem;
using Catch::Contains;

namespace {

fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }

e2e::CommandResult info(const fs::path& file, const std::string& options = "") {
  return e2e::surrogate("info " + e2e::quote(file) + options);
}

// Every entry (files and folders) under `root`, by relative path: what `run` left behind.
std::vector<std::string> listing(const fs::path& root) {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    out.push_back(fs::relative(entry.path(), root).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("info on the Canon EOS D30 raw shows the camera once and the recorded lens range and f/5.6 and an ISO date") {
  const e2e::CommandResult r = info(fixture("raw-real/canon-eos-d30.crw"));
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("  camera:      Canon EOS D30, serial 123502474\n"));
  CHECK_THAT(r.output, !Contains("Canon Canon"));
  // Exif.CanonCs.Lens 16.0 - 35.0 mm; Exif.CanonCs.LensType's reading is a 70-200 mm lens.
  CHECK_THAT(r.output, Contains("  lens:        16-35 mm (recorded focal range; the lens code reads as "
                                "Canon EF 70-200mm f/2.8L IS II USM, which does not match it)\n"));
  CHECK_THAT(r.output, Contains("  exposure:    31 mm, f/5.6, 1 s, ISO 100\n"));  // F5.7 = 2828427/500000
  CHECK_THAT(r.output, Contains("  taken:       2018-01-01T13:03:32\n"));
  CHECK_THAT(r.output, !Contains("5.65685"));

  const e2e::CommandResult j = info(fixture("raw-real/canon-eos-d30.crw"), " --json");
  INFO(j.output);
  REQUIRE(j.exitCode == 0);
  CHECK_THAT(j.output, Contains("\"decodable\":true"));
  CHECK_THAT(j.output, Contains("\"focalLengthMm\":31,"));
  CHECK_THAT(j.output, Contains("\"fNumber\":5.656854,"));  // 2828427/500000, exactly
  CHECK_THAT(j.output, Contains("\"lensFocalRangeMm\":[16,35]"));
  CHECK_THAT(j.output, Contains("\"iso\":100,"));
  CHECK_THAT(j.output, Contains("\"dateTimeOriginal\":\"2018-01-01T13:03:32\""));
  CHECK_THAT(j.output, Contains("\"aperture\":\"f/5.6\""));
  CHECK_THAT(j.output, Contains("\"camera\":\"Canon EOS D30\""));
}

TEST_CASE("info on a Sony JPEG omits the serial and lens it does not record") {
  const e2e::CommandResult r = info(fixture("raw-metadata/DSC_3079.jpg"));
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("  camera:      Sony D5803\n"));
  CHECK_THAT(r.output, !Contains("serial") && !Contains("lens:"));
  CHECK_THAT(r.output, Contains("  exposure:    4.6 mm, f/2, 1/32 s, ISO 64\n"));
  CHECK_THAT(r.output, Contains("  XMP:         3179 bytes\n"));
  const e2e::CommandResult j = info(fixture("raw-metadata/DSC_3079.jpg"), " --json");
  CHECK_THAT(j.output, !Contains("\"serial\"") && !Contains("\"lens\""));
  CHECK_THAT(j.output, Contains("\"focalLengthMm\":4.6,") && Contains("\"fNumber\":2,"));
}

TEST_CASE("files Exiv2 reads but LibRaw cannot decode have their metadata shown and the refusal stated apart") {
  const e2e::CommandResult dng = info(fixture("raw-metadata/IMG_1361.dng"));
  INFO(dng.output);
  CHECK(dng.exitCode == 0);
  CHECK_THAT(dng.output, Contains("  camera:      Apple iPhone 12 Pro\n"));
  CHECK_THAT(dng.output, Contains("  exposure:    4.2 mm, f/1.6, 1/5556 s, ISO 32\n"));
  CHECK_THAT(dng.output, Contains("  taken:       2020-12-29T14:24:45-05:00\n"));  // OffsetTimeOriginal -05:00
  CHECK_THAT(dng.output, Contains("\n  decoding:    refused: ") && Contains("truncated"));

  const e2e::CommandResult cr3 = info(fixture("raw-metadata/Canon-R6-pruned.CR3"));
  INFO(cr3.output);
  CHECK(cr3.exitCode == 0);
  CHECK_THAT(cr3.output, Contains("  camera:      Canon EOS R6, serial 093022004357\n"));
  CHECK_THAT(cr3.output, Contains("  lens:        RF70-200mm F2.8 L IS USM\n"));
  CHECK_THAT(cr3.output, Contains("  exposure:    200 mm, f/25, 1/4 s, ISO 100\n"));
  CHECK_THAT(cr3.output, Contains("  taken:       2021-05-12T12:21:21+02:00\n"));
  CHECK_THAT(cr3.output, Contains("\n  decoding:    refused: ") && Contains("CR3"));

  const e2e::CommandResult j = info(fixture("raw-metadata/Canon-R6-pruned.CR3"), " --json");
  INFO(j.output);
  CHECK(j.exitCode == 0);
  CHECK_THAT(j.output, Contains("\"decodable\":false,\"decodeProblem\":\""));
  CHECK_THAT(j.output, Contains("\"focalLengthMm\":200,") && Contains("\"fNumber\":25,"));
  CHECK_THAT(j.output, Contains("\"offsetTimeOriginal\":\"+02:00\""));

  // Neither pixels nor metadata: still bad input.
  const fs::path dir = e2e::freshDir("info-not-image");
  std::ofstream(dir / "notes.jpg") << "not a picture";
  CHECK(info(dir / "notes.jpg").exitCode == 1);
}

TEST_CASE("info describes an XMP sidecar as a sidecar") {
  const e2e::CommandResult r = info(fixture("raw-metadata/StaffPhotographer-Example.xmp"));
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains(": XMP sidecar ("));
  CHECK_THAT(r.output, Contains("  written by:  Adobe Photoshop CS Windows\n"));  // Xmp.xmp.CreatorTool
  CHECK_THAT(r.output, Contains("  creator:     John Doe\n"));
  CHECK_THAT(r.output, !Contains("unsupported") && !Contains("not an image"));
  const e2e::CommandResult j = info(fixture("raw-metadata/StaffPhotographer-Example.xmp"), " --json");
  CHECK_THAT(j.output, Contains("{\"kind\":\"xmp-sidecar\",\"bytes\":10715,\"software\":\"Adobe Photoshop CS Windows\""));
  // Its PRONOM format, from its bytes (mappings/pronom.md).
  CHECK_THAT(r.output, Contains("  PRONOM:      Extensible Metadata Platform Packet (fmt/570)\n"));
  CHECK_THAT(j.output, Contains("\"puid\":\"fmt/570\",\"pronom\":\"Extensible Metadata Platform Packet (fmt/570)\",\"version\":{"));
}

TEST_CASE("info names an image's and a model's PRONOM format from their bytes") {
  const e2e::CommandResult dng = info(fixture("raw-metadata/IMG_1361.dng"));
  INFO(dng.output);
  CHECK_THAT(dng.output, Contains("\n  PRONOM:      Digital Negative Format (DNG) 1.4 (fmt/730)\n"));
  const e2e::CommandResult jpeg = info(fixture("raw-metadata/DSC_3079.jpg"), " --json");
  INFO(jpeg.output);
  CHECK_THAT(jpeg.output, Contains("{\"kind\":\"image\",\"puid\":\"fmt/43\",\"pronom\":\"JPEG File Interchange Format 1.01 (fmt/43)\","));
  const fs::path capture = e2e::processedCapture(e2e::freshDir("info-pronom"));
  const e2e::CommandResult ptm = info(capture / "finished-files/ptm-lrgb.ptm");
  INFO(ptm.output);
  CHECK_THAT(ptm.output, Contains("\n  PRONOM:    Polynomial Texture Map (fmt/519)\n"));
  const e2e::CommandResult rti = info(capture / "finished-files/hsh2.rti", " --json");
  INFO(rti.output);
  CHECK_THAT(rti.output, Contains("\"puid\":\"\",\"pronom\":\"no PRONOM signature matches\""));
}

TEST_CASE("info on a carrier lists decisions with what and who and when and why and the exclusions and creators and metadata") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("info-carrier"));
  const std::string c = e2e::quote(capture);
  REQUIRE(e2e::surrogate("run " + c + " --quiet --title \"Stela 12\" --creator \"Ana Silva:photographer\""
                         " --meta \"site=Museum store 3\" --rights \"Museum use only\""
                         " --license https://creativecommons.org/licenses/by/4.0/"
                         " --exclude IMG_0003 --reason \"the flash did not fire\" --operator \"Ana Silva\"")
              .exitCode == 0);
  REQUIRE(e2e::surrogate("run " + c + " --quiet --sphere 339,57,45 --reason \"cut by the frame edge\""
                         " --operator \"Ben Okafor\"").exitCode == 0);

  const e2e::CommandResult r = info(capture);
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("  title:   Stela 12\n"));
  CHECK_THAT(r.output, Contains("  photographer: Ana Silva\n"));
  CHECK_THAT(r.output, Contains("  rights:  Museum use only\n"));
  CHECK_THAT(r.output, Contains("  licence: https://creativecommons.org/licenses/by/4.0/\n"));
  CHECK_THAT(r.output, Contains("  metadata: site = Museum store 3\n"));
  CHECK_THAT(r.output, Contains("    exclude-image IMG_0003 (s1 CaptureIngest): IMG_0003 is left out of every step\n"
                                "      by Ana Silva, "));
  CHECK_THAT(r.output, Contains(": the flash did not fire\n"));
  CHECK_THAT(r.output, Contains("    manual-sphere 0 (s3 SphereDetection): circle of sphere 1 given by hand "
                                "(x,y,r 339,57,45)\n      by Ben Okafor, "));
  CHECK_THAT(r.output, Contains("  excluded images: IMG_0003\n"));
  CHECK_THAT(r.output, Contains("    s1 CaptureIngest v") && Contains(": completed in "));
  CHECK_THAT(r.output, !Contains("intervention(s)"));

  const e2e::CommandResult j = info(capture, " --json");
  INFO(j.output);
  REQUIRE(j.exitCode == 0);
  CHECK_THAT(j.output, Contains("\"creators\":[{\"name\":\"Ana Silva\",\"role\":\"photographer\"}]"));
  CHECK_THAT(j.output, Contains("\"rights\":\"Museum use only\",\"license\":\"https://creativecommons.org/licenses/by/4.0/\""));
  CHECK_THAT(j.output, Contains("\"metadata\":[{\"name\":\"site\",\"value\":\"Museum store 3\"}]"));
  CHECK_THAT(j.output, Contains("\"exclusions\":[{\"image\":\"IMG_0003\",\"who\":\"Ana Silva\""));
  CHECK_THAT(j.output, Contains("\"kind\":\"manual-sphere\",\"target\":\"0\",\"value\":\"339,57,45\""));
  CHECK_THAT(j.output, Contains("\"who\":\"Ben Okafor\""));

  // An older carrier wrote numbers with 17 digits: shown to 0.1 all the same.
  std::string xml = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  const std::string recorded = "value=\"339,57,45\"";
  REQUIRE(xml.find(recorded) != std::string::npos);
  xml.replace(xml.find(recorded), recorded.size(), "value=\"339.00000000000006,56.999999999999993,45\"");
  const fs::path old = e2e::freshDir("info-carrier-old") / "carrier.xml";
  std::ofstream(old, std::ios::binary) << xml;
  const e2e::CommandResult o = info(old);
  INFO(o.output);
  REQUIRE(o.exitCode == 0);
  CHECK_THAT(o.output, Contains("given by hand (x,y,r 339,57,45)\n"));
  CHECK_THAT(o.output, !Contains("339.00000000000006"));
  CHECK_THAT(o.output, Contains("  processing choices (a run without options repeats them):\n    image source: auto\n"));

  // A carrier whose steps this version cannot read (here a fit of an unknown basis) is still
  // described, its choices left out with the reason.
  const std::string basis = "<param name=\"basis\" value=\"hsh2\"/>";
  REQUIRE(xml.find(basis) != std::string::npos);
  xml.replace(xml.find(basis), basis.size(), "<param name=\"basis\" value=\"bogus\"/>");
  const fs::path odd = e2e::freshDir("info-carrier-odd") / "carrier.xml";
  std::ofstream(odd, std::ios::binary) << xml;
  const e2e::CommandResult d = info(odd);
  INFO(d.output);
  CHECK(d.exitCode == 0);
  CHECK_THAT(d.output, Contains("processing choices: not readable by this version of Surrogate (") && Contains("bogus"));
  CHECK_THAT(d.output, Contains("  runs:\n"));
  const e2e::CommandResult dj = info(odd, " --json");
  CHECK(dj.exitCode == 0);
  CHECK_THAT(dj.output, Contains("\"choices\":null"));
}

TEST_CASE("info on a capture of exports alone calls the exports the originals the pipeline reads") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("info-exports"));
  fs::remove_all(capture / "original-captures");
  const e2e::CommandResult r = info(capture);
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("  shots:     8 (exports in jpeg-exports/, no raw originals: the exports are "
                                "the originals the pipeline reads)\n"));
  CHECK_THAT(r.output, !Contains("0 originals") && !Contains(" in -"));
  const e2e::CommandResult j = info(capture, " --json");
  CHECK_THAT(j.output, Contains("\"originals\":0,\"exports\":8,\"originalsFolder\":\"jpeg-exports/\""));
}

TEST_CASE("info on an .lp shows elevations to 0.1 degree") {
  const fs::path dir = e2e::freshDir("info-lp");
  // Directions of elevation asin(0.5) = 30 degrees and asin(0.9) = 64.158... degrees.
  std::ofstream(dir / "two.lp") << "2\nIMG_0001.jpg 0.866025403784 0 0.5\nIMG_0002.jpg 0.435889894354 0 0.9\n";
  const e2e::CommandResult r = info(dir / "two.lp");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("elevation: 30.0 to 64.2 degrees\n"));
}

TEST_CASE("info on RTIBuilder's real log says what its processing used and found, in text and JSON") {
  // tests/data/rtibuilder/Fisch.xml: RTIBuilder 2.0.2's log of CHI's fish fossil sample (source
  // in that folder's README.md); the values below were read from the file.
  const e2e::CommandResult r = info(fixture("rtibuilder/Fisch.xml"));
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("Fisch.xml: RTIBuilder log (RTIBuilder 2.0.2)\n"));
  CHECK_THAT(r.output, Contains("  project:     Fisch, by kacebe on c-gv-bruhn (Windows 10 x86)\n"));
  CHECK_THAT(r.output, Contains("  created:     2017/4/5 9:49:21\n"));
  CHECK_THAT(r.output, Contains("  images:      36 listed, 36 used, 0 excluded, 2000x1334\n"));
  CHECK_THAT(r.output, Contains("  sphere 2:    centre 168, 208, radius 85; found on 10 images"));
  CHECK_THAT(r.output, Contains("              36 highlights (search area x:83.0 y:123.0 to x:253.0 y:293.0, threshold 250), "
                                "36 light directions\n"));
  CHECK_THAT(r.output, Contains("  fitter:      hshfitter, HSH order 2 (hsh2), 4 threads\n"));
  CHECK_THAT(r.output, Contains("  model:       C:\\tmp\\rti\\fish_fossil-data-set_2000\\finished-files\\Fisch_2000.rti\n"));
  CHECK_THAT(r.output, Contains("  fit:         Fitter return ok!HSH was generated successfully\n"));
  CHECK_THAT(r.output, Contains("  messages:    13 (3 info, 1 information, 9 warning)\n"));
  CHECK_THAT(r.output, !Contains("carrier.xsd"));

  const e2e::CommandResult j = info(fixture("rtibuilder/Fisch.xml"), " --json");
  INFO(j.output);
  REQUIRE(j.exitCode == 0);
  CHECK_THAT(j.output, Contains("\"kind\":\"rtibuilder-log\""));
  CHECK_THAT(j.output, Contains("\"version\":\"2.0.2\""));
  CHECK_THAT(j.output, Contains("\"imageWidth\":2000,\"imageHeight\":1334"));
  CHECK_THAT(j.output, Contains("\"excludedImages\":[]"));
  CHECK_THAT(j.output, Contains("\"order\":2,\"threads\":4"));
  CHECK_THAT(j.output, Contains("{\"image\":\"fish_fossil_01.jpg\",\"x\":-0.8247194,\"y\":0.47309062,\"z\":0.30987605}"));
  CHECK_THAT(j.output, Contains("\"succeeded\":true"));
}

TEST_CASE("info on other XML still reads it as a carrier, and on a log in another namespace says what a log is") {
  const fs::path dir = e2e::freshDir("info-xml");
  std::ofstream(dir / "notes.xml") << "<?xml version=\"1.0\"?>\n<notes/>\n";
  const e2e::CommandResult notes = info(dir / "notes.xml");
  INFO(notes.output);
  CHECK(notes.exitCode == 1);
  CHECK_THAT(notes.output, Contains("does not conform to carrier.xsd"));
  std::ofstream(dir / "other.xml") << "<XMLCarrier xmlns=\"urn:example\"/>\n";
  const e2e::CommandResult other = info(dir / "other.xml");
  INFO(other.output);
  CHECK(other.exitCode == 1);
  CHECK_THAT(other.output, Contains("other.xml: is not an RTIBuilder log"));
  CHECK_THAT(other.output, Contains("its root element is <XMLCarrier> in urn:example"));
}

TEST_CASE("help COMMAND and COMMAND --help print the help of that command for every command") {
  for (const char* command :
       {"run", "pack", "lights", "fit", "render", "publish", "info", "report", "review", "verify", "audit"}) {
    const e2e::CommandResult help = e2e::surrogate(std::string("help ") + command);
    const e2e::CommandResult option = e2e::surrogate(std::string(command) + " --help");
    INFO(command << "\n" << help.output);
    CHECK(help.exitCode == 0);
    CHECK_THAT(help.output, Contains(std::string("usage: surrogate ") + command + " "));
    CHECK_THAT(help.output, Contains("\nexit codes:\n  0  "));
    CHECK(help.output == option.output);
  }
  const e2e::CommandResult helpHelp = e2e::surrogate("help help");
  CHECK(helpHelp.exitCode == 0);
  CHECK(helpHelp.output == e2e::surrogate("--help").output);
  const e2e::CommandResult unknown = e2e::surrogate("help frobnicate");
  INFO(unknown.output);
  CHECK(unknown.exitCode == 2);
  CHECK_THAT(unknown.output, Contains("\"frobnicate\"") &&
                                 Contains("run, pack, lights, fit, render, publish, info, report, review, verify, audit"));
}

TEST_CASE("run refuses a folder that is not a capture and writes nothing in it") {
  const fs::path root = e2e::freshDir("run-not-capture");
  fs::create_directories(root / "notes");
  std::ofstream(root / "notes/readme.txt") << "a folder of notes\n";
  fs::create_directories(root / "empty-originals/original-captures");
  fs::create_directories(root / "loose");
  fs::copy_file(e2e::smallCapture(e2e::freshDir("run-not-capture-src")) / "jpeg-exports/IMG_0001.jpg",
                root / "loose/IMG_0001.jpg");
  for (const char* folder : {"notes", "empty-originals", "loose"}) {
    const std::vector<std::string> before = listing(root / folder);
    for (const char* command : {"run", "lights"}) {
      const std::string output = std::string(command) == "lights" ? " -o " + e2e::quote(root / "out.lp") : "";
      const e2e::CommandResult r =
          e2e::surrogate(std::string(command) + " " + e2e::quote(root / folder) + output + " --quiet");
      INFO(command << " " << folder << "\n" << r.output);
      CHECK(r.exitCode == 1);
      CHECK_THAT(r.output, Contains(folder + std::string(": is not a capture folder")));
      CHECK_THAT(r.output, Contains("original-captures/"));
      CHECK(listing(root / folder) == before);
    }
  }
}

// Issue 51: a run killed in its commit leaves a journal the next command finishes (run/run_commit.h);
// `info` said nothing of it, and showed the record before that run as the capture's.
TEST_CASE("info on a capture says a commit is pending and what the next command will do with it") {
  const fs::path capture = e2e::processedCapture(e2e::freshDir("info-pending"));
  CHECK_THAT(info(capture, " --json").output, Contains("\"pendingCommit\":null"));
  CHECK_THAT(info(capture).output, !Contains("pending:"));

  // Killed between moving the results and the carrier (the fault injection of test_workflow_e2e).
  const e2e::CommandResult crash = e2e::runShell("SURROGATE_FAULT_INJECTION=commit " + std::string(SURROGATE_EXE) +
                                                 " run " + e2e::quote(capture) + " --basis hsh2 --no-report --quiet");
  REQUIRE(crash.exitCode == 137);
  REQUIRE(fs::exists(capture / ".surrogate/commit"));
  const e2e::CommandResult text = info(capture);
  INFO(text.output);
  CHECK(text.exitCode == 0);
  CHECK_THAT(text.output, Contains("  pending:   run r2 (run, started ") &&
                              Contains(") was stopped while it committed its results (its journal is .surrogate/commit): "
                                       "the next run, lights, pack, audit or Apply in review first finishes that commit"));
  const e2e::CommandResult json = info(capture, " --json");
  CHECK(json.exitCode == 0);
  CHECK_THAT(json.output, Contains("\"pendingCommit\":{\"state\":\"finish-commit\",\"description\":\"run r2 (run, "));

  // Finished by the next command: nothing pending any more, and info says nothing of it.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --no-report --quiet").exitCode == 0);
  CHECK_THAT(info(capture).output, !Contains("pending:"));

  // A staging folder without a journal: a run killed before its commit, discarded next time.
  fs::create_directories(capture / ".surrogate/staging/assembly-files");
  CHECK_THAT(info(capture).output,
             Contains("  pending:   a run was stopped before its commit: the next run, lights, pack, audit or Apply in "
                      "review discards its partial results (.surrogate/staging); the capture stays as recorded\n"));
  CHECK_THAT(info(capture, " --json").output, Contains("\"pendingCommit\":{\"state\":\"discard-staging\""));

  // A journal with a staged record that cannot be read: recovery stops on it, and info says so.
  std::ofstream(capture / ".surrogate/staging/assembly-files/carrier.xml") << "<garbage";
  std::ofstream(capture / ".surrogate/commit") << "commit\n";
  CHECK_THAT(info(capture).output, Contains("its staged record (.surrogate/staging/assembly-files/carrier.xml) cannot be "
                                            "read (") &&
                                       Contains("stops on it; restore the capture from a backup or package\n"));
}

// Issue 51: the help listed 0, 1, 2 and 5, while info exits 3 for a damaged archive and 2 for a
// file named as a package that is none; each exit code info gives is in its help.
TEST_CASE("info's help lists the exit codes info gives for a damaged archive and a file that is no package") {
  const fs::path dir = e2e::freshDir("info-exits");
  std::ofstream(dir / "damaged.zip", std::ios::binary) << std::string("PK\3\4", 4) << "a header cut short";
  std::ofstream(dir / "text.zip", std::ios::binary) << "a text file named as a package\n";
  const e2e::CommandResult damaged = info(dir / "damaged.zip");
  const e2e::CommandResult none = info(dir / "text.zip");
  CHECK(damaged.exitCode == 3);
  CHECK(none.exitCode == 2);
  const std::string help = e2e::surrogate("info --help").output;
  CHECK_THAT(help, Contains("\n  3  a package archive truncated or damaged\n"));
  CHECK_THAT(help, Contains("\n  2  bad usage (an unknown option, a missing or malformed value), or a package that is not"));
}

// Issue 56: an .lp, a .ptm and an .rti are described in the layout of every other kind (an
// image, a capture, a package): "PATH: what it is", then indented "label: value" lines, the
// values in one column.
TEST_CASE("info on an .lp and a .ptm and an .rti uses the layout of an image and a capture and a package") {
  const fs::path capture = e2e::processedCapture(e2e::freshDir("info-layout"));
  const std::regex factLine("  [A-Za-z][A-Za-z ]*: +[^ ].*");
  auto checkLayout = [&](const fs::path& file, const std::string& heading) {
    const e2e::CommandResult r = info(file);
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    std::istringstream lines(r.output);
    std::string first, line;
    std::getline(lines, first);
    CHECK(first == file.string() + ": " + heading);
    std::size_t column = 0;
    int facts = 0;
    while (std::getline(lines, line)) {
      INFO(line);
      CHECK(std::regex_match(line, factLine));
      const std::size_t value = line.find_first_not_of(' ', line.find(':') + 1);
      if (column == 0) column = value;
      CHECK(value == column);  // one column of values
      ++facts;
    }
    CHECK(facts >= 3);
  };
  checkLayout(capture / "assembly-files/lights.lp", "light positions (.lp), 8 lights");
  checkLayout(capture / "finished-files/ptm-lrgb.ptm", "PTM model ptm-lrgb, 400x300");
  checkLayout(capture / "finished-files/hsh2.rti", "RTI model hsh2, 400x300");
  // The kinds they now match: an image, and the first lines of a capture folder.
  const e2e::CommandResult image = info(capture / "jpeg-exports/IMG_0001.jpg");
  CHECK_THAT(image.output, Contains(capture.string() + "/jpeg-exports/IMG_0001.jpg: image ") && Contains("\n  PRONOM:  "));
  const e2e::CommandResult folder = info(capture);
  CHECK_THAT(folder.output, Contains(capture.string() + ": capture folder\n  shots: "));
  // The facts themselves.
  const e2e::CommandResult lp = info(capture / "assembly-files/lights.lp");
  CHECK_THAT(lp.output, Contains("\n  PRONOM:    Plain Text File (x-fmt/111,") && Contains("\n  elevation: ") &&
                            Contains("\n  bytes:     "));
  const e2e::CommandResult ptm = info(capture / "finished-files/ptm-lrgb.ptm");
  CHECK_THAT(ptm.output, Contains("\n  format:    PTM_1.2, PTM_FORMAT_LRGB\n  terms:     6 per channel\n  scale:     "));
}

// Issue 56: pack says it writes data/ro-crate-metadata.json, and info names it for what it is,
// not "other payload".
TEST_CASE("pack mentions the RO-Crate metadata it writes and info names it for what it is") {
  const fs::path dir = e2e::freshDir("info-ro-crate");
  const fs::path capture = e2e::processedCapture(dir);
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "pkg"));
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  CHECK_THAT(pack.output, Contains("data/ro-crate-metadata.json (RO-Crate"));
  const e2e::CommandResult text = info(dir / "pkg");
  INFO(text.output);
  CHECK_THAT(text.output, Contains("\n    RO-Crate metadata 1 file, "));
  CHECK(text.output.find("other payload") == std::string::npos);
  const e2e::CommandResult json = info(dir / "pkg", " --json");
  CHECK_THAT(json.output, Contains("{\"role\":\"RO-Crate metadata\",\"files\":1,"));
  CHECK(json.output.find("other payload") == std::string::npos);
}
