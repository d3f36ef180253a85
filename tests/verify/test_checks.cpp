// Each check of the verifier fails for the problem it is about, with the right exit code.
#include <catch2/catch.hpp>

#include "bag_fixture.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "report_helpers.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace verify_test;
using Catch::Matchers::Contains;

TEST_CASE("a clean bag passes every check as a directory, tar, tar with a top folder and zip",
          "[verify][checks]") {
  const fs::path bag = cleanBag("clean");
  const fs::path dir = bag.parent_path();
  archiveDirectory(bag, dir / "bag.tar", "");
  archiveDirectory(bag, dir / "prefixed.tar", "stela/");
  archiveDirectory(bag, dir / "bag.zip", "");
  for (const fs::path& p : {bag, dir / "bag.tar", dir / "prefixed.tar", dir / "bag.zip"}) {
    const verify::Report r = run(p);
    INFO(p << "\n" << allText(r));
    CHECK(r.exitCode() == 0);
    CHECK(r.sound());
    CHECK(r.checks.size() >= 10);
  }
}

TEST_CASE("a changed payload byte fails fixity in both manifests (exit 3)", "[verify][checks]") {
  const fs::path bag = cleanBag("flip");
  std::string text = readText(bag / "data/original-captures/IMG_0001.jpg");
  text[3] ^= 0x01;
  writeText(bag / "data/original-captures/IMG_0001.jpg", text);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.fixity-sha256"));
  CHECK(failed(r, "bagit.fixity-sha512"));
  CHECK(failed(r, "carrier.files"));
  CHECK_THAT(allText(r), Contains("data/original-captures/IMG_0001.jpg"));
}

TEST_CASE("missing and unlisted payload files fail completeness (exit 3)", "[verify][checks]") {
  const fs::path bag = cleanBag("complete");
  fs::remove(bag / "data/original-captures/IMG_0002.jpg");
  verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.complete"));
  CHECK(failed(r, "bagit.payload-oxum"));

  const fs::path other = cleanBag("unlisted");
  writeText(other / "data/original-captures/extra.jpg", "smuggled\n");
  r = run(other);
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.complete"));
  CHECK_THAT(allText(r), Contains("not listed in manifest-sha256.txt"));
}

TEST_CASE("a tag file added after packaging fails completeness (exit 3)", "[verify][checks]") {
  // RFC 8493 lets a bag leave tag files out of its tag manifests: the bag stays valid, but a
  // Surrogate package lists every one, so the package is not sound.
  const fs::path bag = cleanBag("addtag");
  writeText(bag / "metadata/extra.xml", "<x/>\n");
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "package.tags-listed"));
  CHECK(r.bagitValid());
  CHECK_FALSE(r.packageSound());
  CHECK_THAT(allText(r), Contains("metadata/extra.xml"));
}

TEST_CASE("a changed tag file fails the tagmanifest (exit 3)", "[verify][checks]") {
  const fs::path bag = cleanBag("tag");
  replaceInFile(bag / "bag-info.txt", "Surrogate test", "Surrogate tesT");
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.tagfixity-sha256"));
}

TEST_CASE("a bag without bagit.txt or manifests is not a bag (exit 2), a Surrogate package "
          "without them is incomplete (exit 3)", "[verify][checks]") {
  // A plain BagIt bag (no carrier, no Surrogate identifier): without bagit.txt it is no bag.
  fs::path plain = freshDir("plain") / "bag";
  writeText(plain / "data/hello.txt", "hello\n");
  writeText(plain / "manifest-sha256.txt",
            sha256Hex("hello\n") + "  data/hello.txt\n");
  verify::Report r = run(plain);
  INFO(allText(r));
  CHECK(r.exitCode() == 2);
  CHECK(failed(r, "bagit.declaration"));
  CHECK_FALSE(failed(r, "package.complete"));

  fs::path bag = cleanBag("nodecl");
  fs::remove(bag / "bagit.txt");
  fs::remove(bag / "tagmanifest-sha256.txt");
  fs::remove(bag / "tagmanifest-sha512.txt");
  r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "bagit.declaration"));
  CHECK(failed(r, "package.complete"));
  CHECK_THAT(allText(r), Contains("tagmanifest-sha512.txt: missing"));

  bag = cleanBag("nomanifest");
  fs::remove(bag / "manifest-sha256.txt");
  fs::remove(bag / "manifest-sha512.txt");
  rehashTagManifests(bag);
  r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK(failed(r, "package.complete"));
  CHECK(r.exitCode() == 3);
}

TEST_CASE("manifest paths outside the bag or outside data/ are invalid", "[verify][checks]") {
  const fs::path bag = cleanBag("outside");
  const std::string h(64, '0');
  writeText(bag / "manifest-sha256.txt",
            readText(bag / "manifest-sha256.txt") + h + "  ../../etc/passwd\n" + h + "  bagit.txt\n");
  rehashTagManifests(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK(r.exitCode() == 2);
  CHECK_THAT(allText(r), Contains("would leave the bag"));
}

TEST_CASE("an unsupported algorithm and a malformed bag-info are invalid", "[verify][checks]") {
  const fs::path bag = cleanBag("crc32");
  writeText(bag / "manifest-crc32.txt", "00000000  data/original-captures/IMG_0001.jpg\n");
  writeText(bag / "bag-info.txt", readText(bag / "bag-info.txt") + "Payload-Oxum: 1.1\n");
  rehashTagManifests(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "bagit.manifests"));
  CHECK(failed(r, "bagit.info"));
  CHECK(r.exitCode() == 2);
}

TEST_CASE("a carrier whose hashes disagree with the bag fails carrier.files (exit 3)",
          "[verify][checks]") {
  // A file replaced and the manifests fixed: only the carrier still knows the old hash.
  const fs::path bag = cleanBag("carrierhash");
  writeText(bag / "data/original-captures/IMG_0002.jpg", "a different image\n");
  rehashBag(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK_FALSE(failed(r, "bagit.fixity-sha256"));
  CHECK(failed(r, "carrier.files"));
  CHECK(r.exitCode() == 3);
}

TEST_CASE("a payload file the carrier does not record fails carrier.files (exit 3)",
          "[verify][checks]") {
  const fs::path bag = cleanBag("carrierextra");
  writeText(bag / "data/original-captures/IMG_0003.jpg", "an image added later\n");
  rehashBag(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK_FALSE(failed(r, "bagit.complete"));
  CHECK(failed(r, "carrier.files"));
  CHECK_THAT(allText(r), Contains("not recorded in the carrier"));
  CHECK(r.exitCode() == 3);
}

TEST_CASE("a carrier naming an unsafe path is invalid and never re-executed", "[verify][checks]") {
  const fs::path bag = cleanBag("carrierpath");
  replaceInFile(bag / "data/assembly-files/carrier.xml", "path=\"original-captures/IMG_0002.jpg\"",
                "path=\"../../../etc/passwd\"");
  rehashBag(bag);
  verify::VerifyOptions options;
  options.reexecute = true;
  const verify::Report r = verify::verifyPackage(bag, options);
  INFO(allText(r));
  CHECK(failed(r, "carrier.paths"));
  CHECK(r.exitCode() == 2);
}

TEST_CASE("metadata that is missing or not well-formed fails the metadata checks", "[verify][checks]") {
  fs::path bag = cleanBag("metadata");
  writeText(bag / "metadata/crm.rdf", "<rdf:RDF");
  rehashTagManifests(bag);
  verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "metadata.crm"));
  CHECK(r.exitCode() == 2);

  bag = cleanBag("nomets");
  fs::remove(bag / "metadata/mets.xml");
  rehashTagManifests(bag);
  r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "metadata.mets"));
  CHECK(failed(r, "package.complete"));  // a package without its METS is incomplete
  CHECK(r.exitCode() == 3);
}

TEST_CASE("the report's exit code prefers fixity over invalid over not reproduced",
          "[verify][checks]") {
  verify::Report r;
  r.checks.push_back({"a", false, verify::Severity::NotReproduced, "", {}});
  CHECK(r.exitCode() == 4);
  r.checks.push_back({"b", false, verify::Severity::Invalid, "", {}});
  CHECK(r.exitCode() == 2);
  r.checks.push_back({"c", false, verify::Severity::Fixity, "", {}});
  CHECK(r.exitCode() == 3);
  CHECK(r.failures() == 3);
}
