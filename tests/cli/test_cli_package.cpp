// `surrogate info PACKAGE` and `surrogate verify PACKAGE` as an archivist uses them: a packed
// capture as a folder, .tar and .zip, and bags other tools made.
#include <catch2/catch.hpp>

#include <regex>

#include "e2e_support.h"
#include "generic_bag.h"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// One capture with a decision (an excluded image), packed in the three forms.
struct Packed {
  fs::path folder, tar, zip;
};

const Packed& packed() {
  static const Packed p = [] {
    const fs::path work = e2e::freshDir("info-package");
    const fs::path capture = e2e::smallCapture(work);
    const e2e::CommandResult run =
        e2e::surrogate("run " + e2e::quote(capture) + " --quiet --operator \"Ana Silva\" "
                       "--exclude IMG_0008.dng --reason \"out of focus\"");
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    Packed out{work / "stela bag", work / "stela.tar", work / "stela.zip"};
    for (const fs::path& to : {out.folder, out.tar, out.zip}) {
      const e2e::CommandResult r =
          e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(to) + " --quiet");
      INFO(r.output);
      REQUIRE(r.exitCode == 0);
    }
    return out;
  }();
  return p;
}

}  // namespace

TEST_CASE("info describes a package as a folder, .tar and .zip: roles, who and when, steps, "
          "decisions, results, the command to verify it", "[cli][info]") {
  const Packed& p = packed();
  for (const fs::path& package : {p.folder, p.tar, p.zip}) {
    const e2e::CommandResult r = e2e::surrogate("info " + e2e::quote(package));
    INFO(package << "\n" << r.output);
    REQUIRE(r.exitCode == 0);
    CHECK_THAT(r.output, Contains(": Surrogate package ("));
    CHECK_THAT(r.output, Contains("identifier: urn:sha256:"));
    // The capture's identifier, from the SHA-256 of its first photograph (bag-info.txt).
    CHECK(std::regex_search(r.output, std::regex("\n  capture: +urn:surrogate:capture:[0-9a-f]{64}\n")));
    CHECK_THAT(r.output, Contains("by Surrogate "));
    for (const char* role : {"originals", "results", "assembly", "metadata", "bag files"})
      CHECK_THAT(r.output, Contains(std::string("    ") + role));
    CHECK_THAT(r.output, Contains("finished-files/") && Contains(".ptm"));
    CHECK_THAT(r.output, Contains("steps:"));
    CHECK_THAT(r.output, Contains("out of focus"));
    CHECK_THAT(r.output, Contains("Ana Silva"));
    CHECK_THAT(r.output, !Contains("has no original-captures") && !Contains("not an image"));

    // The command it gives runs, as given.
    std::smatch m;
    REQUIRE(std::regex_search(r.output, m, std::regex("\n    (surrogate verify [^\n]*)\n")));
    const std::string bin = fs::path(SURROGATE_EXE).parent_path().string();
    const e2e::CommandResult verify =
        e2e::runShell("PATH=" + e2e::quote(bin) + ":\"$PATH\" " + m[1].str());
    INFO(m[1].str() << "\n" << verify.output);
    CHECK(verify.exitCode == 0);
    CHECK_THAT(verify.output, Contains("BagIt: valid\nSurrogate package: sound\n"));

    const e2e::CommandResult json = e2e::surrogate("info " + e2e::quote(package) + " --json");
    INFO(json.output);
    CHECK(json.exitCode == 0);
    CHECK_THAT(json.output, Contains("\"kind\":\"package\"") && Contains("\"surrogatePackage\":true"));
    CHECK_THAT(json.output, Contains("{\"role\":\"originals\",\"files\":"));
    CHECK_THAT(json.output, Contains("\"carrier\":{\"kind\":\"carrier\""));
    CHECK_THAT(json.output, Contains("\"reason\":\"out of focus\""));
  }
}

TEST_CASE("verify gives a bag another tool made its BagIt verdict alone, in text and JSON",
          "[cli][verify]") {
  const fs::path work = e2e::freshDir("verify-generic");
  verify_test::GenericBag bag;
  bag.payload = {{"data/test 1.txt", "one\n"}, {"data/b.txt", "two\n"}};
  bag.encoding = "UTF-16";
  bag.fetch = "http://example.org/t - data/test 1.txt\n";
  bag.write(work / "bag");
  verify_test::archiveDirectory(work / "bag", work / "bag.zip", "");

  for (const fs::path& p : {work / "bag", work / "bag.zip"}) {
    e2e::CommandResult r = e2e::surrogate("verify " + e2e::quote(p));
    INFO(r.output);
    CHECK(r.exitCode == 0);
    CHECK_THAT(r.output, Contains("BagIt: valid\nSurrogate package: not a Surrogate package"));
    CHECK_THAT(r.output, Contains("Warnings:\n  manifest-md5.txt: md5 is accepted"));
    CHECK_THAT(r.output, Contains("VALID BAG"));
    CHECK_THAT(r.output, !Contains("carrier.") && !Contains("metadata."));

    r = e2e::surrogate("verify " + e2e::quote(p) + " --json");
    INFO(r.output);
    CHECK(r.exitCode == 0);
    CHECK_THAT(r.output, Contains("\"bagit\":{\"valid\":true,\"verdict\":\"valid\",\"failedChecks\":[]}"));
    CHECK_THAT(r.output, Contains("\"surrogatePackage\":{\"is\":false,\"sound\":null,"
                                  "\"verdict\":\"not a Surrogate package\""));
    CHECK_THAT(r.output, Contains("\"warnings\":[\"manifest-md5.txt: md5"));

    r = e2e::surrogate("info " + e2e::quote(p));
    INFO(r.output);
    CHECK(r.exitCode == 0);
    CHECK_THAT(r.output, Contains("BagIt bag, not a Surrogate package"));
    CHECK_THAT(r.output, Contains("Source-Organization: Library of Congress"));
    CHECK_THAT(r.output, Contains("surrogate verify "));
  }

  verify_test::writeText(work / "bag/data/b.txt", "changed\n");
  const e2e::CommandResult r = e2e::surrogate("verify " + e2e::quote(work / "bag"));
  INFO(r.output);
  CHECK(r.exitCode == 3);
  CHECK_THAT(r.output, Contains("BagIt: invalid ("));
  CHECK_THAT(r.output, Contains("NOT VALID (fixity failure, exit 3)"));
}
