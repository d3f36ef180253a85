// Fault injection: a bag of a generated capture, then one fault at a time. Every fault must be
// detected by the right check with the right exit code, and the clean bag must pass, including
// re-execution (made with 2 threads, verified with 1).
#include <catch2/catch.hpp>
#include <functional>
#include <iostream>

#include "archive/digest.h"
#include "bag_fixture.h"
#include "carrier/carrier.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using namespace verify_test;
using Catch::Matchers::Contains;

namespace {

struct Fixture {
  fs::path dir, capture, bag, tar;
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
#ifdef SURROGATE_HAVE_PACK
    for (const fs::path& out : {x.bag, x.tar}) {
      const e2e::CommandResult pack =
          e2e::surrogate("pack " + e2e::quote(x.capture) + " -o " + e2e::quote(out) + " --quiet");
      if (pack.exitCode != 0) throw std::runtime_error("surrogate pack failed: " + pack.output);
    }
#else
    makeBag(x.capture, x.bag);
    archiveDirectory(x.bag, x.tar, "bag/");
#endif
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
  return e2e::surrogate("verify " + e2e::quote(package) + " --quiet " + extra);
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
  CHECK_THAT(r.output, Contains("reexecute.s6.RtiFit"));
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
              "<param name=\"threshold\" value=\"0.80000000000000004\"/>",
              "<param name=\"threshold\" value=\"0.5\"/>");
  rehashBag(b);
  r = verify(b, "--reexecute");
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK_THAT(r.output, Contains("software differs: Eigen 0.0.1-"));
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
       3, "bagit.complete"},
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
         const auto before = surrogate::archive::digestFile(ptm);
         fs::copy_file(otherFit(), ptm, fs::copy_options::overwrite_existing);
         const auto after = surrogate::archive::digestFile(ptm);
         replaceText(b / "data/assembly-files/carrier.xml",
                     "size=\"" + std::to_string(before.size) + "\" sha256=\"" + before.sha256,
                     "size=\"" + std::to_string(after.size) + "\" sha256=\"" + after.sha256);
         rehashBag(b);
         return b;
       },
       4, "reexecute.s6.RtiFit", true, "coefficients differ by at most"},
      {"edit a recorded parameter, hashes and metadata updated consistently",
       [] {
         auto b = copyOfBag("param");
         replaceText(b / "data/assembly-files/carrier.xml",
                     "<param name=\"threshold\" value=\"0.80000000000000004\"/>",
                     "<param name=\"threshold\" value=\"0.5\"/>");
         rehashBag(b);
         return b;
       },
       4, "reexecute.s4.HighlightDetection", true, "dB"},
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
    if (fault.reexecute) {
      // Without re-execution the consistent edit is invisible: the package itself is sound.
      const e2e::CommandResult plain = verify(package);
      INFO(plain.output);
      CHECK(plain.exitCode == 0);
    }
  }
  std::cout << faults.size() << " faults injected, " << detected << " detected\n";
  CHECK(detected == static_cast<int>(faults.size()));
  (void)f;
}
