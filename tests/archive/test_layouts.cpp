// The places of the bag's files in an E-ARK SIP (docs/package.md, "The package as an E-ARK
// SIP"), both ways: verify puts the bag back together with bagPathOf, so every file a bag
// can hold must come back to where it was, the tag files other versions may add included.
// The checks of an OCFL object that verify and pack --layout ocfl share, on hostile
// inventories and objects (run under AddressSanitizer too), and the names a package can have.
#include <catch2/catch.hpp>

#include <fstream>

#include "archive/bag.h"
#include "archive/eark_layout.h"
#include "archive/ocfl_object.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/text.h"
#include "test_files.h"

using surrogate::archive::bagPathOf;
using surrogate::archive::sipPathOf;

TEST_CASE("E-ARK SIP places: each bag file where docs/package.md puts it, and back", "[layouts]") {
  const std::vector<std::pair<std::string, std::string>> places = {
      {"data/original-captures/IMG_1.dng", "representations/rep1/data/original-captures/IMG_1.dng"},
      {"data/assembly-files/carrier.xml", "representations/rep1/data/assembly-files/carrier.xml"},
      {"metadata/mets.xml", "metadata/preservation/mets.xml"},
      {"metadata/crm.rdf", "metadata/descriptive/crm.rdf"},
      {"metadata/xsd/mets-1.12.1.xsd", "schemas/mets-1.12.1.xsd"},
      {"metadata/mappings/carrier-to-mets.md", "documentation/mappings/carrier-to-mets.md"},
      {"metadata/xslt/carrier-to-crm.xsl", "documentation/xslt/carrier-to-crm.xsl"},
      {"metadata/formats.md", "documentation/formats.md"},
      {"bagit.txt", "metadata/other/bagit/bagit.txt"},
      {"bag-info.txt", "metadata/other/bagit/bag-info.txt"},
      {"tagmanifest-sha512.txt", "metadata/other/bagit/tagmanifest-sha512.txt"},
      {"README.txt", "metadata/other/bagit/README.txt"},
  };
  for (const auto& [bag, sip] : places) {
    INFO(bag);
    CHECK(sipPathOf(bag) == sip);
    CHECK(bagPathOf(sip) == bag);
  }
  // The METS files and anything no bag file maps to have no place in the bag.
  for (const char* sip : {"METS.xml", "representations/rep1/METS.xml", "representations/rep2/data/x",
                          "metadata/other/bagit/", "metadata/preservation/premis.xml", "extra.txt"}) {
    INFO(sip);
    CHECK(!bagPathOf(sip));
  }
}

namespace {

namespace fs = std::filesystem;
using namespace surrogate;

std::string sha512Of(const std::string& bytes) {
  MultiDigest d({DigestAlgorithm::Sha512});
  d.update(bytes.data(), bytes.size());
  return d.hex(DigestAlgorithm::Sha512);
}

void put(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

// A one-version inventory holding `content` as v1/content/bagit.txt, logical path `logical`;
// `contentPath` replaces the manifest's path when given.
std::string inventory(const std::string& content, const std::string& logical = "bagit.txt",
                      const std::string& contentPath = "v1/content/bagit.txt") {
  const std::string digest = sha512Of(content);
  return "{\"digestAlgorithm\":\"sha512\",\"head\":\"v1\",\"id\":\"urn:x\",\"manifest\":{\"" + digest + "\":[\"" +
         contentPath + "\"]},\"type\":\"https://ocfl.io/1.1/spec/#inventory\",\"versions\":{\"v1\":{\"created\":"
         "\"2023-11-14T22:13:20Z\",\"state\":{\"" + digest + "\":[\"" + logical + "\"]}}}}\n";
}

// A sound OCFL 1.1 object of one version holding one file.
fs::path soundObject(const std::string& name) {
  const fs::path obj = testfiles::freshDir(name) / "object";
  const std::string content = "BagIt-Version: 1.0\n", text = inventory(content);
  put(obj / "0=ocfl_object_1.1", "ocfl_object_1.1\n");
  put(obj / "v1" / "content" / "bagit.txt", content);
  for (const fs::path& folder : {obj, obj / "v1"}) {
    put(folder / "inventory.json", text);
    put(folder / "inventory.json.sha512", sha512Of(text) + " inventory.json\n");
  }
  return obj;
}

bool mentions(const std::vector<std::string>& problems, const std::string& what) {
  for (const std::string& p : problems)
    if (p.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("an OCFL inventory whose paths leave the object or its versions is refused", "[layouts][ocfl]") {
  const std::string content = "x";
  std::vector<std::string> problems;
  REQUIRE(archive::parseOcflInventory(inventory(content), "1.1", problems));
  CHECK(problems.empty());
  const std::vector<std::pair<std::string, std::string>> hostile = {
      {inventory(content, "bagit.txt", "../../../../etc/passwd"), "../../../../etc/passwd"},
      {inventory(content, "bagit.txt", "/etc/passwd"), "/etc/passwd"},
      {inventory(content, "bagit.txt", "v1/content/../../x"), "v1/content/../../x"},
      {inventory(content, "bagit.txt", "v2/content/bagit.txt"), "v2/content/bagit.txt"},  // no such version
      {inventory(content, "bagit.txt", "v1/bagit.txt"), "v1/bagit.txt"},                  // not under content/
      {inventory(content, "../bagit.txt"), "../bagit.txt"},
      {inventory(content, "/etc/passwd"), "/etc/passwd"},
      {inventory(content, "data/a\\\\b.txt"), "a\\b.txt"},
      {"[]", "not a JSON object"},
      {"{\"id\":1}", "\"id\""},
      {std::string(200000, '['), "levels deep"},
      {"{\"id\":", "not valid JSON"},
      {std::string(100000, '[') + std::string(100000, ']'), "levels deep"},
  };
  for (const auto& [text, named] : hostile) {
    INFO(text.substr(0, 300));
    problems.clear();
    CHECK(!archive::parseOcflInventory(text, "1.1", problems));
    CHECK(mentions(problems, named));
  }
  // Brackets inside a string do not nest.
  problems.clear();
  CHECK(archive::parseOcflInventory("{\"note\":\"[[[[[[[[[[[[[[[[[[[[\\\"[[\"," + inventory(content).substr(1), "1.1", problems));
  CHECK(problems.empty());
}

TEST_CASE("checkOcflObject finds a link, a changed copy and an edited inventory in an object", "[layouts][ocfl]") {
  CHECK(archive::checkOcflObject(soundObject("ocfl-sound")).sound());

  const fs::path linked = soundObject("ocfl-link");
  fs::remove(linked / "v1" / "content" / "bagit.txt");
  fs::create_symlink("/etc/passwd", linked / "v1" / "content" / "bagit.txt");
  const archive::OcflObjectCheck l = archive::checkOcflObject(linked);
  CHECK(mentions(l.walk.problems, "v1/content/bagit.txt: a symbolic link"));
  CHECK(mentions(l.complete, "v1/content/bagit.txt"));  // a link is no content file

  const fs::path version = soundObject("ocfl-version-link");
  fs::rename(version / "v1", version.parent_path() / "v1-elsewhere");
  fs::create_symlink(version.parent_path() / "v1-elsewhere", version / "v1");
  CHECK(mentions(archive::checkOcflObject(version).problems(), "v1: a symbolic link"));

  const fs::path flipped = soundObject("ocfl-flip");
  put(flipped / "v1" / "content" / "bagit.txt", "BagIt-Version: 1.1\n");
  const archive::OcflObjectCheck f = archive::checkOcflObject(flipped);
  CHECK(mentions(f.fixity, "v1/content/bagit.txt"));
  archive::OcflCheckOptions noDigests;
  noDigests.contentDigests = false;
  CHECK(archive::checkOcflObject(flipped, noDigests).sound());

  const fs::path huge = soundObject("ocfl-huge");  // never read whole
  fs::resize_file(huge / "inventory.json", archive::kMaxOcflInventoryBytes + 1);
  CHECK(mentions(archive::checkOcflObject(huge).inventoryProblems, "more than the 64 MiB"));

  // Deeply nested, under an unknown key: pack would have written it back out (see nestingDepth).
  const fs::path deep = soundObject("ocfl-deep");
  const std::string deepText = "{\"x\":" + std::string(20, '[') + std::string(20, ']') + "," + inventory("BagIt-Version: 1.0\n").substr(1);
  put(deep / "inventory.json", deepText);
  put(deep / "inventory.json.sha512", sha512Of(deepText) + " inventory.json\n");
  CHECK(mentions(archive::checkOcflObject(deep).inventoryProblems, "levels deep"));

  const fs::path edited = soundObject("ocfl-edited");
  put(edited / "inventory.json", inventory("BagIt-Version: 1.1\n"));
  CHECK(!archive::checkOcflObject(edited).sidecar.empty());
}

TEST_CASE("a package name that is not UTF-8 or holds a control character or backslash is refused", "[layouts][names]") {
  for (const char* good : {"pkg.zip", "stela 12 \xc3\xa9.tar", "bag", "repo/stela12/", "a.b.zip", "a:b", "x~.zip"}) {
    INFO(good);
    CHECK_NOTHROW(archive::checkPackageName(good));
  }
  for (const char* bad : {"lat\xe9.zip", "lat\xe9.tar", "lat\xe9", "back\\slash.zip", "tab\t.zip", "line\n.tar",
                          "...zip", "..tar", "sip\x01/", "sip\xef\xbf\xbe", "c1\xc2\x85.zip", "a:b.zip",
                          "~home.tar"}) {
    INFO(bad);
    try {
      archive::checkPackageName(bad);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(e.exitCode() == 1);
      CHECK(!needsEscaping(e.text(), true));  // shown escaped
    }
  }
}

TEST_CASE("writeBag refuses an entry name that is not UTF-8 instead of handing it to libarchive", "[layouts][names]") {
  // libarchive 3.6 keeps such a name, then finds no name to write: its zip writer dereferenced a
  // null pointer (a crash), its tar writer failed with "Unknown error -1".
  const fs::path dir = testfiles::freshDir("bag-names");
  put(dir / "src" / "a.txt", "a");
  for (const char* out : {"pkg.zip", "pkg.tar"}) {
    INFO(out);
    archive::BagInput in;
    in.payload.push_back({"data/lat\xe9.txt", dir / "src" / "a.txt", ""});
    try {
      archive::writeBag(in, dir / out);
      FAIL("written");
    } catch (const Error& e) {
      CHECK(e.exitCode() == 1);
      CHECK(e.text().find("lat\\xE9.txt") != std::string::npos);
    }
    CHECK(!fs::exists(dir / out));
  }
}
