// The hostile-input suite, writes (issue 51): a batch's ledger follows the output rule of
// capture/output_rule.h like every -o (appending is writing), and report, lights, render, fit
// and publish never replace a package, a bag's file or a file with other names. Each refusal is
// exit 1 naming the path, fast, with nothing written: the capture, the packages and the list are
// compared byte for byte before and after.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

// One processed capture, its zip package and its package as a bag folder, made once for the
// process: the commands below are refused before reading them, so they are shared.
struct Packed {
  fs::path dir, cap, zip, bag;
};

const Packed& packed() {
  static const Packed p = [] {
    Packed made;
    made.dir = e2e::freshDir("hostile-writes");
    made.cap = e2e::processedCapture(made.dir);
    made.zip = made.dir / "cap.zip";
    made.bag = made.dir / "cap-bag";
    for (const fs::path& out : {made.zip, made.bag}) {
      const e2e::CommandResult r = e2e::surrogate("pack " + e2e::quote(made.cap) + " -o " + e2e::quote(out));
      if (r.exitCode != 0) throw std::runtime_error("pack failed: " + r.output);
    }
    return made;
  }();
  return p;
}

std::string anOriginal(const fs::path& cap) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(cap / "original-captures")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return "original-captures/" + names.front();
}

// Everything a refused command could have damaged, byte for byte.
std::map<std::string, std::string> state(const Packed& p, const fs::path& extra) {
  std::map<std::string, std::string> all;
  for (const fs::path& root : {p.cap, p.bag, extra})
    for (const auto& [name, sha] : e2e::snapshot(root)) all[(root / name).string()] = sha;
  all[p.zip.string()] = e2e::bytesOf(p.zip);
  return all;
}

// `surrogate ARGS` bounded in time and memory: a reader that waits on a FIFO or reads
// /dev/zero without end fails the test instead of hanging it or filling the machine.
// (No limit on address space under AddressSanitizer, which reserves terabytes of it.)
e2e::CommandResult bounded(const std::string& args) {
#if defined(__SANITIZE_ADDRESS__)
  const std::string memory;
#else
  const std::string memory = "ulimit -v 4000000; ";
#endif
  return e2e::runShell(memory + "timeout 30 " + std::string(SURROGATE_EXE) + " " + args);
}

}  // namespace

TEST_CASE("a batch ledger is never an original, a carrier, a package, a bag file, the list, a link or a device") {
  const Packed& p = packed();
  const fs::path dir = e2e::freshDir("hostile-ledgers");
  const fs::path list = dir / "packages.txt";
  std::ofstream(list) << p.zip.string() << "\n";
  const std::string original = anOriginal(p.cap);
  fs::create_symlink(p.cap / original, dir / "link.jsonl");
  fs::create_hard_link(p.cap / original, dir / "hard.jsonl");
  REQUIRE(::mkfifo((dir / "fifo.jsonl").c_str(), 0600) == 0);
  std::ofstream(dir / "notes.txt") << "the photographer's notes\nsecond line\n";
  const auto before = state(p, dir);

  const std::vector<fs::path> ledgers = {p.cap / original,        p.cap / "assembly-files/carrier.xml",
                                         p.zip,                   p.bag / "bagit.txt",
                                         p.bag / "new.jsonl",     list,
                                         dir / "link.jsonl",      dir / "hard.jsonl",
                                         dir / "fifo.jsonl",      "/dev/full",
                                         dir / "notes.txt",       p.cap / "ledger.jsonl"};
  for (const fs::path& ledger : ledgers) {
    for (const std::string& command : {"verify --batch " + e2e::quote(list) + " -o " + e2e::quote(ledger),
                                       "batch " + e2e::quote(list) + " -o " + e2e::quote(ledger) + " --do verify"}) {
      INFO(command);
      const e2e::CommandResult r = bounded(command);
      INFO(r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find(ledger.filename().string()) != std::string::npos);  // names the ledger
    }
  }
  CHECK(state(p, dir) == before);
  CHECK_FALSE(fs::exists(p.bag / "new.jsonl"));
  CHECK_FALSE(fs::exists(p.cap / "ledger.jsonl"));
  // The same ledger given fresh is taken, and a second batch appends to it.
  const fs::path good = dir / "ledger.jsonl";
  CHECK(e2e::surrogate("verify --batch " + e2e::quote(list) + " -o " + e2e::quote(good) + " --quiet").exitCode == 0);
  CHECK(e2e::surrogate("batch " + e2e::quote(list) + " -o " + e2e::quote(good) + " --do verify --quiet").exitCode == 0);
}

TEST_CASE("a ledger that is a FIFO, a device or a folder is refused at once by every reader") {
  const fs::path dir = e2e::freshDir("hostile-ledger-reads");
  REQUIRE(::mkfifo((dir / "fifo.jsonl").c_str(), 0600) == 0);
  for (const std::string& ledger : {e2e::quote(dir / "fifo.jsonl"), std::string("/dev/zero"), e2e::quote(dir)}) {
    for (const std::string& command : {"batch --summary -o " + ledger, "batch --summary " + ledger + " --json"}) {
      INFO(command);
      const e2e::CommandResult r = bounded(command);
      INFO(r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find("not a regular file") != std::string::npos);
    }
  }
}

TEST_CASE("report, lights, render, fit and publish never replace a package, a bag's file or another name of a file") {
  const Packed& p = packed();
  const fs::path dir = e2e::freshDir("hostile-package-outputs");
  const std::string cap = e2e::quote(p.cap);
  const std::string rti = e2e::quote(p.cap / "finished-files/hsh2.rti");
  const std::string lp = e2e::quote(p.cap / "assembly-files/lights.lp");
  // A tar archive of someone's, an OCFL object and an E-ARK package (their root files are
  // what the rule knows them by), a hard link outside the capture to an original.
  std::ofstream(dir / "notes.txt") << "notes";
  REQUIRE(e2e::runShell("tar cf " + e2e::quote(dir / "notes.tar") + " -C " + e2e::quote(dir) + " notes.txt").exitCode == 0);
  fs::create_directories(dir / "object");
  std::ofstream(dir / "object/0=ocfl_object_1.1") << "ocfl_object_1.1\n";
  fs::create_directories(dir / "sip/representations");
  std::ofstream(dir / "sip/METS.xml") << "<mets/>";
  fs::create_hard_link(p.cap / anOriginal(p.cap), dir / "hard.html");
  const auto names = fs::hard_link_count(dir / "hard.html");
  const auto before = state(p, dir);

  const std::vector<fs::path> targets = {p.zip,
                                         dir / "notes.tar",
                                         p.bag / "bagit.txt",
                                         p.bag / "manifest-sha256.txt",
                                         p.bag / "data/new.html",
                                         p.bag / "new.html",
                                         dir / "object/new.html",
                                         dir / "sip/new.html",
                                         dir / "hard.html"};
  for (const fs::path& t : targets) {
    const std::string o = e2e::quote(t);
    const std::vector<std::string> commands = {
        "report " + cap + " -o " + o,
        "report " + e2e::quote(p.zip) + " -o " + o,
        "lights " + cap + " -o " + o,
        "render " + rti + " --light 0,0,1 -o " + o,
        "fit --lp " + lp + " -o " + o,  // the rule before the name's extension
    };
    for (const std::string& c : commands) {
      INFO(c);
      const e2e::CommandResult r = bounded(c);
      INFO(r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find(t.filename().string()) != std::string::npos);
    }
  }
  CHECK(bounded("publish " + rti + " -o " + e2e::quote(p.bag / "web")).exitCode == 1);
  CHECK_FALSE(fs::exists(p.bag / "web"));
  CHECK(state(p, dir) == before);
  CHECK(fs::hard_link_count(dir / "hard.html") == names);  // the link was not replaced
  // A package is verified as sound after all of it.
  CHECK(e2e::surrogate("verify " + e2e::quote(p.zip)).exitCode == 0);
  CHECK(e2e::surrogate("verify " + e2e::quote(p.bag)).exitCode == 0);
}
