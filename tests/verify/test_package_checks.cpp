// A package is sound only if it is complete and is what `surrogate pack` wrote: every cut of a
// bag (file by file, or an archive cut anywhere) fails, the bundled resources must be this
// verifier's, bag-info.txt must agree with the carrier, every recorded step must be runnable,
// and temporary folders go whatever is left in them. On the tiny bag (fast); the packed bags
// of a real run are in test_fault_injection.cpp.
#include <sys/stat.h>

#include <fstream>

#include <catch2/catch.hpp>

#include "bag_fixture.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "mapping/mapping.h"
#include "pipeline/stage.h"
#include "stages/registry.h"
#include "report_helpers.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace verify_test;
using Catch::Matchers::Contains;

namespace {

bool has(const verify::Report& r, const std::string& name) {
  for (const verify::Check& c : r.checks)
    if (c.name == name) return true;
  return false;
}

std::string stageVersion(const std::string& component) {
  stages::registerBuiltinStages();
  return pipeline::StageRegistry::instance().create(component)->version();
}

// The tiny capture's carrier with `steps` added, as a bag (hashes and metadata consistent).
fs::path bagWithSteps(const std::string& name, const std::function<void(carrier::Carrier&)>& steps) {
  const fs::path dir = freshDir(name);
  const fs::path capture = tinyCapture(dir);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  steps(c);
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  makeBag(capture, dir / "bag");
  return dir / "bag";
}

}  // namespace

TEST_CASE("the tiny bag is a whole Surrogate package", "[verify][package]") {
  const verify::Report r = run(cleanBag("whole"));
  INFO(allText(r));
  CHECK(r.exitCode() == 0);
  for (const char* name : {"package.complete", "package.bundled", "package.info", "carrier.steps"})
    CHECK(has(r, name));
}

TEST_CASE("every prefix of a bag, cut file by file in the order pack writes, fails",
          "[verify][package]") {
  const fs::path bag = cleanBag("prefixes");
  const std::vector<std::string> files = filesInWriteOrder(bag);
  REQUIRE(files.size() > 15);
  const fs::path cut = freshDir("prefix") / "bag";
  fs::create_directories(cut);
  for (std::size_t k = 0; k < files.size(); ++k) {
    // The prefix of k files.
    const verify::Report r = run(cut);
    INFO("first " << k << " files, next " << files[k] << "\n" << allText(r));
    CHECK(r.exitCode() == (k == 0 ? 2 : 3));
    if (k > 0) CHECK(failed(r, "package.complete"));
    fs::create_directories((cut / files[k]).parent_path());
    fs::copy_file(bag / files[k], cut / files[k]);
  }
  const verify::Report whole = run(cut);
  INFO(allText(whole));
  CHECK(whole.exitCode() == 0);
}

TEST_CASE("deleted tag manifests make a package incomplete (exit 3)", "[verify][package]") {
  for (const char* removed : {"tagmanifest-sha256.txt", "tagmanifest-sha512.txt"}) {
    const fs::path bag = cleanBag("notagmanifest");
    fs::remove(bag / removed);
    const verify::Report r = run(bag);
    INFO(removed << "\n" << allText(r));
    CHECK(r.exitCode() == 3);
    CHECK(failed(r, "package.complete"));
    CHECK_THAT(allText(r), Contains(std::string(removed) + ": missing"));
  }
  const fs::path bag = cleanBag("notagmanifests");
  fs::remove(bag / "tagmanifest-sha256.txt");
  fs::remove(bag / "tagmanifest-sha512.txt");
  CHECK(run(bag).exitCode() == 3);
}

TEST_CASE("a tag manifest must cover every tag file", "[verify][package]") {
  const fs::path bag = cleanBag("uncovered");
  std::string t = readText(bag / "tagmanifest-sha256.txt");
  const auto at = t.find("metadata/xsd/carrier.xsd");
  REQUIRE(at != std::string::npos);
  const auto start = t.rfind('\n', at);
  t.erase(start + 1, t.find('\n', at) - start);
  writeText(bag / "tagmanifest-sha256.txt", t);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 3);
  CHECK(failed(r, "package.tags-listed"));
  CHECK_THAT(allText(r), Contains("metadata/xsd/carrier.xsd: a tag file not listed in tagmanifest-sha256.txt"));
}

TEST_CASE("bundled schemas, stylesheets and tables must be this verifier's (exit 2)",
          "[verify][package]") {
  SECTION("an emptied carrier.xsd") {
    const fs::path bag = cleanBag("emptyxsd");
    writeText(bag / "metadata/xsd/carrier.xsd", "");
    rehashTagManifests(bag);
    const verify::Report r = run(bag);
    INFO(allText(r));
    CHECK(r.exitCode() == 2);
    CHECK(failed(r, "package.bundled"));
    CHECK_THAT(allText(r), Contains("metadata/xsd/carrier.xsd: differs from the carrier.xsd this verifier bundles"));
  }
  SECTION("a garbage stylesheet") {
    const fs::path bag = cleanBag("garbagexsl");
    writeText(bag / "metadata/xslt/carrier-to-mets.xsl", "<not a stylesheet");
    rehashTagManifests(bag);
    const verify::Report r = run(bag);
    INFO(allText(r));
    CHECK(r.exitCode() == 2);
    CHECK_THAT(allText(r), Contains("metadata/xslt/carrier-to-mets.xsl: differs"));
  }
  SECTION("a table of another version says so") {
    const fs::path bag = cleanBag("otherversion");
    writeText(bag / "metadata/mappings/carrier-to-crm.md", "# an older table\n");
    replaceInFile(bag / "bag-info.txt", "Bag-Software-Agent: Surrogate test", "Bag-Software-Agent: Surrogate 0.0.9");
    rehashTagManifests(bag);
    const verify::Report r = run(bag);
    INFO(allText(r));
    CHECK(r.exitCode() == 2);
    CHECK_THAT(allText(r), Contains("made by Surrogate 0.0.9"));
    CHECK_THAT(allText(r), Contains("verify it with Surrogate 0.0.9"));
  }
  SECTION("another file in metadata/") {
    const fs::path bag = cleanBag("extratag");
    writeText(bag / "metadata/xsd/extra.xsd", "<schema/>\n");
    rehashTagManifests(bag);
    const verify::Report r = run(bag);
    INFO(allText(r));
    CHECK(r.exitCode() == 2);
    CHECK_THAT(allText(r), Contains("metadata/xsd/extra.xsd: not a file `surrogate pack` writes"));
  }
}

TEST_CASE("bag-info.txt that disagrees with the carrier is invalid, a wrong Payload-Oxum a "
          "fixity failure", "[verify][package]") {
  struct Forgery {
    const char* what;
    std::string from, to;
    int exit;
    const char* check;
    const char* text;
  };
  // "line:LABEL" stands for the whole line of that label in the bag being forged (the
  // identifier depends on the carrier, whose creation time differs from bag to bag).
  const auto line = [](const std::string& info, const std::string& label) {
    const auto at = info.find(label + ": ");
    REQUIRE(at != std::string::npos);
    return info.substr(at, info.find('\n', at) - at);
  };
  const std::string oxum = "line:Payload-Oxum", id = "line:Surrogate-Package-Identifier";
  const std::vector<Forgery> forgeries = {
      {"External-Description edited", "Highlight-RTI capture: Tiny", "Highlight-RTI capture: Stela 9", 2,
       "package.info", "External-Description is \"Highlight-RTI capture: Stela 9\""},
      {"a Surrogate-* label added", "Bagging-Date", "Surrogate-Verified: yes\nBagging-Date", 2,
       "package.info", "Surrogate-Verified is a Surrogate-* label that packing the carrier does not give"},
      {"External-Description removed", "line:External-Description", "", 2, "package.info",
       "External-Description is missing"},
      {"External-Description given again by a holder", "line:External-Description",
       "External-Description: Highlight-RTI capture: Tiny\nExternal-Description: a holder's", 2,
       "package.info", "External-Description is given 2 times"},
      {"a malformed Bag-Count added", "Bagging-Date", "Bag-Count: 3 of 2\nBagging-Date", 2, "package.info",
       "Bag-Count \"3 of 2\" is not \"N of T\""},
      {"the identifier forged", id, "Surrogate-Package-Identifier: urn:sha256:" + std::string(64, '0'), 2,
       "package.info", "the carrier in the package gives urn:sha256:"},
      {"the identifier given twice", id, "", 2, "package.info", "given 2 times"},
      {"Bag-Size forged", "Bag-Size: ", "Bag-Size: 9", 2, "package.info", "Bag-Size is"},
      {"Bagging-Date forged", "Bagging-Date: 2026-11-25", "Bagging-Date: 2026-11-24", 2, "package.info",
       "is not the day of"},
      {"the agent is not Surrogate", "Bag-Software-Agent: Surrogate test", "Bag-Software-Agent: bagit.py", 2,
       "package.info", "not Surrogate"},
      {"Payload-Oxum forged", oxum, "Payload-Oxum: 1.2", 3, "bagit.payload-oxum", "Payload-Oxum says 1.2"},
  };
  for (const Forgery& f : forgeries) {
    const fs::path bag = cleanBag("forged");
    std::string from = f.from, to = f.to;
    if (from.compare(0, 5, "line:") == 0) {
      from = line(readText(bag / "bag-info.txt"), from.substr(5));
      if (to.empty()) to = std::string(f.what).find("removed") != std::string::npos ? "" : from + "\n" + from;
      if (to.empty()) from += "\n";
    }
    replaceInFile(bag / "bag-info.txt", from, to);
    rehashTagManifests(bag);  // the forger redid the tag manifests
    const verify::Report r = run(bag);
    INFO(f.what << "\n" << allText(r));
    CHECK(r.exitCode() == f.exit);
    CHECK(failed(r, f.check));
    CHECK_THAT(allText(r), Contains(f.text));
  }
}

TEST_CASE("bag-info fields a holder adds are listed as the holder's, the tag manifests still the "
          "authority", "[verify][package]") {
  // RFC 8493 lets the holder of a bag add fields; the fields Surrogate wrote stay as they were.
  const fs::path bag = cleanBag("holder");
  writeText(bag / "bag-info.txt", readText(bag / "bag-info.txt") +
                                      "Internal-Sender-Identifier: accession 2026/17\n"
                                      "External-Identifier: ark:/12345/x9\n"
                                      "Contact-Name: A. Archivist\n"
                                      "Contact-Name: B. Archivist\n"
                                      "Bag-Count: 1 of ?\n");
  {
    // Without the tag manifests redone, the edit is a fixity failure, whatever it added.
    const verify::Report r = run(bag);
    INFO(allText(r));
    CHECK(r.exitCode() == 3);
    CHECK(failed(r, "bagit.tagfixity-sha256"));
  }
  rehashTagManifests(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(r.exitCode() == 0);
  CHECK_FALSE(failed(r, "package.info"));
  using Field = std::pair<std::string, std::string>;
  CHECK(r.holderFields == std::vector<Field>{{"Internal-Sender-Identifier", "accession 2026/17"},
                                             {"External-Identifier", "ark:/12345/x9"},
                                             {"Contact-Name", "A. Archivist"},
                                             {"Contact-Name", "B. Archivist"},
                                             {"Bag-Count", "1 of ?"}});
  CHECK_THAT(allText(r), Contains("5 more added by the holder"));

  // A bag as packed has none.
  CHECK(run(cleanBag("holder-none")).holderFields.empty());
}

TEST_CASE("carriers whose steps cannot run are invalid (exit 2), and never re-executed",
          "[verify][package]") {
  struct Case {
    const char* what;
    std::function<void(carrier::Carrier&)> steps;
    const char* text;
  };
  const std::vector<Case> cases = {
      {"a NaN threshold",
       [](carrier::Carrier& c) {
         c.addStep("HighlightDetection", stageVersion("HighlightDetection")).setParam("threshold", "nan");
       },
       "threshold"},
      {"an unknown component",
       [](carrier::Carrier& c) { c.addStep("MagicFix", "1"); }, "step s1 (MagicFix): no stage of this build"},
      {"a version this build does not have",
       [](carrier::Carrier& c) { c.addStep("LightDirections", "99"); }, "version 99 is recorded"},
      {"an output path escaping the capture",
       [](carrier::Carrier& c) {
         carrier::Step& s = c.addStep("RtiFit", stageVersion("RtiFit"));
         s.setParam("basis", "ptm-lrgb");
         s.setParam("output", "finished-files/../../evil.ptm");
       },
       "output=finished-files/../../evil.ptm"},
      {"an unknown parameter",
       [](carrier::Carrier& c) { c.addStep("LightDirections", stageVersion("LightDirections")).setParam("speed", "11"); },
       "parameter speed=11 is not one LightDirections takes"},
      {"an unknown raw setting",
       [](carrier::Carrier& c) { c.addStep("ImageDecode", stageVersion("ImageDecode")).setParam("sharpen", "yes"); },
       "sharpen"},
      {"a manual sphere that is not a circle",
       [](carrier::Carrier& c) {
         carrier::Step& s = c.addStep("SphereDetection", stageVersion("SphereDetection"));
         s.interventions.push_back({"manual-sphere", "0", "10,10,nan", "A. Tester", "2026-11-25T08:00:00Z", "by eye"});
       },
       "intervention manual-sphere 0"},
      {"maps of a model no step fits",
       [](carrier::Carrier& c) { c.addStep("DerivedMaps", stageVersion("DerivedMaps")).setParam("model", "hsh3"); },
       "model=hsh3 names a model no earlier RtiFit or LearnedFit step fits"},
  };
  for (const Case& k : cases) {
    const fs::path bag = bagWithSteps("steps", k.steps);
    for (const bool reexecute : {false, true}) {
      const verify::Report r = run(bag, reexecute);
      INFO(k.what << (reexecute ? " (--reexecute)" : "") << "\n" << allText(r));
      CHECK(r.exitCode() == 2);
      CHECK(failed(r, "carrier.steps"));
      CHECK_THAT(allText(r), Contains(k.text));
      if (reexecute) {
        CHECK_THAT(allText(r), Contains("not re-executed: the carrier records steps this build cannot run"));
        CHECK_FALSE(r.reexecuted);
      }
    }
  }
  // Valid steps pass the check (they are not run by plain verify).
  const fs::path valid = bagWithSteps("validsteps", [](carrier::Carrier& c) {
    c.addStep("HighlightDetection", stageVersion("HighlightDetection")).setParam("threshold", "0.8");
    carrier::Step& fit = c.addStep("RtiFit", stageVersion("RtiFit"));
    fit.setParam("basis", "hsh2");
    fit.setParam("output", "finished-files/hsh2.rti");
    c.addStep("DerivedMaps", stageVersion("DerivedMaps")).setParam("model", "hsh2");
  });
  const verify::Report r = run(valid);
  INFO(allText(r));
  CHECK(r.exitCode() == 0);
}

TEST_CASE("a tar or zip cut at any entry boundary, or with data after its end, fails (exit 3)",
          "[verify][package]") {
  const fs::path bag = cleanBag("archives");
  const fs::path dir = bag.parent_path();
  archiveDirectory(bag, dir / "whole.tar", "bag/");
  archiveDirectory(bag, dir / "whole.zip", "bag/");
  for (const char* name : {"whole.tar", "whole.zip"}) {
    const verify::Report r = run(dir / name);
    INFO(name << "\n" << allText(r));
    REQUIRE(r.exitCode() == 0);
  }
  const std::string tar = readText(dir / "whole.tar"), zip = readText(dir / "whole.zip");
  std::vector<std::pair<std::string, std::uint64_t>> cuts;
  for (const std::uint64_t at : tarEntryOffsets(tar)) {
    // (Fewer than 512 bytes are no recognisable tar at all: not a package, exit 2.)
    if (at > 0) cuts.push_back({"cut.tar", at});          // at an entry boundary
    if (at > 0) cuts.push_back({"cut.tar", at + 100});    // inside a header
    if (at + 1024 < tar.size()) cuts.push_back({"cut.tar", at + 700});  // inside data or marker
  }
  const std::uint64_t end = tarEntryOffsets(tar).back();
  cuts.push_back({"cut.tar", end + 512});   // half the end-of-archive marker
  cuts.push_back({"cut.tar", end + 1100});  // inside a block after the marker
  for (const std::uint64_t at : zipEntryOffsets(zip)) {
    if (at > 0) cuts.push_back({"cut.zip", at});
    cuts.push_back({"cut.zip", at + 10});
  }
  cuts.push_back({"cut.zip", zip.size() - 1});
  for (const auto& [name, at] : cuts) {
    const std::string& whole = name == "cut.tar" ? tar : zip;
    if (at >= whole.size()) continue;
    writeText(dir / name, whole.substr(0, at));
    const verify::Report r = run(dir / name);
    INFO(name << " cut at byte " << at << " of " << whole.size() << "\n" << allText(r));
    CHECK(r.exitCode() == 3);
    CHECK(failed(r, "package.read"));
  }

  // Data after the end: a second archive, or anything.
  for (const auto& [name, whole, extra] :
       {std::tuple<std::string, std::string, std::string>{"more.tar", tar, tar},
        {"more.tar", tar, "x"},
        {"more.zip", zip, zip},
        {"more.zip", zip, std::string(3, '\0')}}) {
    writeText(dir / name, whole + extra);
    const verify::Report r = run(dir / name);
    INFO(name << " + " << extra.size() << " bytes\n" << allText(r));
    CHECK(r.exitCode() == 3);
    CHECK_THAT(allText(r), Contains("data follow the end of the archive"));
  }
  // Whole blocks of zeros after the end of a tar are padding, as tar writers add.
  writeText(dir / "padded.tar", tar + std::string(10240, '\0'));
  const verify::Report padded = run(dir / "padded.tar");
  INFO(allText(padded));
  CHECK(padded.exitCode() == 0);
}

TEST_CASE("a temporary folder is removed whatever permissions are left in it", "[verify][package]") {
  fs::path where;
  {
    TempDir temp("test");
    where = temp.path();
    fs::create_directories(where / "a/b/c");
    writeText(where / "a/b/c/file.txt", "x");
    writeText(where / "a/top.txt", "y");
    ::chmod((where / "a/b/c/file.txt").c_str(), 0400);
    ::chmod((where / "a/b/c").c_str(), 0500);
    ::chmod((where / "a/b").c_str(), 0000);
    ::chmod((where / "a").c_str(), 0500);
    fs::create_symlink("/etc", where / "link");
  }
  CHECK_FALSE(fs::exists(where));
  CHECK(fs::exists("/etc/passwd"));  // links are removed, never followed
  // An exception on the way out removes it too.
  try {
    TempDir temp("test");
    where = temp.path();
    fs::create_directories(where / "replay");
    ::chmod((where / "replay").c_str(), 0500);
    throw Error(ErrorKind::Input, "x", "test", "a step failed");
  } catch (const Error&) {
  }
  CHECK_FALSE(fs::exists(where));
}

TEST_CASE("the streaming METS validator agrees with the document validator, and checks IDs",
          "[verify][package]") {
  const fs::path bag = cleanBag("streaming");
  const std::string mets = readText(bag / "metadata/mets.xml");
  auto streamed = [](const std::string& text) -> std::string {
    try {
      mapping::MetsValidator v("mets.xml");
      for (std::size_t at = 0; at < text.size(); at += 997) v.feed(text.data() + at, std::min<std::size_t>(997, text.size() - at));
      v.finish();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  auto whole = [](const std::string& text) -> std::string {
    try {
      mapping::validateMets(text, "mets.xml");
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  CHECK(streamed(mets).empty());
  CHECK(whole(mets).empty());
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string t = mets;
    const auto at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
    return t;
  };
  for (const std::string& bad : {edited("CHECKSUMTYPE=\"SHA-256\"", "CHECKSUMTYPE=\"SHA-257\""),
                                 edited("<premis:size>", "<premis:sighs>"),
                                 edited("</mets:mets>", "</mets:met>"), mets.substr(0, mets.size() / 2)}) {
    CHECK_FALSE(whole(bad).empty());
    CHECK_THAT(streamed(bad), Contains("does not conform to mets-premis.xsd (line "));
  }
  // xs:ID and xs:IDREF, which libxml2 checks on a document tree only.
  CHECK_THAT(streamed(edited("ID=\"file-f2\"", "ID=\"file-f1\"")), Contains("'file-f1' is not unique"));
  CHECK_THAT(streamed(edited("ADMID=\"amd-f2\"", "ADMID=\"amd-f2 amd-0\"")),
             Contains("'amd-0' refers to no ID"));
}

TEST_CASE("a tar with pax extended headers (long names) is read whole, and cut, is not",
          "[verify][package]") {
  const fs::path bag = cleanBag("pax");
  const std::string longName = "data/original-captures/" + std::string(150, 'n') + ".txt";
  writeText(bag / longName, "a file whose name needs a pax header\n");
  const fs::path dir = bag.parent_path();
  archiveDirectory(bag, dir / "pax.tar", "");
  const std::string tar = readText(dir / "pax.tar");
  REQUIRE(tar.find("path=" + longName) != std::string::npos);  // a pax 'x' header
  verify::Report r = run(dir / "pax.tar");
  INFO(allText(r));
  CHECK_FALSE(failed(r, "package.read"));
  for (const std::uint64_t at : tarEntryOffsets(tar)) {
    if (at == 0) continue;
    writeText(dir / "cut.tar", tar.substr(0, at));
    r = run(dir / "cut.tar");
    INFO("cut at " << at << "\n" << allText(r));
    CHECK(failed(r, "package.read"));
  }
}

TEST_CASE("a README.txt that says what the carrier does not fails, tag manifests redone or not",
          "[verify][package][readme]") {
  const fs::path bag = cleanBag("readme-forged");
  // Who made it, rewritten, and the tag manifests redone to match.
  replaceInFile(bag / "README.txt", "A. Tester (creator)", "B. Forger (creator)");
  rehashTagManifests(bag);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "package.readme"));
  CHECK_THAT(allText(r), Contains("derived \"  Made by:") && Contains("B. Forger"));
  CHECK(r.exitCode() == 2);

  // Removed, the manifests redone: the package is incomplete.
  fs::remove(bag / "README.txt");
  rehashTagManifests(bag);
  const verify::Report gone = run(bag);
  INFO(allText(gone));
  CHECK(failed(gone, "package.complete"));
  CHECK_THAT(allText(gone), Contains("README.txt: missing"));
  CHECK(gone.exitCode() == 3);
}

TEST_CASE("the documents in metadata/docs/ must be there and another wording is only a warning",
          "[verify][package][readme]") {
  const fs::path bag = cleanBag("docs-wording");
  // Reworded (by another build, or by a holder who redid the tag manifests): no check relies on
  // the documents, so the verdict stands, and the warning names the file.
  {
    std::ofstream(bag / "metadata/docs/formats.md", std::ios::app) << "\nA later paragraph.\n";
  }
  rehashTagManifests(bag);
  const verify::Report reworded = run(bag);
  INFO(allText(reworded));
  CHECK(reworded.exitCode() == 0);
  REQUIRE(reworded.warnings.size() == 1);
  CHECK_THAT(reworded.warnings.front(), Contains("metadata/docs/formats.md: not the wording this verifier bundles"));

  // Changed without the tag manifests redone: a fixity failure like any tag file.
  {
    std::ofstream(bag / "metadata/docs/carrier.md", std::ios::app) << "\nchanged\n";
  }
  const verify::Report changed = run(bag);
  INFO(allText(changed));
  CHECK(changed.exitCode() == 3);

  fs::remove(bag / "metadata/docs/carrier.md");
  rehashTagManifests(bag);
  const verify::Report gone = run(bag);
  INFO(allText(gone));
  CHECK(failed(gone, "package.complete"));
  CHECK_THAT(allText(gone), Contains("metadata/docs/carrier.md: missing"));
}

TEST_CASE("an RO-Crate that says what the carrier does not fails with every manifest redone",
          "[verify][package][ro-crate]") {
  const fs::path bag = cleanBag("ro-crate-forged");
  REQUIRE(fs::exists(bag / "data/ro-crate-metadata.json"));
  {
    const verify::Report clean = run(bag);
    INFO(allText(clean));
    CHECK(clean.exitCode() == 0);
    CHECK(has(clean, "metadata.ro-crate"));
  }
  replaceInFile(bag / "data/ro-crate-metadata.json", "\"name\": \"A. Tester\"", "\"name\": \"B. Forger\"");
  rehashBag(bag, true);
  const verify::Report r = run(bag);
  INFO(allText(r));
  CHECK(failed(r, "metadata.ro-crate"));
  CHECK_THAT(allText(r), Contains("B. Forger"));
  CHECK(r.exitCode() == 2);

  // Removed, with the manifests redone: incomplete.
  fs::remove(bag / "data/ro-crate-metadata.json");
  rehashBag(bag, true);
  const verify::Report gone = run(bag);
  INFO(allText(gone));
  CHECK(failed(gone, "package.complete"));
  CHECK_THAT(allText(gone), Contains("data/ro-crate-metadata.json: missing"));
}
