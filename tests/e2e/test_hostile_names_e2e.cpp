// The hostile-input suite, names: a capture holding names its package cannot hold (two names
// that differ only in letter case, the same name with its accent composed and decomposed, a
// backslash, a control character) is refused by `run` and by `pack` before anything is
// processed, every such name listed (control characters escaped) with what to do; and names
// that are awkward but legal (spaces, quotes, percent signs, letters beyond ASCII, long names)
// give a package, as a folder, .tar and .zip, that `verify` finds SOUND. The rule is
// core/file_names.h, shared by the capture scan, pack and verify.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

// The capture's files, less Surrogate's lock (.surrogate/), which any run takes and leaves.
std::map<std::string, std::string> inputsOf(const fs::path& capture) {
  std::map<std::string, std::string> files = e2e::snapshot(capture);
  for (auto it = files.begin(); it != files.end();)
    it = it->first.rfind(".surrogate/", 0) == 0 ? files.erase(it) : std::next(it);
  return files;
}

struct BadNames {
  std::string kind;
  std::vector<std::string> files;   // written into the capture (relative paths)
  std::vector<std::string> shown;   // what the refusal must say
};

}  // namespace

TEST_CASE("run and pack refuse names the package cannot hold, listing every one") {
  const std::string composed = "caf\xC3\xA9.txt", decomposed = "cafe\xCC\x81.txt";
  const std::vector<BadNames> cases = {
      {"letter case", {"notes/Readme.txt", "notes/README.txt"},
       {"notes/README.txt  and  notes/Readme.txt", "differ only in letter case"}},
      {"normalisation", {"notes/" + composed, "notes/" + decomposed},
       {"notes/" + decomposed + " (accents decomposed, as macOS writes them)  and  notes/" + composed}},
      {"folders", {"Notes/a.txt", "notes/b.txt"}, {"Notes  and  notes"}},
      {"backslash", {"notes/a\\b.txt"}, {"notes/a\\b.txt", "backslash"}},
      {"control character", {"notes/x\x01y.txt", "notes/line\nbreak.txt"},
       {"notes/x\\x01y.txt", "notes/line\\x0Abreak.txt", "control character"}},
      {"all together", {"notes/Readme.txt", "notes/README.txt", "notes/a\\b.txt", "notes/x\x01y.txt"},
       {"4 name(s) of the capture", "notes/README.txt  and  notes/Readme.txt", "notes/a\\b.txt",
        "notes/x\\x01y.txt"}},
  };
  const fs::path dir = e2e::freshDir("hostile-names");
  const fs::path source = e2e::smallCapture(dir);
  for (const BadNames& c : cases) {
    INFO(c.kind);
    const fs::path work = e2e::freshDir("hostile-names-case");
    const fs::path cap = work / "cap";
    fs::copy(source, cap, fs::copy_options::recursive);
    for (const std::string& f : c.files) {
      fs::create_directories((cap / f).parent_path());
      std::ofstream(cap / f) << f;
    }
    const auto before = inputsOf(cap);
    for (const std::string& command : {"run " + e2e::quote(cap) + " --quiet",
                                       "pack " + e2e::quote(cap) + " -o " + e2e::quote(work / "pkg.zip") + " --quiet"}) {
      INFO(command);
      const e2e::CommandResult r = e2e::surrogate(command);
      INFO(r.output);
      CHECK(r.exitCode == 1);
      for (const std::string& s : c.shown) CHECK(r.output.find(s) != std::string::npos);
      CHECK(r.output.find("rename") != std::string::npos);
      // Shown escaped: no raw control byte but the line ends.
      CHECK(r.output.find('\x01') == std::string::npos);
      CHECK(r.output.find("line\nbreak") == std::string::npos);
      // Refused before anything ran: no carrier, no results, the capture as it was.
      CHECK_FALSE(fs::exists(cap / "assembly-files"));
      CHECK_FALSE(fs::exists(cap / "finished-files"));
      CHECK_FALSE(fs::exists(work / "pkg.zip"));
      CHECK(inputsOf(cap) == before);
    }
  }
}

TEST_CASE("awkward but legal names give a package that verifies SOUND as a folder, .tar and .zip") {
  const fs::path dir = e2e::freshDir("legal-names");
  const fs::path cap = e2e::smallCapture(dir);
  const std::vector<std::string> names = {
      "notes/a name with  spaces .txt",
      "notes/quotes 'single' \"double\" `back`.txt",
      "notes/100% of 50%25 and %0A and %0D.txt",       // what manifests escape, and look-alikes
      "notes/na\xC3\xAFve caf\xC3\xA9 \xC3\x85ngstr\xC3\xB6m.txt",  // Latin letters, composed
      "notes/\xCE\xA3\xCF\x84\xCE\xAE\xCE\xBB\xCE\xB7.txt",          // Greek
      "notes/\xE7\x9F\xB3\xE7\xA2\x91.txt",                          // CJK
      "notes/" + std::string(240, 'L') + ".txt",                     // a long name
      "notes/deep/er/and/deeper/still/#hash;semi,comma=eq+plus&amp@at!bang~tilde.txt",
      "-dash first.txt", "~tilde first.txt", "IMG_0001 notes.txt",
  };
  for (const std::string& n : names) {
    fs::create_directories((cap / n).parent_path());
    std::ofstream(cap / n) << "about " << n << "\n";
  }
  const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(cap) + " --quiet --no-report");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  for (const char* out : {"pkg", "pkg.tar", "pkg.zip"}) {
    INFO(out);
    const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(cap) + " -o " + e2e::quote(dir / out) + " --quiet");
    INFO(pack.output);
    REQUIRE(pack.exitCode == 0);
    const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(dir / out));
    INFO(verify.output);
    CHECK(verify.exitCode == 0);
    CHECK(verify.output.find("SOUND") != std::string::npos);
  }
}
