// Bags that other tools made (md5 and sha1 manifests, UTF-16 and ISO-8859-1 tag files,
// fetch.txt): classified by their BagIt validity alone, as a folder, .tar and .zip; and the
// two-part verdict of Surrogate packages.
#include <catch2/catch.hpp>

#include "archive/bag_text.h"
#include "bag_fixture.h"
#include "generic_bag.h"
#include "report_helpers.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace verify_test;
using Catch::Matchers::Contains;

namespace {

// The bag as a folder, a .tar with a top folder and a .zip.
std::vector<fs::path> threeForms(const GenericBag& bag, const std::string& name) {
  const fs::path dir = freshDir(name);
  bag.write(dir / "bag");
  archiveDirectory(dir / "bag", dir / "bag.tar", "bag/");
  archiveDirectory(dir / "bag", dir / "bag.zip", "");
  return {dir / "bag", dir / "bag.tar", dir / "bag.zip"};
}

GenericBag sample() {
  GenericBag b;
  b.payload = {{"data/hello.txt", "hello\n"},
               {"data/test 1.txt", "a name with a space\n"},
               {"data/caf\xC3\xA9/100% done.txt", "percent and accent\n"}};
  return b;
}

bool onlyBagItChecks(const verify::Report& r) {
  for (const verify::Check& c : r.checks)
    if (!c.aboutBagIt()) return false;
  return true;
}

}  // namespace

TEST_CASE("a valid md5 bag from another tool is a valid bag, not a Surrogate package, with a "
          "warning (exit 0)", "[verify][generic]") {
  for (const fs::path& p : threeForms(sample(), "generic-md5")) {
    const verify::Report r = run(p);
    INFO(p << "\n" << allText(r));
    CHECK(r.exitCode() == 0);
    CHECK(r.bagitValid());
    CHECK_FALSE(r.surrogatePackage);
    CHECK_FALSE(r.packageSound());
    CHECK(onlyBagItChecks(r));  // never mixed with carrier or METS failures
    CHECK_FALSE(failed(r, "bagit.fixity-md5"));
    REQUIRE(r.warnings.size() >= 1);
    CHECK_THAT(r.warnings.front(), Contains("manifest-md5.txt") && Contains("sha256 or sha512"));
  }
}

TEST_CASE("sha1 and md5 manifests check fixity: a changed or missing file fails (exit 3)",
          "[verify][generic]") {
  GenericBag b = sample();
  b.algorithms = {DigestAlgorithm::Sha1, DigestAlgorithm::Md5};
  const fs::path dir = freshDir("generic-sha1");
  b.write(dir / "bag");
  verify::Report r = run(dir / "bag");
  INFO(allText(r));
  CHECK(r.exitCode() == 0);
  CHECK_FALSE(failed(r, "bagit.tagfixity-sha1"));

  writeText(dir / "bag/data/hello.txt", "hellO\n");
  r = run(dir / "bag");
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.fixity-sha1"));
  CHECK(failed(r, "bagit.fixity-md5"));
  CHECK_FALSE(r.bagitValid());
  CHECK(onlyBagItChecks(r));

  fs::remove(dir / "bag/data/test 1.txt");
  r = run(dir / "bag");
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.complete"));
}

TEST_CASE("tag files in UTF-16 (with a byte-order mark) and ISO-8859-1 are read as bagit.txt "
          "declares", "[verify][generic]") {
  for (const char* encoding : {"UTF-16", "ISO-8859-1"}) {
    GenericBag b = sample();
    b.encoding = encoding;
    b.algorithms = {DigestAlgorithm::Sha256};
    b.bagInfo += "Contact-Name: Jos\xC3\xA9 M\xC3\xBCller\n";
    for (const fs::path& p : threeForms(b, std::string("generic-") + encoding)) {
      const verify::Report r = run(p);
      INFO(encoding << " " << p << "\n" << allText(r));
      CHECK(r.exitCode() == 0);
      CHECK(r.bagitValid());
      CHECK(r.warnings.empty());
    }
  }
}

TEST_CASE("a tag file that is not valid in the declared encoding, or an encoding no one knows, "
          "is invalid (exit 2)", "[verify][generic]") {
  GenericBag b = sample();
  b.encoding = "UTF-16";
  b.tagManifests = false;  // so that only the manifest's text is at fault
  const fs::path dir = freshDir("generic-badenc");
  b.write(dir / "bag");
  // An odd number of bytes ends UTF-16 in the middle of a character.
  writeText(dir / "bag/manifest-md5.txt", readText(dir / "bag/manifest-md5.txt") + "x");
  verify::Report r = run(dir / "bag");
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK_THAT(allText(r), Contains("manifest-md5.txt: cannot be read as UTF-16"));
  CHECK(r.exitCode() == 2);

  GenericBag unknown = sample();
  unknown.tagManifests = false;
  const fs::path other = freshDir("generic-unknownenc");
  unknown.write(other / "bag");
  writeText(other / "bag/bagit.txt", "BagIt-Version: 0.97\nTag-File-Character-Encoding: KLINGON-8\n");
  r = run(other / "bag");
  INFO(allText(r));
  CHECK(failed(r, "bagit.declaration"));
  CHECK_THAT(allText(r), Contains("KLINGON-8"));
  CHECK(r.exitCode() == 2);
}

TEST_CASE("fetch.txt: the path is the rest of the line, percent-encoded, and files to fetch "
          "must be in the bag", "[verify][generic]") {
  GenericBag b = sample();
  b.fetch = "http://example.org/hello.txt 6 data/hello.txt\n"
            "https://example.org/t1 - data/test 1.txt\n"
            "https://example.org/p\t19\tdata/caf\xC3\xA9/100%25 done.txt\n";
  for (const fs::path& p : threeForms(b, "generic-fetch")) {
    const verify::Report r = run(p);
    INFO(p << "\n" << allText(r));
    CHECK(r.exitCode() == 0);
    CHECK_FALSE(failed(r, "bagit.fetch"));
    CHECK_FALSE(failed(r, "bagit.manifests"));
  }

  // A file still to be fetched: the bag is incomplete (exit 3), said once, by bagit.fetch.
  const fs::path dir = freshDir("generic-fetch-missing");
  b.write(dir / "bag");
  fs::remove(dir / "bag/data/test 1.txt");
  verify::Report r = run(dir / "bag");
  INFO(allText(r));
  CHECK(failed(r, "bagit.fetch"));
  CHECK_FALSE(failed(r, "bagit.complete"));
  CHECK_THAT(allText(r), Contains("data/test 1.txt: to be fetched from https://example.org/t1"));
  CHECK(r.exitCode() == 3);

  // Malformed lines and paths outside data/ are invalid.
  GenericBag bad = sample();
  bad.fetch = "http://example.org/x 12\n"
              "http://example.org/y twelve data/hello.txt\n"
              "http://example.org/z - ../etc/passwd\n"
              "http://example.org/w - bag-info.txt\n";
  const fs::path badDir = freshDir("generic-fetch-bad");
  bad.write(badDir / "bag");
  r = run(badDir / "bag");
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  const std::string text = allText(r);
  CHECK_THAT(text, Contains("fetch.txt: line 1"));
  CHECK_THAT(text, Contains("fetch.txt: line 2: length \"twelve\""));
  CHECK_THAT(text, Contains("would leave the bag"));
  CHECK_THAT(text, Contains("bag-info.txt is outside data/"));
  CHECK(r.exitCode() == 2);
}

TEST_CASE("invalid generic bags: an unknown algorithm, no manifest, a wrong Payload-Oxum",
          "[verify][generic]") {
  const fs::path dir = freshDir("generic-invalid");
  GenericBag b = sample();
  b.write(dir / "crc");
  writeText(dir / "crc/manifest-crc32.txt", "00000000  data/hello.txt\n");
  verify::Report r = run(dir / "crc");
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK_THAT(allText(r), Contains("\"crc32\" is not one this verifier accepts"));
  CHECK(r.exitCode() == 2);

  b.algorithms.clear();
  b.write(dir / "none");
  r = run(dir / "none");
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK(r.exitCode() == 2);

  b = sample();
  b.payloadOxum = false;
  b.bagInfo += "Payload-Oxum: 1.1\n";
  b.write(dir / "oxum");
  r = run(dir / "oxum");
  INFO(allText(r));
  CHECK(failed(r, "bagit.payload-oxum"));
  CHECK(r.exitCode() == 3);
  CHECK(onlyBagItChecks(r));
}

TEST_CASE("re-execution of a bag that is not a Surrogate package warns and re-runs nothing",
          "[verify][generic]") {
  const fs::path dir = freshDir("generic-reexecute");
  sample().write(dir / "bag");
  const verify::Report r = run(dir / "bag", true);
  INFO(allText(r));
  CHECK(r.exitCode() == 0);
  CHECK_FALSE(r.reexecuted);
  CHECK_THAT(r.warnings.back(), Contains("not re-executed"));
}

TEST_CASE("a Surrogate package's verdict has two parts", "[verify][generic]") {
  // Sound: both parts.
  fs::path bag = cleanBag("twoparts");
  verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.surrogatePackage);
  CHECK(r.bagitValid());
  CHECK(r.packageSound());

  // A valid bag whose METS is broken (tag manifests redone): BagIt valid, package not sound.
  writeText(bag / "metadata/mets.xml", "<mets/>\n");
  rehashTagManifests(bag);
  r = run(bag);
  INFO(allText(r));
  CHECK(r.bagitValid());
  CHECK_FALSE(r.packageSound());
  CHECK(r.exitCode() == 2);

  // A changed original: the bag is invalid, and so the package is not sound.
  bag = cleanBag("twoparts-fixity");
  writeText(bag / "data/original-captures/IMG_0001.jpg", "changed\n");
  r = run(bag);
  CHECK_FALSE(r.bagitValid());
  CHECK_FALSE(r.packageSound());
  CHECK(r.exitCode() == 3);

  // An md5 manifest added to a package: accepted by BagIt with a warning, but not a file
  // `surrogate pack` writes.
  bag = cleanBag("twoparts-md5");
  std::string manifest;
  for (const std::string& p : filesInWriteOrder(bag))
    if (p.compare(0, 5, "data/") == 0)
      manifest += hexDigest(readText(bag / p), DigestAlgorithm::Md5) + "  " + p + "\n";
  writeText(bag / "manifest-md5.txt", manifest);
  rehashTagManifests(bag);
  r = run(bag);
  INFO(allText(r));
  CHECK(r.bagitValid());
  CHECK_FALSE(r.warnings.empty());
  CHECK(failed(r, "package.bundled"));
  CHECK(r.exitCode() == 2);
}

namespace {

// Removes a payload file the way a careful forger would: its manifest lines go, Payload-Oxum is
// redone, bag-info loses the lines named in `dropInfo`, and the tag manifests are redone.
void removeConsistently(const fs::path& bag, const std::string& payloadPath,
                        const std::vector<std::string>& dropInfo) {
  const std::uint64_t size = fs::file_size(bag / payloadPath);
  fs::remove(bag / payloadPath);
  for (const char* manifest : {"manifest-sha256.txt", "manifest-sha512.txt"}) {
    std::string kept;
    for (const std::string& line : surrogate::archive::splitLines(readText(bag / manifest)))
      if (!line.empty() && line.find("  " + payloadPath) == std::string::npos) kept += line + "\n";
    writeText(bag / manifest, kept);
  }
  std::string info;
  for (const std::string& line : surrogate::archive::splitLines(readText(bag / "bag-info.txt"))) {
    if (line.empty()) continue;
    bool drop = false;
    for (const std::string& label : dropInfo) drop = drop || line.rfind(label + ":", 0) == 0;
    if (drop) continue;
    if (line.rfind("Payload-Oxum:", 0) == 0) {
      const std::string value = line.substr(line.find(':') + 1);
      const std::uint64_t octets = std::stoull(value.substr(0, value.find('.')));
      const std::uint64_t streams = std::stoull(value.substr(value.find('.') + 1));
      info += "Payload-Oxum: " + std::to_string(octets - size) + "." + std::to_string(streams - 1) + "\n";
    } else {
      info += line + "\n";
    }
  }
  writeText(bag / "bag-info.txt", info);
  rehashTagManifests(bag);
}

}  // namespace

TEST_CASE("a Surrogate package stripped of its carrier and its identifier is still judged as one "
          "and is not sound whatever mark of pack is left",
          "[verify][generic]") {
  // The carrier and the package identifier gone, consistently: metadata/ and the software agent
  // still say Surrogate made it.
  fs::path bag = cleanBag("stripped-carrier");
  removeConsistently(bag, "data/assembly-files/carrier.xml",
                     {"Surrogate-Package-Identifier", "Surrogate-Packaging-Time"});
  verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.bagitValid());
  CHECK(r.surrogatePackage);
  CHECK_FALSE(r.packageSound());
  CHECK(failed(r, "package.complete"));
  CHECK(r.exitCode() != 0);

  // Then metadata/ too: only "Bag-Software-Agent: Surrogate ..." is left.
  fs::remove_all(bag / "metadata");
  rehashTagManifests(bag);
  r = run(bag);
  INFO(allText(r));
  CHECK(r.bagitValid());
  CHECK(r.surrogatePackage);
  CHECK(failed(r, "package.complete"));
  CHECK(r.exitCode() != 0);
}
