// `surrogate pack` on a generated capture, as a user runs it: the pipeline runs when needed,
// the bag checks out (RFC 8493 validation with recomputed digests), the originals are
// byte-identical inside it, the metadata is valid, and two packs are byte-identical; a
// holder's bag-info fields (pack --bag-info, or added afterwards) keep it sound.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bag_check.h"
#include "e2e_support.h"
#include "mapping/mapping.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using testfiles::slurp;

namespace {
struct Epoch {
  Epoch() { ::setenv("SOURCE_DATE_EPOCH", "1700000000", 1); }
  ~Epoch() { ::unsetenv("SOURCE_DATE_EPOCH"); }
};
}  // namespace

TEST_CASE("surrogate pack runs the pipeline when needed and writes a valid bag", "[e2e][pack]") {
  Epoch epoch;
  const fs::path dir = e2e::freshDir("pack");
  const fs::path capture = e2e::smallCapture(dir);
  const auto originalsBefore = e2e::snapshot(capture / "original-captures");
  const auto exportsBefore = e2e::snapshot(capture / "jpeg-exports");

  e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "pkg.zip") +
                                        " --meta Source-Organization=Museum --meta External-Identifier=INV-7 --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(r.output.find("\"pipelineRan\":true") != std::string::npos);
  CHECK(fs::exists(capture / "assembly-files/carrier.xml"));

  const bagcheck::BagFiles bag = bagcheck::readBag(dir / "pkg.zip");
  const auto problems = bagcheck::validate(bag);
  INFO((problems.empty() ? std::string() : problems.front()));
  CHECK(problems.empty());
  // The originals are untouched in the capture and byte-identical in the bag.
  CHECK(e2e::snapshot(capture / "original-captures") == originalsBefore);
  CHECK(e2e::snapshot(capture / "jpeg-exports") == exportsBefore);
  for (const auto& [rel, sha] : originalsBefore) {
    INFO(rel);
    REQUIRE(bag.files.count("data/original-captures/" + rel) == 1);
    CHECK(bagcheck::sha256(bag.files.at("data/original-captures/" + rel)) == sha);
  }
  CHECK(bag.files.at("data/assembly-files/carrier.xml") == slurp(capture / "assembly-files/carrier.xml"));
  CHECK(bag.files.count("data/assembly-files/lights.lp") == 1);
  CHECK(bag.files.count("data/finished-files/ptm-lrgb.ptm") == 1);
  CHECK(bag.files.count("data/finished-files/report.html") == 1);
  const auto info = bagcheck::parseBagInfo(bag.files.at("bag-info.txt"));
  CHECK(info.find("Source-Organization")->second == "Museum");
  CHECK(info.find("External-Identifier")->second == "INV-7");
  CHECK(info.find("Bagging-Date")->second == "2023-11-14");

  // Metadata: METS+PREMIS valid offline; crm.rdf parses with rapper.
  CHECK_NOTHROW(mapping::validateMets(bag.files.at("metadata/mets.xml"), "metadata/mets.xml"));
  std::ofstream(dir / "crm.rdf", std::ios::binary) << bag.files.at("metadata/crm.rdf");
  const e2e::CommandResult rapper = e2e::runShell("rapper -i rdfxml -c " + e2e::quote(dir / "crm.rdf"));
  INFO(rapper.output);
  CHECK(rapper.exitCode == 0);
  CHECK(rapper.output.find("returned 0 triples") == std::string::npos);

  // Again: the carrier is complete now, the pipeline does not run, and the bytes are the same.
  fs::create_directories(dir / "again");
  r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "again/pkg.zip") + " --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(r.output.find("\"pipelineRan\":false") != std::string::npos);
  CHECK(slurp(dir / "pkg.zip") == slurp(dir / "again/pkg.zip"));

  // As a tar and as a folder: the same files.
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "pkg.tar") + " --quiet").exitCode == 0);
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "pkg") + " --quiet").exitCode == 0);
  CHECK(bagcheck::readBag(dir / "pkg.tar").files == bag.files);
  CHECK(bagcheck::readBag(dir / "pkg").files == bag.files);
}

TEST_CASE("surrogate pack re-runs the pipeline when a result no longer matches the carrier", "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-stale");
  const fs::path capture = e2e::smallCapture(dir);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet").exitCode == 0);
  // Same size, other content: only the digest computed while packing can tell.
  {
    std::fstream f(capture / "finished-files/ptm-lrgb.ptm", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-1, std::ios::end);
    f.put('\x5a');
  }
  const e2e::CommandResult r =
      e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "pkg.tar") + " --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(r.output.find("\"pipelineRan\":true") != std::string::npos);
  CHECK(r.output.find("ptm-lrgb.ptm no longer matches the carrier") != std::string::npos);
  CHECK(bagcheck::validate(bagcheck::readBag(dir / "pkg.tar")).empty());
}

TEST_CASE("surrogate pack explains a bad command line or an unwritable output", "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-errors");
  const fs::path capture = e2e::smallCapture(dir);
  e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(capture));
  CHECK(r.exitCode == 2);
  CHECK(r.output.find("-o OUT") != std::string::npos);
  // A capture that is not there is bad input, as for run (exit 1).
  r = e2e::surrogate("pack " + e2e::quote(dir / "nothing") + " -o " + e2e::quote(dir / "x.zip"));
  CHECK(r.exitCode == 1);
  r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "missing/folder/pkg.zip") + " --quiet");
  CHECK(r.exitCode == 2);
  CHECK(r.output.find("pkg.zip") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "missing"));
  r = e2e::surrogate("pack --help");
  CHECK(r.exitCode == 0);
  CHECK(r.output.find("BagIt") != std::string::npos);
}

// Issue 51: a name that is not UTF-8 crashed libarchive's zip writer (exit 139) and gave "Unknown
// error -1" for a .tar; a backslash, tab or line feed gave a package its own verify refused.
// Every such name is refused before anything is written, shown escaped, in every layout.
TEST_CASE("pack refuses a package name no package can hold before writing anything", "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-names");
  const fs::path capture = e2e::processedCapture(dir);
  const auto captureBefore = e2e::snapshot(capture);
  struct Name {
    std::string name, shown, layout;
  };
  const std::vector<Name> names = {
      {"lat\xe9.zip", "lat\\xE9.zip", ""},
      {"lat\xe9.tar", "lat\\xE9.tar", ""},
      {"lat\xe9", "lat\\xE9", ""},
      {"back\\slash.zip", "back\\slash.zip", ""},
      {"tab\there.zip", "tab\\x09here.zip", ""},
      {"line\nfeed.tar", "line\\x0Afeed.tar", ""},
      {"...zip", "\"..\"", ""},  // the folder inside would be ".."
      {"object\xe9", "object\\xE9", "--layout ocfl"},
      {"sip\x01", "sip\\x01", "--layout eark"},
      {"sip\xef\xbf\xbe", "sip\\xEF\\xBF\\xBE", "--layout eark"},  // U+FFFE: its METS could not name it
  };
  for (const Name& n : names) {
    INFO(n.shown);
    const e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / n.name) +
                                                " --quiet " + n.layout);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find(n.shown) != std::string::npos);
    if (n.shown.find("\\x") != std::string::npos)
      CHECK(r.output.find(n.name) == std::string::npos);  // never the raw bytes
  }
  // Nothing beside the capture (no package, no leftover), nothing changed in it.
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  CHECK(left == std::vector<std::string>{"cap"});
  CHECK(e2e::snapshot(capture) == captureBefore);
}

TEST_CASE("pack shows the tabs and line feeds of a capture's name and its bytes that are not UTF-8 escaped", "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-shown");
  const fs::path capture = dir / "cap\ttab\nline\xe9";  // the capture's name is not in its package
  fs::rename(e2e::processedCapture(dir), capture);
  for (const std::string& quiet : {"", " --quiet"}) {
    const fs::path out = dir / ("pkg" + std::to_string(quiet.size()) + ".zip");
    const e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(out) + quiet);
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    CHECK(r.output.find("cap\\x09tab\\x0Aline\\xE9") != std::string::npos);
    CHECK(r.output.find('\t') == std::string::npos);
    CHECK(r.output.find("\xe9") == std::string::npos);
  }
}

TEST_CASE("verify sets aside the files an operating system leaves in a bag folder, with a warning", "[e2e][pack]") {
  // A bag folder copied with a Mac or opened on Windows gains .DS_Store, ._* and Thumbs.db
  // files. run and pack ignore them; verify names each with the command to remove it and
  // counts them only with --strict. A real unlisted file still fails, and a listed file is
  // payload whatever its name.
  const fs::path dir = e2e::freshDir("pack-system-files");
  const fs::path capture = e2e::smallCapture(dir);
  const fs::path bag = dir / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  for (const char* name : {".DS_Store", "data/.DS_Store", "data/finished-files/._ptm-lrgb.ptm", "metadata/Thumbs.db"})
    std::ofstream(bag / name) << "left by a file manager";

  const auto lenient = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute");
  INFO(lenient.output);
  CHECK(lenient.exitCode == 0);
  CHECK_THAT(lenient.output, Catch::Contains("data/.DS_Store: a file the operating system left") &&
                                 Catch::Contains("rm '" + (bag / "metadata/Thumbs.db").string() + "'") &&
                                 Catch::Contains("including re-execution"));
  const auto strict = e2e::surrogate("verify " + e2e::quote(bag) + " --strict --quiet");
  CHECK(strict.exitCode == 3);
  CHECK_THAT(strict.output, Catch::Contains("data/.DS_Store: in the payload but not listed"));

  std::ofstream(bag / "data/notes.txt") << "added after packing";
  const auto added = e2e::surrogate("verify " + e2e::quote(bag) + " --quiet");
  CHECK(added.exitCode == 3);
  CHECK_THAT(added.output, Catch::Contains("data/notes.txt: in the payload but not listed"));
}

namespace {

// What a holder who edits a tag file does, as RFC 8493 asks: every tag manifest's lines redone
// for the files as they are now.
void redoTagManifests(const fs::path& bag) {
  for (const char* algorithm : {"sha256", "sha512"}) {
    const fs::path manifest = bag / (std::string("tagmanifest-") + algorithm + ".txt");
    std::istringstream in(slurp(manifest));
    std::string line, out;
    while (std::getline(in, line)) {
      const std::string path = line.substr(line.find("  ") + 2);
      const std::string bytes = slurp(bag / path);
      out += (algorithm == std::string("sha256") ? bagcheck::sha256(bytes) : bagcheck::sha512(bytes)) + "  " +
             path + "\n";
    }
    std::ofstream(manifest, std::ios::binary | std::ios::trunc) << out;
  }
}

void replaceIn(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = slurp(file);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

}  // namespace

TEST_CASE("bag-info fields a holder adds afterwards keep the package sound, listed as the holder's",
          "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-holder");
  const fs::path capture = e2e::processedCapture(dir);
  const fs::path bag = dir / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  std::ofstream(bag / "bag-info.txt", std::ios::binary | std::ios::app)
      << "Internal-Sender-Identifier: accession 2026/17\nExternal-Identifier: ark:/12345/stela12\n";

  // bag-info.txt changed and the tag manifests not redone: a fixity failure.
  auto r = e2e::surrogate("verify " + e2e::quote(bag) + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 3);
  CHECK_THAT(r.output, Catch::Contains("bag-info.txt: sha256"));

  redoTagManifests(bag);
  r = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("Internal-Sender-Identifier: accession 2026/17  (added by the holder)") &&
                           Catch::Contains("External-Identifier: ark:/12345/stela12  (added by the holder)") &&
                           Catch::Contains("SOUND"));
  r = e2e::surrogate("verify " + e2e::quote(bag) + " --json");
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("\"holderFields\":[{\"label\":\"Internal-Sender-Identifier\","
                                       "\"value\":\"accession 2026/17\",\"addedBy\":\"holder\"},"
                                       "{\"label\":\"External-Identifier\",\"value\":\"ark:/12345/stela12\","
                                       "\"addedBy\":\"holder\"}]"));

  // A field Surrogate wrote, changed with the tag manifests redone: still invalid.
  replaceIn(bag / "bag-info.txt", "External-Description: ", "External-Description: Stela 9, ");
  redoTagManifests(bag);
  r = e2e::surrogate("verify " + e2e::quote(bag) + " --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Catch::Contains("FAIL  package.info") && Catch::Contains("the carrier's header gives"));
}

TEST_CASE("pack --bag-info writes a holder's fields into bag-info.txt, and refuses malformed ones",
          "[e2e][pack]") {
  const fs::path dir = e2e::freshDir("pack-bag-info");
  const fs::path capture = e2e::processedCapture(dir);
  const std::string carrierBefore = slurp(capture / "assembly-files/carrier.xml");
  const fs::path bag = dir / "pkg.zip";
  auto r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) +
                          " --bag-info External-Identifier=INV-7 --bag-info 'Contact-Name=Ana Silva'"
                          " --bag-info Contact-Email=archive@museum.example --bag-info 'Contact-Name=Rui Costa'"
                          " --bag-info Source-Organization=Museum --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(r.output.find("\"pipelineRan\":false") != std::string::npos);
  CHECK(r.output.find("{\"label\":\"External-Identifier\",\"value\":\"INV-7\"}") != std::string::npos);
  // Not in the carrier: the capture's record and the package identifier are the same.
  CHECK(slurp(capture / "assembly-files/carrier.xml") == carrierBefore);
  const bagcheck::BagFiles files = bagcheck::readBag(bag);
  CHECK(bagcheck::validate(files).empty());
  const std::string info = files.files.at("bag-info.txt");
  CHECK_THAT(info, Catch::EndsWith("External-Identifier: INV-7\nContact-Name: Ana Silva\n"
                                   "Contact-Email: archive@museum.example\nContact-Name: Rui Costa\n"
                                   "Source-Organization: Museum\n"));
  r = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("Contact-Email: archive@museum.example  (added by the holder)") &&
                           Catch::Contains("Contact-Name: Rui Costa  (added by the holder)") &&
                           Catch::Contains("SOUND"));
  r = e2e::surrogate("info " + e2e::quote(bag));
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Catch::Contains("holder's:   External-Identifier: INV-7 (added by the holder)"));
  CHECK(r.output.find("holder's:   External-Description") == std::string::npos);

  // Refused before anything is written, exit 2, saying why.
  struct Refusal {
    std::string option, text;
  };
  const std::vector<Refusal> refusals = {
      {"--bag-info 'Contact Name=Ana'", "is not a usable bag-info.txt label"},
      {"--bag-info 'Contact:Name=Ana'", "is not a usable bag-info.txt label"},
      {"--bag-info ' Contact-Name=Ana'", "is not a usable bag-info.txt label"},
      {"--bag-info \"Contact-Name=Ana$(printf '\\nX')\"", "has a value with a line break"},
      {"--bag-info Payload-Oxum=1.1", "is written by Surrogate itself"},
      {"--bag-info Surrogate-Note=x", "is written by Surrogate itself"},
      {"--bag-info External-Description=x", "is already written by Surrogate from the carrier"},
      {"--bag-info Contact-Name", "needs the form LABEL=VALUE"},
  };
  for (const Refusal& f : refusals) {
    const fs::path out = dir / "refused.zip";
    r = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(out) + " --quiet " + f.option);
    INFO(f.option << "\n" << r.output);
    CHECK(r.exitCode == 2);
    CHECK_THAT(r.output, Catch::Contains(f.text));
    CHECK_FALSE(fs::exists(out));
  }
}
