// The Library of Congress BagIt conformance suite (tests/data/bagit-conformance, SOURCE.md):
// every bag of it verified, each judged by the suite's own folders. valid: exit 0; invalid
// (and the invalid bags of linux-only and windows-only, which are invalid here too): refused,
// with the exit code docs/package.md gives (3 a file missing, changed or to be fetched, 2 a
// malformed bag); warning: what this verifier does with each, and why, below.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>

#include "report_helpers.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace verify_test;
using Catch::Matchers::Contains;

namespace {

const fs::path kSuite = fs::path(SURROGATE_SOURCE_DIR) / "tests/data/bagit-conformance";

// Every bag that is not in a "valid" folder, by "version/folder/bag": its exit code. Several
// invalid bags were made by editing one file of a valid bag without redoing the tag manifests,
// so they fail tag fixity too, and fixity (3) comes before invalid (2).
const std::map<std::string, int>& expectedOutcomes() {
  static const std::map<std::string, int> outcomes = {
      {"v0.97/invalid/baginfo-missing-encoding", 3},  // bagit.txt of one line; tag fixity
      {"v0.97/invalid/bom-in-bagit.txt", 2},
      {"v0.97/invalid/corrupt-data-file", 3},
      {"v0.97/invalid/corrupt-tag-file", 3},
      {"v0.97/invalid/extra-file-in-bag", 3},
      {"v0.97/invalid/invalid-version-number", 3},  // ".97"; tag fixity
      {"v0.97/invalid/missing-baginfo", 3},         // listed in the tag manifest, absent
      {"v0.97/invalid/missing-bagit.txt", 3},
      {"v0.97/invalid/out-of-scope-file-paths-using-dot-notation", 2},
      {"v0.97/invalid/out-of-scope-file-paths-using-dot-notation-for-fetch", 2},
      {"v0.97/invalid/same-filename-listed-twice-with-different-hashes", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-absolute-path", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-absolute-path-for-fetch", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-shortcut", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-shortcut-for-fetch", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-shortcut-username", 2},
      {"v0.97/linux-only/out-of-scope-file-paths-using-shortcut-username-for-fetch", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-absolute-path", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-absolute-path-for-fetch", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-shortcut", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-shortcut-for-fetch", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-unc", 2},
      {"v0.97/windows-only/out-of-scope-file-paths-using-unc-for-fetch", 2},
      // warning: valid, with a warning (md5sum's '*'; a 0.97 repeat), or valid as the suite's
      // valid bag-with-leading-dot-slash-in-manifest ("./data/hello.txt")...
      {"v0.97/warning/made-with-md5sum-tools", 0},
      {"v0.97/warning/same-filename-listed-twice-with-the-same-hash", 0},
      {"v0.97/warning/relative-path", 0},
      // ... or incomplete: the manifest lists a file the bag does not hold (data/HELLO.txt
      // beside data/hello.txt; data/Núñez decomposed beside it composed; data/.DS_Store).
      {"v0.97/warning/duplicate-file-with-different-case", 3},
      {"v0.97/warning/same-filename-listed-twice-with-different-normalization", 3},
      {"v0.97/warning/special-system-files", 3},
      {"v1.0/invalid/bagit-with-invalid-whitespace", 2},
      {"v1.0/invalid/notAllManifestsListAllFiles", 3},
      {"v1.0/invalid/same-filename-listed-twice-with-different-hashes", 3},
      {"v1.0/invalid/same-filename-listed-twice-with-the-same-hash", 3},  // tag fixity too
  };
  return outcomes;
}

bool anyWarningContains(const verify::Report& r, const std::string& text) {
  return std::any_of(r.warnings.begin(), r.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

std::string warningsText(const verify::Report& r) {
  std::string s;
  for (const std::string& w : r.warnings) s += "warning: " + w + "\n";
  return s;
}

}  // namespace

TEST_CASE("the Library of Congress BagIt conformance suite: every valid bag passes, every "
          "invalid bag is refused", "[verify][generic][conformance]") {
  REQUIRE(fs::is_directory(kSuite));
  std::map<std::string, int> seen;
  std::size_t valid = 0;
  for (const auto& version : fs::directory_iterator(kSuite)) {
    if (!version.is_directory()) continue;
    for (const auto& folder : fs::directory_iterator(version.path())) {
      if (!folder.is_directory()) continue;
      const std::string category = folder.path().filename().string();
      for (const auto& bag : fs::directory_iterator(folder.path())) {
        if (!bag.is_directory()) continue;
        const std::string name = version.path().filename().string() + "/" + category + "/" +
                                 bag.path().filename().string();
        const verify::Report r = run(bag.path());
        INFO(name << "\n" << allText(r) << warningsText(r));
        CHECK_FALSE(r.surrogatePackage);
        if (category == "valid") {
          ++valid;
          CHECK(r.exitCode() == 0);
          CHECK(r.bagitValid());
          continue;
        }
        seen[name] = r.exitCode();
        const auto expected = expectedOutcomes().find(name);
        REQUIRE(expected != expectedOutcomes().end());  // a bag the table does not know
        CHECK(r.exitCode() == expected->second);
        if (category != "warning") {
          CHECK(r.exitCode() != 0);
          CHECK_FALSE(r.bagitValid());
        }
      }
    }
  }
  // The whole suite was there: its 6 versions' valid bags and every other bag of the table.
  CHECK(valid == 27);
  CHECK(seen.size() == expectedOutcomes().size());
}

TEST_CASE("the four conformance bags bagit-python accepts and this verifier once refused pass "
          "with a warning each", "[verify][generic][conformance]") {
  SECTION("sha224 manifests and whitespace around a bag-info label") {
    const verify::Report r = run(kSuite / "v0.97/valid/uncommon-metadata-separators");
    INFO(allText(r) << warningsText(r));
    CHECK(r.exitCode() == 0);
    CHECK_FALSE(failed(r, "bagit.fixity-sha224"));
    CHECK(anyWarningContains(r, "Test-Tag"));
  }
  SECTION("a manifest written by md5sum, '*' before each path") {
    const verify::Report r = run(kSuite / "v0.97/warning/made-with-md5sum-tools");
    INFO(allText(r) << warningsText(r));
    CHECK(r.exitCode() == 0);
    CHECK(anyWarningContains(r, "binary-mode marker"));
  }
  SECTION("a 0.97 manifest listing a file twice with the same checksum") {
    const verify::Report r = run(kSuite / "v0.97/warning/same-filename-listed-twice-with-the-same-hash");
    INFO(allText(r) << warningsText(r));
    CHECK(r.exitCode() == 0);
    CHECK(anyWarningContains(r, "listed again with the same checksum"));
    // The same manifests in a 1.0 bag: RFC 8493 does not allow it.
    const verify::Report strict = run(kSuite / "v1.0/invalid/same-filename-listed-twice-with-the-same-hash");
    CHECK(strict.exitCode() != 0);
    CHECK(failed(strict, "bagit.manifests"));
    CHECK_THAT(allText(strict), Contains("invalid in BagIt 1.0"));
  }
  SECTION("Bagging-Date given twice") {
    const verify::Report r = run(kSuite / "v0.97/valid/duplicate-metadata-entries");
    INFO(allText(r) << warningsText(r));
    CHECK(r.exitCode() == 0);
    CHECK(anyWarningContains(r, "Bagging-Date is repeated"));
  }
}

TEST_CASE("a Surrogate package gets none of that latitude: it is held to what pack writes",
          "[verify][conformance]") {
  const fs::path bag = cleanBag("conformance-latitude");
  std::string manifest = readText(bag / "manifest-sha256.txt");
  for (std::size_t at = manifest.find("  data/"); at != std::string::npos;
       at = manifest.find("  data/", at))
    manifest.replace(at, 2, " *");
  writeText(bag / "manifest-sha256.txt", manifest);
  std::string info = readText(bag / "bag-info.txt");
  const std::size_t date = info.find("Bagging-Date: ");
  REQUIRE(date != std::string::npos);
  info.insert(date, info.substr(date, info.find('\n', date) + 1 - date));
  writeText(bag / "bag-info.txt", info);
  writeText(bag / "manifest-sha224.txt", "");
  rehashTagManifests(bag);
  const verify::Report r = run(bag);
  INFO(allText(r) << warningsText(r));
  CHECK(r.surrogatePackage);
  CHECK(failed(r, "bagit.manifests"));
  CHECK_THAT(allText(r), Contains("binary-mode marker") && Contains("manifest-sha224.txt"));
  CHECK(failed(r, "bagit.info"));
  CHECK_THAT(allText(r), Contains("Bagging-Date is repeated"));
  CHECK(r.exitCode() == 2);
}
