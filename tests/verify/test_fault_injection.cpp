// Fault injection: a bag of a generated capture, then one fault at a time. Every fault must be
// detected by the right check with the right exit code, and the clean bag must pass, including
// re-execution (made with 2 threads, verified with 1).
#include <catch2/catch.hpp>
#include <functional>
#include <iostream>

#include "bag_fixture.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "e2e_support.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace verify_test;
using Catch::Matchers::Contains;

namespace {

struct Fixture {
  fs::path dir, capture, bag, tar, zip;
};

// Made once per test process: the capture, run with 2 threads, and its bag (dir and .tar).
const Fixture& fixture() {
  static Fixture f = [] {
    Fixture x;
    x.dir = verify_test::freshDir("faults");
    x.capture = e2e::smallCapture(x.dir, 12);
    const e2e::CommandResult run =
        e2e::surrogate("run " + e2e::quote(x.capture) + " --threads 2 --quiet");
    if (run.exitCode != 0) throw std::runtime_error("surrogate run failed: " + run.output);
    x.bag = x.dir / "bag";
    x.tar = x.dir / "bag.tar";
    x.zip = x.dir / "bag.zip";
    for (const fs::path& out : {x.bag, x.tar, x.zip}) {
      const e2e::CommandResult pack =
          e2e::surrogate("pack " + e2e::quote(x.capture) + " -o " + e2e::quote(out) + " --quiet");
      if (pack.exitCode != 0) throw std::runtime_error("surrogate pack failed: " + pack.output);
    }
    return x;
  }();
  return f;
}

fs::path copyOfBag(const std::string& name) {
  const fs::path target = verify_test::freshDir(name) / "bag";
  fs::copy(fixture().bag, target, fs::copy_options::recursive);
  return target;
}

void flipByte(const fs::path& file, double where = 0.5) {
  std::string bytes = readText(file);
  REQUIRE(!bytes.empty());
  const std::size_t at = static_cast<std::size_t>(bytes.size() * where);
  bytes[at] = static_cast<char>(bytes[at] ^ 0x20);
  writeText(file, bytes);
}

void replaceText(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = readText(file);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  writeText(file, text);
}

struct Fault {
  Fault(std::string n, std::function<fs::path()> m, int exit, std::string check,
        bool reexec = false, std::string text = "")
      : name(std::move(n)), make(std::move(m)), expectedExit(exit), expectedCheck(std::move(check)),
        reexecute(reexec), expectedText(std::move(text)) {}
  std::string name;
  std::function<fs::path()> make;  // returns the package to verify
  int expectedExit;
  std::string expectedCheck;  // a check that must be reported as failed
  bool reexecute;
  std::string expectedText;   // also in the report, when not empty
};

e2e::CommandResult verify(const fs::path& package, const std::string& extra = "") {
  // Not --quiet: the tests read the checks by name, passed ones too.
  return e2e::surrogate("verify " + e2e::quote(package) + " " + extra);
}

// Replaces the ptm result by one fitted with other parameters (10 of the 12 images).
fs::path otherFit() {
  const fs::path dir = verify_test::freshDir("otherfit");
  const fs::path copy = dir / "capture";
  fs::copy(fixture().capture, copy, fs::copy_options::recursive);
  std::string lp = readText(copy / "assembly-files/lights.lp");
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < lp.size()) {
    const std::size_t end = lp.find('\n', start);
    lines.push_back(lp.substr(start, end - start));
    start = end == std::string::npos ? lp.size() : end + 1;
  }
  std::string shorter = "10\n";
  for (std::size_t i = 1; i <= 10 && i < lines.size(); ++i) shorter += lines[i] + "\n";
  writeText(copy / "assembly-files/other.lp", shorter);
  const fs::path out = dir / "other.ptm";
  const e2e::CommandResult fit = e2e::surrogate("fit --lp " + e2e::quote(copy / "assembly-files/other.lp") +
                                                " -o " + e2e::quote(out) + " --basis ptm-lrgb --quiet");
  INFO(fit.output);
  REQUIRE(fit.exitCode == 0);
  return out;
}

}  // namespace

TEST_CASE("the clean bag is sound, and re-executes exactly with another thread count",
          "[verify][faults]") {
  const Fixture& f = fixture();
  e2e::CommandResult r = verify(f.bag, "--reexecute --threads 1");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("SOUND"));
  CHECK_THAT(r.output, Contains("reexecute.s7.RtiFit"));
  r = verify(f.tar, "--reexecute --threads 1 --json");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("\"sound\":true"));
  // Re-execution wrote nothing next to the package, and its temporary folder is gone.
  CHECK(e2e::snapshot(f.bag) == e2e::snapshot(copyOfBag("untouched")));
  const fs::path tmp = verify_test::freshDir("tmpdir");
  r = e2e::runShell("TMPDIR=" + e2e::quote(tmp) + " " + SURROGATE_EXE + " verify " +
                    e2e::quote(f.tar) + " --reexecute --quiet");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK(fs::is_empty(tmp));
}

TEST_CASE("software version differences are reported, and next to the differences they cause",
          "[verify][faults]") {
  // The carrier says another LibRaw made it; results are the same, so the package is sound
  // and the difference is reported.
  fs::path b = copyOfBag("software");
  replaceText(b / "data/assembly-files/carrier.xml", "<software name=\"Eigen\" version=\"",
              "<software name=\"Eigen\" version=\"0.0.1-");
  rehashBag(b);
  e2e::CommandResult r = verify(b, "--reexecute --json");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.output, Contains("\"softwareDifferences\":[\"Eigen 0.0.1-"));
  // With a changed parameter as well, the failing step names the software difference.
  replaceText(b / "data/assembly-files/carrier.xml",
              "<param name=\"threshold\" value=\"0.8\"/>",
              "<param name=\"threshold\" value=\"0.5\"/>");
  rehashBag(b);
  r = verify(b, "--reexecute");
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK_THAT(r.output, Contains("software differs: Eigen 0.0.1-"));
}

TEST_CASE("a package made before text had PUIDs re-executes as sound, a changed PUID does not",
          "[verify][faults]") {
  // Before issue 56 the .lp had no PUID (PRONOM gives text no signature); Siegfried and fido
  // name it x-fmt/111, as the carrier now records. The bytes are the same: still sound.
  // The bag with the .lp's PUID attribute replaced by `attribute`, every hash redone.
  const auto reexecuted = [](const std::string& name, const std::string& attribute) {
    const fs::path b = copyOfBag(name);
    replaceText(b / "data/assembly-files/carrier.xml", "mediaType=\"text/plain\" puid=\"x-fmt/111\"",
                "mediaType=\"text/plain\"" + attribute);
    rehashBag(b);
    return verify(b, "--reexecute");
  };
  e2e::CommandResult r = reexecuted("textpuid", "");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  // Any other PUID is a rewritten description: not sound.
  r = reexecuted("otherpuid", " puid=\"fmt/101\"");
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK_THAT(r.output, Contains("@puid: recorded \"fmt/101\", reproduced \"x-fmt/111\""));
}

TEST_CASE("a package with the metadata of the mappings first edition stays sound, its crate changed does not",
          "[verify][faults]") {
  // Packages made before issue 56: no licence entity on a crate whose capture states none, and
  // data/ro-crate-metadata.json of unknown format in mets.xml (src/mapping/mapping.h).
  fs::path b = copyOfBag("edition1");
  rehashBag(b, false, 1);
  const std::string crate = readText(b / "data/ro-crate-metadata.json");
  REQUIRE(crate.find("#no-licence-stated") == std::string::npos);
  REQUIRE(readText(b / "metadata/mets.xml").find("fmt/817") == std::string::npos);
  e2e::CommandResult r = verify(b);
  INFO(r.output);
  CHECK(r.exitCode == 0);
  // The current edition of the same bag names the licence that was not stated.
  fs::path now = copyOfBag("edition2");
  rehashBag(now);
  CHECK(readText(now / "data/ro-crate-metadata.json").find("#no-licence-stated") != std::string::npos);
  CHECK(verify(now).exitCode == 0);
  // A crate neither edition gives is still refused.
  replaceText(b / "data/ro-crate-metadata.json", "\"name\": \"", "\"name\": \"Forged ");
  rehashBag(b, true, 1);
  r = verify(b);
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Contains("metadata.ro-crate"));
}

TEST_CASE("every injected fault is detected with the right check and exit code",
          "[verify][faults]") {
  const Fixture& f = fixture();
  std::vector<Fault> faults = {
      {"flip a byte in an original",
       [] { auto b = copyOfBag("orig"); flipByte(b / "data/original-captures/IMG_0003.dng"); return b; },
       3, "bagit.fixity-sha256"},
      {"flip a byte in an export",
       [] { auto b = copyOfBag("export"); flipByte(b / "data/jpeg-exports/IMG_0004.jpg"); return b; },
       3, "bagit.fixity-sha512"},
      {"flip a byte in the carrier",
       [] { auto b = copyOfBag("carrier"); flipByte(b / "data/assembly-files/carrier.xml", 0.3); return b; },
       3, "bagit.fixity-sha256"},
      {"flip a byte in a result",
       [] { auto b = copyOfBag("result"); flipByte(b / "data/finished-files/ptm-lrgb.ptm", 0.7); return b; },
       3, "carrier.files"},
      {"flip a byte in a manifest",
       [] { auto b = copyOfBag("manifest"); flipByte(b / "manifest-sha256.txt", 0.01); return b; },
       3, "bagit.tagfixity-sha256"},
      {"flip a byte in a tag file",
       [] { auto b = copyOfBag("baginfo"); flipByte(b / "bag-info.txt", 0.2); return b; },
       3, "bagit.tagfixity-sha512"},
      {"flip a byte in the METS",
       [] { auto b = copyOfBag("mets"); flipByte(b / "metadata/mets.xml", 0.5); return b; },
       3, "bagit.tagfixity-sha256"},
      {"delete a file",
       [] { auto b = copyOfBag("delete"); fs::remove(b / "data/jpeg-exports/IMG_0005.jpg"); return b; },
       3, "bagit.complete"},
      {"add an unlisted file",
       [] { auto b = copyOfBag("add"); writeText(b / "data/finished-files/extra.txt", "extra\n"); return b; },
       3, "bagit.complete"},
      {"add an unlisted tag file",
       [] { auto b = copyOfBag("addtag"); writeText(b / "metadata/notes.txt", "added later\n"); return b; },
       3, "package.tags-listed"},
      {"add an original, manifests and metadata redone consistently",
       [] {
         auto b = copyOfBag("addoriginal");
         fs::copy_file(b / "data/original-captures/IMG_0001.dng", b / "data/original-captures/IMG_0099.dng");
         rehashBag(b);
         return b;
       },
       3, "carrier.files"},
      {"rename a file",
       [] {
         auto b = copyOfBag("rename");
         fs::rename(b / "data/original-captures/IMG_0006.dng", b / "data/original-captures/IMG_0006-renamed.dng");
         return b;
       },
       3, "bagit.complete"},
      {"truncate the archive",
       [] {
         const fs::path cut = verify_test::freshDir("cut") / "bag.tar";
         const std::string bytes = readText(fixture().tar);
         writeText(cut, bytes.substr(0, bytes.size() * 6 / 10));
         return cut;
       },
       3, "package.read"},
      {"replace a result by another fit (hashes not updated)",
       [] {
         auto b = copyOfBag("otherfit");
         fs::copy_file(otherFit(), b / "data/finished-files/ptm-lrgb.ptm", fs::copy_options::overwrite_existing);
         return b;
       },
       3, "bagit.fixity-sha256"},
      {"replace a result by another fit, carrier and hashes updated consistently",
       [] {
         auto b = copyOfBag("otherfit2");
         const fs::path ptm = b / "data/finished-files/ptm-lrgb.ptm";
         const auto before = surrogate::digestFile(ptm);
         fs::copy_file(otherFit(), ptm, fs::copy_options::overwrite_existing);
         const auto after = surrogate::digestFile(ptm);
         replaceText(b / "data/assembly-files/carrier.xml",
                     "size=\"" + std::to_string(before.size) + "\" sha256=\"" + before.sha256,
                     "size=\"" + std::to_string(after.size) + "\" sha256=\"" + after.sha256);
         rehashBag(b);
         return b;
       },
       4, "reexecute.s7.RtiFit", true, "coefficients differ by at most"},
      {"edit a recorded parameter, hashes and metadata updated consistently",
       [] {
         auto b = copyOfBag("param");
         replaceText(b / "data/assembly-files/carrier.xml",
                     "<param name=\"threshold\" value=\"0.8\"/>",
                     "<param name=\"threshold\" value=\"0.5\"/>");
         rehashBag(b);
         return b;
       },
       4, "reexecute.s4.HighlightDetection", true, "dB"},
      {"delete both tag manifests",
       [] {
         auto b = copyOfBag("notagmanifests");
         fs::remove(b / "tagmanifest-sha256.txt");
         fs::remove(b / "tagmanifest-sha512.txt");
         return b;
       },
       3, "package.complete", false, "tagmanifest-sha256.txt: missing"},
      {"delete the SHA-512 tag manifest",
       [] { auto b = copyOfBag("notag512"); fs::remove(b / "tagmanifest-sha512.txt"); return b; },
       3, "package.complete", false, "tagmanifest-sha512.txt: missing"},
      {"delete a bundled schema and its tag manifest lines",
       [] {
         auto b = copyOfBag("noxsd");
         fs::remove(b / "metadata/xsd/premis-3.0.xsd");
         rehashTagManifests(b);
         return b;
       },
       3, "package.complete", false, "metadata/xsd/premis-3.0.xsd: missing"},
      {"empty carrier.xsd, tag manifests redone",
       [] {
         auto b = copyOfBag("emptyxsd");
         writeText(b / "metadata/xsd/carrier.xsd", "");
         rehashTagManifests(b);
         return b;
       },
       2, "package.bundled", false, "metadata/xsd/carrier.xsd: differs"},
      {"a garbage stylesheet, tag manifests redone",
       [] {
         auto b = copyOfBag("garbagexsl");
         writeText(b / "metadata/xslt/carrier-to-crm.xsl", "garbage");
         rehashTagManifests(b);
         return b;
       },
       2, "package.bundled", false, "metadata/xslt/carrier-to-crm.xsl: differs"},
      {"a forged bag-info, tag manifests redone",
       [] {
         auto b = copyOfBag("forgedinfo");
         replaceText(b / "bag-info.txt", "External-Description: ", "External-Description: Stela 9, ");
         rehashTagManifests(b);
         return b;
       },
       2, "package.info", false, "the carrier's header gives"},
      {"a forged package identifier, tag manifests redone",
       [] {
         auto b = copyOfBag("forgedid");
         replaceText(b / "bag-info.txt", "Surrogate-Package-Identifier: urn:sha256:",
                     "Surrogate-Package-Identifier: urn:sha256:0");
         rehashTagManifests(b);
         return b;
       },
       2, "package.info", false, "the carrier in the package gives urn:sha256:"},
      {"Payload-Oxum off by one file, tag manifests redone",
       [] {
         auto b = copyOfBag("oxum");
         std::string info = readText(b / "bag-info.txt");
         const auto at = info.find("Payload-Oxum: ");
         const auto dot = info.find('.', at), end = info.find('\n', at);
         info.replace(dot + 1, end - dot - 1, std::to_string(std::stoi(info.substr(dot + 1, end - dot - 1)) + 1));
         writeText(b / "bag-info.txt", info);
         rehashTagManifests(b);
         return b;
       },
       3, "bagit.payload-oxum", false, "Payload-Oxum says"},
      {"append a second tar after the end-of-archive marker",
       [] {
         const fs::path more = verify_test::freshDir("twotars") / "bag.tar";
         const std::string tar = readText(fixture().tar);
         writeText(more, tar + tar);
         return more;
       },
       3, "package.read", false, "data follow the end of the archive"},
      {"a recorded threshold that is not a number, hashes and metadata redone",
       [] {
         auto b = copyOfBag("nan");
         replaceText(b / "data/assembly-files/carrier.xml",
                     "<param name=\"threshold\" value=\"0.8\"/>",
                     "<param name=\"threshold\" value=\"nan\"/>");
         rehashBag(b);
         return b;
       },
       2, "carrier.steps", true, "step s4 (HighlightDetection): threshold"},
      {"an unknown component, hashes and metadata redone",
       [] {
         auto b = copyOfBag("unknown");
         replaceText(b / "data/assembly-files/carrier.xml", "component=\"DerivedMaps\"",
                     "component=\"DerivedMagic\"");
         rehashBag(b);
         return b;
       },
       2, "carrier.steps", true, "(DerivedMagic): no stage of this build"},
      {"an output path escaping the capture, hashes and metadata redone",
       [] {
         auto b = copyOfBag("escape");
         replaceText(b / "data/assembly-files/carrier.xml",
                     "<param name=\"output\" value=\"finished-files/ptm-lrgb.ptm\"/>",
                     "<param name=\"output\" value=\"../../ptm-lrgb.ptm\"/>");
         rehashBag(b);
         return b;
       },
       2, "carrier.steps", true, "output=../../ptm-lrgb.ptm"},
  };

  int detected = 0;
  for (const Fault& fault : faults) {
    const fs::path package = fault.make();
    const e2e::CommandResult r = verify(package, fault.reexecute ? "--reexecute" : "");
    INFO(fault.name << "\n" << r.output);
    const bool rightCode = r.exitCode == fault.expectedExit;
    const bool rightCheck = r.output.find("FAIL  " + fault.expectedCheck) != std::string::npos &&
                            r.output.find(fault.expectedText) != std::string::npos;
    CHECK(rightCode);
    CHECK(rightCheck);
    if (rightCode && rightCheck) ++detected;
    if (fault.reexecute && fault.expectedExit == 4) {
      // Without re-execution the consistent edit is invisible: the package itself is sound.
      const e2e::CommandResult plain = verify(package);
      INFO(plain.output);
      CHECK(plain.exitCode == 0);
    } else if (fault.reexecute) {
      // An invalid carrier: plain verify says so too, and --reexecute never ran it.
      const e2e::CommandResult plain = verify(package);
      INFO(plain.output);
      CHECK(plain.exitCode == fault.expectedExit);
      CHECK(r.output.find("not re-executed") != std::string::npos);
    }
  }
  std::cout << faults.size() << " faults injected, " << detected << " detected\n";
  CHECK(detected == static_cast<int>(faults.size()));
  (void)f;
}

namespace {

surrogate::verify::Report verifyHere(const fs::path& package) {
  return surrogate::verify::verifyPackage(package, {});
}

std::string failures(const surrogate::verify::Report& r) {
  std::string s;
  for (const auto& c : r.checks) {
    if (c.passed) continue;
    s += c.name + ": " + c.what + "\n";
    for (const std::string& w : c.where) s += "  " + w + "\n";
  }
  return s;
}

}  // namespace

TEST_CASE("every prefix of a packed folder bag, cut file by file as pack writes it, fails",
          "[verify][faults]") {
  const fs::path bag = fixture().bag;
  const std::vector<std::string> files = filesInWriteOrder(bag);
  const fs::path cut = verify_test::freshDir("prefixes") / "bag";
  fs::create_directories(cut);
  int failed = 0;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const auto r = verifyHere(cut);
    INFO("the first " << k << " of " << files.size() << " files, up to before " << files[k] << "\n"
                      << failures(r));
    CHECK(r.exitCode() == (k == 0 ? 2 : 3));  // nothing: not a bag; a part: incomplete
    failed += r.exitCode() != 0;
    fs::create_directories((cut / files[k]).parent_path());
    fs::copy_file(bag / files[k], cut / files[k]);
  }
  std::cout << files.size() << " prefixes of a folder bag, " << failed << " failed\n";
  CHECK(failed == static_cast<int>(files.size()));
  CHECK(verifyHere(cut).exitCode() == 0);  // all of it
}

TEST_CASE("a packed tar or zip cut at any entry boundary, or inside entries, fails (exit 3)",
          "[verify][faults]") {
  const fs::path dir = verify_test::freshDir("cuts");
  struct Cut {
    std::string name;
    std::uint64_t at;
  };
  std::vector<Cut> cuts;
  const std::string tar = readText(fixture().tar), zip = readText(fixture().zip);
  const std::vector<std::uint64_t> tarOffsets = tarEntryOffsets(tar), zipOffsets = zipEntryOffsets(zip);
  for (std::size_t i = 0; i < tarOffsets.size(); ++i) {
    if (tarOffsets[i] > 0) cuts.push_back({"cut.tar", tarOffsets[i]});  // entry boundary
    if (i % 5 == 1) {                                                    // some entries: inside
      cuts.push_back({"cut.tar", tarOffsets[i] + 256});
      if (i + 1 < tarOffsets.size())
        cuts.push_back({"cut.tar", (tarOffsets[i] + 512 + tarOffsets[i + 1]) / 2});
    }
  }
  cuts.push_back({"cut.tar", tarOffsets.back() + 512});   // half the end-of-archive marker
  cuts.push_back({"cut.tar", tarOffsets.back() + 1500});  // inside a block of the padding
  for (std::size_t i = 0; i < zipOffsets.size(); ++i) {
    if (zipOffsets[i] > 0) cuts.push_back({"cut.zip", zipOffsets[i]});
    if (i % 5 == 1 && i + 1 < zipOffsets.size())
      cuts.push_back({"cut.zip", (zipOffsets[i] + zipOffsets[i + 1]) / 2});
  }
  cuts.push_back({"cut.zip", zip.size() - 1});
  int failed = 0, tried = 0;
  for (const Cut& c : cuts) {
    const std::string& whole = c.name == "cut.tar" ? tar : zip;
    if (c.at >= whole.size()) continue;
    writeText(dir / c.name, whole.substr(0, c.at));
    const auto r = verifyHere(dir / c.name);
    INFO(c.name << " cut at byte " << c.at << " of " << whole.size() << "\n" << failures(r));
    CHECK(r.exitCode() == 3);
    ++tried;
    failed += r.exitCode() == 3;
  }
  std::cout << tried << " cuts of a packed tar and zip, " << failed << " failed with exit 3\n";
  CHECK(failed == tried);
  // Trailing data after a zip's end, and zeros after a tar's (padding: sound).
  writeText(dir / "more.zip", zip + "PK and more");
  auto r = verifyHere(dir / "more.zip");
  INFO(failures(r));
  CHECK(r.exitCode() == 3);
  writeText(dir / "padded.tar", tar + std::string(10240, '\0'));  // whole blocks of zeros: padding
  r = verifyHere(dir / "padded.tar");
  INFO(failures(r));
  CHECK(r.exitCode() == 0);
}

TEST_CASE("verify refuses a negative thread count", "[verify][faults]") {
  const e2e::CommandResult r = verify(fixture().tar, "--threads -1");
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.output, Contains("--threads"));
}

TEST_CASE("a verify --reexecute stopped by a signal leaves nothing, and a killed one only what "
          "rm -rf removes", "[verify][faults]") {
  for (const std::string signal : {"TERM", "INT", "KILL"}) {
    const fs::path tmp = verify_test::freshDir("killed-" + signal);
    // set -m: with job control a background job keeps SIGINT (else the shell ignores it).
    const std::string script =
        "set -m; TMPDIR=" + e2e::quote(tmp) + " " + SURROGATE_EXE + " verify " + e2e::quote(fixture().tar) +
        " --reexecute --quiet >/dev/null 2>&1 & pid=$!; "
        "for i in $(seq 1 600); do "
        "  if [ -n \"$(find " + e2e::quote(tmp) + " -path '*/replay/original-captures/*' 2>/dev/null | head -1)\" ]; then break; fi; "
        "  sleep 0.02; done; "
        "kill -" + signal + " $pid; wait $pid; echo \"status $?\"";
    e2e::CommandResult r = e2e::runShell("bash -c " + e2e::quote(script));
    INFO(signal << ": " << r.output);
    if (signal != "KILL") {
      CHECK(fs::is_empty(tmp));  // the handler removed the temporary folder
    } else {
      // What SIGKILL leaves is writable for its owner (no folder without u+w, so rm -rf works
      // for a user who is not root too).
      r = e2e::runShell("find " + e2e::quote(tmp) + " -type d ! -perm -u+w | wc -l");
      CHECK(r.output == "0\n");
      r = e2e::runShell("rm -rf " + e2e::quote(tmp) + "/*; echo rm $?; ls -A " + e2e::quote(tmp) + " | wc -l");
      INFO(r.output);
      CHECK_THAT(r.output, Contains("rm 0"));
      CHECK(fs::is_empty(tmp));
    }
  }
}

TEST_CASE("pack removes the partial output of a killed pack to the same name, and says so",
          "[verify][faults]") {
  const fs::path dir = verify_test::freshDir("stale");
  // A process that has ended: its pid names the leftovers.
  const e2e::CommandResult child = e2e::runShell("sh -c 'echo $$'");
  const std::string pid = child.output.substr(0, child.output.find('\n'));
  const fs::path staleFile = dir / (".out.tar.part-" + pid + "-0");
  const fs::path staleDir = dir / (".out.part-" + pid + "-3");
  const fs::path alive = dir / ".out.tar.part-1-0";  // pid 1 runs: kept
  writeText(staleFile, "half a tar");
  writeText(staleDir / "data/x.dng", "half a bag");
  fs::permissions(staleDir / "data", fs::perms::owner_read | fs::perms::owner_exec);
  writeText(alive, "another pack, still writing");
  e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(fixture().capture) + " -o " +
                                        e2e::quote(dir / "out.tar"));
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_FALSE(fs::exists(staleFile));
  CHECK(fs::exists(alive));
  CHECK_THAT(r.output, Contains("Removed " + staleFile.string()));
  CHECK_THAT(r.output, Contains("process " + pid + " no longer runs"));
  r = e2e::surrogate("pack " + e2e::quote(fixture().capture) + " -o " + e2e::quote(dir / "out") + " --json");
  INFO(r.output);
  CHECK(r.exitCode == 0);
  CHECK_FALSE(fs::exists(staleDir));
  CHECK_THAT(r.output, Contains("\"removedLeftovers\":[\"removed " + staleDir.string()));
}

TEST_CASE("a step of the version before re-executes as it ran, an older one is refused by name",
          "[verify][faults]") {
  // HighlightDetection 11 registered frames with cv::phaseCorrelate, 12 with Surrogate's own: a
  // package made before still re-executes (its steps run as they ran), one of version 10 cannot.
  for (const std::string version : {"11", "10"}) {
    const fs::path bag = copyOfBag("version" + version);
    replaceText(bag / "data/assembly-files/carrier.xml", "component=\"HighlightDetection\" version=\"12\"",
                "component=\"HighlightDetection\" version=\"" + version + "\"");
    rehashBag(bag);
    const e2e::CommandResult r = verify(bag, "--reexecute --threads 1");
    INFO(version << ": " << r.output);
    if (version == "11") {
      CHECK(r.exitCode == 0);
      CHECK_THAT(r.output, Contains("SOUND"));
    } else {
      CHECK(r.exitCode == 2);
      CHECK_THAT(r.output, Contains("version 10 is recorded, this build has HighlightDetection version 12"));
    }
  }
}
