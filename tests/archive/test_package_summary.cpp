// describePackage: what a package holds by role, with counts and sizes taken here from the file
// system (the capture that was packed, and the bag folder itself), not from the package reader.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>

#include "archive/package.h"
#include "archive/package_summary.h"
#include "sample_capture.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::archive;
using testfiles::freshDir;

namespace {

struct Tally {
  std::size_t files = 0;
  std::uint64_t bytes = 0;
};

// Every regular file under `folder`, counted with its size from the file system.
Tally tally(const fs::path& folder) {
  Tally t;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (e.is_regular_file()) t.files += 1, t.bytes += fs::file_size(e.path());
  return t;
}

const RoleTotal* role(const PackageSummary& s, const std::string& name) {
  for (const RoleTotal& r : s.roles)
    if (r.role == name) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("describePackage counts a Surrogate package's files by role, as the capture holds them",
          "[archive][summary]") {
  const fs::path dir = freshDir("summary");
  const fs::path capture = samplecapture::make(dir);
  packCapture(capture, dir / "pkg");
  const PackageSummary s = describePackage(dir / "pkg");
  CHECK(s.format == "directory");
  CHECK(s.surrogate);
  const Tally all = tally(dir / "pkg");
  CHECK(s.files == all.files);
  CHECK(s.bytes == all.bytes);
  // The originals (three DNG and a sidecar) and the exports, as in the capture folder.
  const Tally originals = tally(capture / "original-captures"), exports = tally(capture / "jpeg-exports");
  REQUIRE(role(s, "originals"));
  CHECK(role(s, "originals")->files == 4);
  CHECK(role(s, "originals")->files == originals.files);
  CHECK(role(s, "originals")->bytes == originals.bytes);
  REQUIRE(role(s, "exports"));
  CHECK(role(s, "exports")->files == 3);
  CHECK(role(s, "exports")->bytes == exports.bytes);
  REQUIRE(role(s, "carrier"));
  CHECK(role(s, "carrier")->bytes == fs::file_size(capture / "assembly-files/carrier.xml"));
  // The results: the model and the report, with their sizes.
  const std::vector<std::pair<std::string, std::uint64_t>> results = {
      {"finished-files/ptm-lrgb.ptm", 7000},
      {"finished-files/report.html", fs::file_size(capture / "finished-files/report.html")}};
  CHECK(s.results == results);
  CHECK(role(s, "payload") == nullptr);
  // The RO-Crate's metadata pack writes is named for what it is, not "other payload" (issue 56).
  REQUIRE(role(s, "RO-Crate metadata"));
  CHECK(role(s, "RO-Crate metadata")->files == 1);
  CHECK(role(s, "RO-Crate metadata")->bytes == fs::file_size(dir / "pkg/data/ro-crate-metadata.json"));
  CHECK(role(s, "other payload") == nullptr);
  // Roles in their fixed order: originals first, bag files last.
  REQUIRE(s.roles.size() >= 2);
  CHECK(s.roles.front().role == "originals");
  CHECK(s.roles.back().role == "bag files");
  CHECK(s.manifests == std::vector<std::string>{"manifest-sha256.txt", "manifest-sha512.txt"});
  REQUIRE(s.carrier);
  CHECK(s.carrier->header.title == "Stela 12 & <friends>");
  CHECK(s.carrierProblem.empty());
  CHECK_FALSE(s.bagInfoValue("surrogate-package-identifier").empty());
}

TEST_CASE("describePackage tells another tool's bag and a damaged carrier", "[archive][summary]") {
  const fs::path bag = freshDir("summary-other") / "bag";
  fs::create_directories(bag / "data");
  std::ofstream(bag / "data/a.txt") << "hello\n";
  std::ofstream(bag / "bagit.txt") << "BagIt-Version: 1.0\nTag-File-Character-Encoding: UTF-8\n";
  std::ofstream(bag / "bag-info.txt") << "Source-Organization: Elsewhere\nBagging-Date: 2020-01-01\n";
  std::ofstream(bag / "manifest-md5.txt") << "b1946ac92492d2347c6235b4d2611184  data/a.txt\n";
  const PackageSummary other = describePackage(bag);
  CHECK_FALSE(other.surrogate);
  CHECK(other.files == 4);
  REQUIRE(other.roles.size() == 2);
  CHECK(other.roles[0].role == "payload");
  CHECK(other.roles[0].files == 1);
  CHECK(other.roles[0].bytes == 6);
  CHECK(other.roles[1].role == "bag files");
  CHECK(other.roles[1].files == 3);
  CHECK(other.bagInfoValue("source-organization") == "Elsewhere");
  CHECK(other.bagInfo.size() == 2);
  CHECK(other.manifests == std::vector<std::string>{"manifest-md5.txt"});
  CHECK_FALSE(other.carrier);

  // A carrier that is not XML makes the bag a Surrogate package whose carrier cannot be read.
  fs::create_directories(bag / "data/assembly-files");
  std::ofstream(bag / "data/assembly-files/carrier.xml") << "not xml";
  const PackageSummary damaged = describePackage(bag);
  CHECK(damaged.surrogate);
  CHECK_FALSE(damaged.carrier);
  CHECK_FALSE(damaged.carrierProblem.empty());
}

TEST_CASE("packageRole follows the carrier's roles, then the package layout", "[archive][summary]") {
  const std::map<std::string, std::string> roles = {{"original-captures/a.dng", "original"},
                                                    {"original-captures/a.xmp", "sidecar"},
                                                    {"finished-files/x.ptm", "prior"},
                                                    {"notes.txt", "other"}};
  CHECK(packageRole("data/original-captures/a.dng", roles, true) == "originals");
  CHECK(packageRole("data/original-captures/a.xmp", roles, true) == "originals");
  CHECK(packageRole("data/finished-files/x.ptm", roles, true) == "prior work");
  CHECK(packageRole("data/notes.txt", roles, true) == "other payload");
  CHECK(packageRole("data/ro-crate-metadata.json", roles, true) == "RO-Crate metadata");
  CHECK(packageRole("data/assembly-files/carrier.xml", roles, true) == "carrier");
  CHECK(packageRole("data/jpeg-exports/b.jpg", roles, true) == "exports");
  CHECK(packageRole("data/finished-files/report.html", roles, true) == "results");
  CHECK(packageRole("metadata/mets.xml", roles, true) == "metadata");
  CHECK(packageRole("bag-info.txt", roles, true) == "bag files");
  CHECK(packageRole("data/original-captures/a.dng", roles, false) == "payload");
  CHECK(packageRole("metadata/mets.xml", roles, false) == "bag files");
}
