// data/ro-crate-metadata.json: the payload folder is an RO-Crate 1.1 with the Process, Workflow
// and Provenance Run Crate profiles. Judged by tools that are not Surrogate's: Python's json,
// PyLD's JSON-LD expansion (Debian python3-pyld) with the RO-Crate contexts kept in
// tests/data/ro-crate, hashlib for each file's size and SHA-256, and xml.etree for the
// carrier's steps (tests/mapping/ro_crate_check.py).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "archive/package.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/error.h"
#include "mapping/mapping.h"
#include "sample_capture.h"
#include "test_files.h"

namespace fs = std::filesystem;
using namespace surrogate;
using testfiles::freshDir;
using testfiles::slurp;

namespace {

// Debian's interpreter, where scripts/install-deps puts python3-pyld (a python3 earlier in the
// PATH, e.g. pyenv's, would not have it).
std::string python() {
  std::error_code ec;
  return fs::exists("/usr/bin/python3", ec) ? "/usr/bin/python3" : "python3";
}

std::pair<int, std::string> check(const fs::path& bag) {
  const std::string source = SURROGATE_SOURCE_DIR;
  const std::string command = python() + " '" + source + "/tests/mapping/ro_crate_check.py' '" +
                              bag.string() + "' '" + source + "/tests/data/ro-crate' 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(command.c_str(), "r"), &pclose);
  REQUIRE(p);
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, p.get())) > 0) out.append(buffer, n);
  return {pclose(p.release()), out};
}

}  // namespace

TEST_CASE("the package's RO-Crate expands as JSON-LD with every file and every step",
          "[archive][package][ro-crate]") {
  const fs::path dir = freshDir("ro-crate");
  const fs::path capture = samplecapture::make(dir);
  const fs::path bag = dir / "pkg";
  const archive::PackResult packed = archive::packCapture(capture, bag);
  REQUIRE(fs::is_regular_file(bag / mapping::kRoCratePath));
  // In the payload manifests, like every payload file.
  CHECK(slurp(bag / "manifest-sha256.txt").find("  data/ro-crate-metadata.json\n") != std::string::npos);

  const auto [status, output] = check(bag);
  INFO(output);
  CHECK(status == 0);
  CHECK(output.rfind("ok: ", 0) == 0);

  const std::string crate = slurp(bag / mapping::kRoCratePath);
  CHECK(crate.find("\"identifier\": [\"" + packed.packageId + "\", \"" + packed.captureId + "\"]") != std::string::npos);
  CHECK(crate.find("\"datePublished\": \"" + packed.packagingTime + "\"") != std::string::npos);

  SECTION("the checker finds a crate that lost a file or a step") {
    std::string cut = crate;
    const std::string step = "\n        {\"@id\": \"#step-s1\"},";
    REQUIRE(cut.find(step) != std::string::npos);
    cut.erase(cut.find(step), step.size());
    std::ofstream(bag / mapping::kRoCratePath, std::ios::binary | std::ios::trunc) << cut;
    const auto [cutStatus, cutOutput] = check(bag);
    INFO(cutOutput);
    CHECK(cutStatus != 0);
    CHECK(cutOutput.find("step s1 is not a HowToStep of the workflow") != std::string::npos);
  }
}

TEST_CASE("a capture's own file where the RO-Crate goes is refused by pack, naming it",
          "[archive][package][ro-crate]") {
  const fs::path dir = freshDir("ro-crate-clash");
  const fs::path capture = samplecapture::make(dir);
  std::ofstream(capture / "ro-crate-metadata.json") << "{}\n";
  // Not in the carrier: refused as unrecorded first, so record it as the carrier would.
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  carrier::FileRecord f;
  f.path = "ro-crate-metadata.json";
  f.role = "other";
  f.format = "JSON";
  f.size = 3;
  f.sha256 = sha256Hex(slurp(capture / "ro-crate-metadata.json"));
  c.putFile(f);
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  try {
    (void)archive::packCapture(capture, dir / "pkg");
    FAIL("packed");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK_THAT(e.text(), Catch::Matchers::Contains("ro-crate-metadata.json") &&
                             Catch::Matchers::Contains("move it into a folder of the capture"));
  }
  CHECK_FALSE(fs::exists(dir / "pkg"));
}

namespace {

// The root's licence and the entity it names, read with nlohmann's JSON parser.
std::pair<std::string, nlohmann::json> rootLicence(const fs::path& bag) {
  const nlohmann::json crate = nlohmann::json::parse(slurp(bag / mapping::kRoCratePath));
  nlohmann::json root, named;
  for (const auto& e : crate["@graph"])
    if (e["@id"] == "./") root = e;
  REQUIRE(root.is_object());
  REQUIRE(root.contains("license"));
  const std::string id = root["license"]["@id"];
  for (const auto& e : crate["@graph"])
    if (e["@id"] == id) named = e;
  return {id, named};
}

}  // namespace

// Issue 56: RO-Crate 1.1 requires `license` on the root data entity (ro-crate-js reports
// "licenseRequired"); a capture recorded without --license or --rights has an entity that says
// no licence was stated.
TEST_CASE("the RO-Crate root always names a licence, the one given or one saying none was stated",
          "[archive][package][ro-crate]") {
  const fs::path dir = freshDir("ro-crate-licence");
  const fs::path capture = samplecapture::make(dir);
  (void)archive::packCapture(capture, dir / "none");
  const auto [noneId, none] = rootLicence(dir / "none");
  CHECK(noneId == "#no-licence-stated");
  REQUIRE(none.is_object());
  CHECK(none["@type"] == "CreativeWork");
  CHECK(none["name"] == "No licence stated");
  CHECK_THAT(none["description"].get<std::string>(), Catch::Matchers::Contains("ask the depositor"));
  {
    const auto [status, output] = check(dir / "none");
    INFO(output);
    CHECK(status == 0);
  }

  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  c.header.license = "https://creativecommons.org/licenses/by/4.0/";
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  (void)archive::packCapture(capture, dir / "given");
  const auto [givenId, given] = rootLicence(dir / "given");
  CHECK(givenId == "https://creativecommons.org/licenses/by/4.0/");
  REQUIRE(given.is_object());
  CHECK(given["name"] == "https://creativecommons.org/licenses/by/4.0/");
  CHECK(slurp(dir / "given" / mapping::kRoCratePath).find("no-licence-stated") == std::string::npos);
  const auto [status, output] = check(dir / "given");
  INFO(output);
  CHECK(status == 0);

  // The checker finds a root without a licence (as the crate of 9cd773a was).
  std::string crate = slurp(dir / "none" / mapping::kRoCratePath);
  const std::string ref = ",\n      \"license\": {\"@id\": \"#no-licence-stated\"}";
  REQUIRE(crate.find(ref) != std::string::npos);
  crate.erase(crate.find(ref), ref.size());
  std::ofstream(dir / "none" / mapping::kRoCratePath, std::ios::binary | std::ios::trunc) << crate;
  const auto [cutStatus, cutOutput] = check(dir / "none");
  INFO(cutOutput);
  CHECK(cutStatus != 0);
  CHECK(cutOutput.find("licenseRequired") != std::string::npos);
}
