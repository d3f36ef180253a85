// The hostile-input suite, outputs: every command that writes is pointed at the capture's
// evidence, its record, a device, a FIFO and a symbolic link, and must refuse (exit 1) with
// nothing changed; pack never replaces a package without --force, and two packs to one name
// give one package, which verifies, and one refusal. The rule is capture/output_rule.h.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

std::string firstExport(const fs::path& capture) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(capture / "jpeg-exports")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names.front();
}

}  // namespace

TEST_CASE("no command writes over a capture's originals, exports, carrier or results") {
  const fs::path dir = e2e::freshDir("hostile-outputs");
  const fs::path cap = e2e::processedCapture(dir);
  const std::string q = e2e::quote(cap);
  const std::string rti = e2e::quote(cap / "finished-files/hsh2.rti");
  const std::string lp = e2e::quote(cap / "assembly-files/lights.lp");
  const auto before = e2e::snapshot(cap);
  const std::string jpeg = "jpeg-exports/" + firstExport(cap);
  const std::string dng = "original-captures/" + fs::path(firstExport(cap)).stem().string() + ".dng";
  REQUIRE(fs::exists(cap / dng));

  // Each target is a file the capture holds; each command line writes it.
  const std::vector<std::string> targets = {jpeg, dng, "assembly-files/carrier.xml", "assembly-files/lights.lp",
                                            "finished-files/ptm-lrgb.ptm", "finished-files/new.png"};
  for (const std::string& t : targets) {
    const std::string o = e2e::quote(cap / t);
    const std::vector<std::string> commands = {
        "render " + rti + " --light 0,0,1 -o " + o,
        "report " + q + " -o " + o,
        "lights " + q + " -o " + o,
        "fit --lp " + lp + " -o " + e2e::quote((cap / t).replace_extension(".rti")),
        "publish " + rti + " -o " + e2e::quote((cap / t).parent_path() / "web"),
    };
    for (const std::string& c : commands) {
      INFO(c);
      const e2e::CommandResult r = e2e::surrogate(c);
      INFO(r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find("-o ") != std::string::npos);  // names the option and the path
    }
  }
  CHECK(e2e::snapshot(cap) == before);
  // A package anywhere in the capture would be bagged by the next pack.
  const e2e::CommandResult inside = e2e::surrogate("pack " + q + " -o " + e2e::quote(cap / "pkg.zip"));
  CHECK(inside.exitCode == 1);
  CHECK_FALSE(fs::exists(cap / "pkg.zip"));
  // A link to the capture's folder is the folder.
  fs::create_directory_symlink(cap / "jpeg-exports", dir / "photos");
  CHECK(e2e::surrogate("render " + rti + " --light 0,0,1 -o " + e2e::quote(dir / "photos/x.png")).exitCode == 1);
  CHECK(e2e::snapshot(cap) == before);
}

TEST_CASE("devices, FIFOs and symbolic links are never replaced by an output") {
  const fs::path dir = e2e::freshDir("hostile-outputs-special");
  const fs::path cap = e2e::processedCapture(dir);
  const std::string rti = e2e::quote(cap / "finished-files/hsh2.rti");
  REQUIRE(::mkfifo((dir / "pipe.png").c_str(), 0600) == 0);
  fs::create_symlink(cap / "finished-files/hsh2.rti", dir / "link.png");
  std::ofstream(dir / "elsewhere.png") << "someone else's picture";
  fs::create_symlink(dir / "elsewhere.png", dir / "link-to-file.png");
  for (const fs::path& target : {fs::path("/dev/null"), dir / "pipe.png", dir / "link.png", dir / "link-to-file.png"}) {
    const e2e::CommandResult r = e2e::surrogate("render " + rti + " --light 0,0,1 -o " + e2e::quote(target));
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find("not a regular file") != std::string::npos);
  }
  struct stat st {};
  REQUIRE(::lstat("/dev/null", &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
  CHECK(fs::is_fifo(dir / "pipe.png"));
  CHECK(fs::is_symlink(dir / "link.png"));
  CHECK(e2e::bytesOf(dir / "elsewhere.png") == "someone else's picture");
  // A render into its own earlier output is documented and allowed.
  CHECK(e2e::surrogate("render " + rti + " --light 0,0,1 -o " + e2e::quote(dir / "r.png")).exitCode == 0);
  CHECK(e2e::surrogate("render " + rti + " --light 0.5,0,1 -o " + e2e::quote(dir / "r.png")).exitCode == 0);
}

TEST_CASE("pack replaces a package only with --force, and two packs to one name give one package") {
  const fs::path dir = e2e::freshDir("hostile-outputs-pack");
  const fs::path cap = e2e::processedCapture(dir);
  fs::copy(cap, dir / "cap2", fs::copy_options::recursive);
  const fs::path pkg = dir / "pkg.zip";
  std::ofstream(pkg) << "an earlier package";
  const e2e::CommandResult refused = e2e::surrogate("pack " + e2e::quote(cap) + " -o " + e2e::quote(pkg) + " --quiet");
  INFO(refused.output);
  CHECK(refused.exitCode == 1);
  CHECK(refused.output.find("--force") != std::string::npos);
  CHECK(e2e::bytesOf(pkg) == "an earlier package");
  CHECK(e2e::surrogate("pack " + e2e::quote(cap) + " -o " + e2e::quote(pkg) + " --quiet --force").exitCode == 0);
  CHECK(e2e::surrogate("verify " + e2e::quote(pkg) + " --quiet").exitCode == 0);

  for (const std::string name : {"race.tar", "race.zip", "race-bag"}) {
    const fs::path out = dir / name;
    auto pack = [&](const fs::path& capture) {
      return e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(out) + " --quiet");
    };
    auto a = std::async(std::launch::async, pack, cap);
    auto b = std::async(std::launch::async, pack, dir / "cap2");
    const e2e::CommandResult ra = a.get(), rb = b.get();
    INFO(name << "\n" << ra.output << "\n" << rb.output);
    CHECK(((ra.exitCode == 0 && rb.exitCode == 1) || (ra.exitCode == 1 && rb.exitCode == 0)));
    const std::string refusal = ra.exitCode == 1 ? ra.output : rb.output;
    // The loser is refused before packing (the name is taken) or at the rename (it appeared).
    CHECK((refusal.find("already exists") != std::string::npos || refusal.find("appeared") != std::string::npos));
    CHECK(e2e::surrogate("verify " + e2e::quote(out) + " --quiet").exitCode == 0);
    for (const auto& e : fs::directory_iterator(dir))
      CHECK(e.path().filename().string().find(".part-") == std::string::npos);  // no leftovers
  }
}

TEST_CASE("report reads a capture under a reader's lock: refused while a command writes it") {
  const fs::path dir = e2e::freshDir("hostile-outputs-report-lock");
  const fs::path cap = e2e::processedCapture(dir);
  // util-linux flock(1) holds the capture's lock as a run would (exclusively) for a while.
  const fs::path lock = cap / ".surrogate/lock";
  fs::create_directories(lock.parent_path());
  const e2e::CommandResult held = e2e::runShell(
      "flock -x " + e2e::quote(lock) + " sleep 3 & sleep 0.5; " + std::string(SURROGATE_EXE) + " report " +
      e2e::quote(cap) + " -o " + e2e::quote(dir / "r.html") + " --quiet 2>&1; echo \"exit $?\"; wait");
  INFO(held.output);
  CHECK(held.output.find("another Surrogate command is working on this capture") != std::string::npos);
  CHECK(held.output.find("exit 1") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "r.html"));
  // Two readers at once are fine.
  const e2e::CommandResult two = e2e::runShell(
      "flock -s " + e2e::quote(lock) + " sleep 2 & sleep 0.5; " + std::string(SURROGATE_EXE) + " report " +
      e2e::quote(cap) + " -o " + e2e::quote(dir / "r.html") + " --quiet 2>&1; echo \"exit $?\"; wait");
  INFO(two.output);
  CHECK(two.output.find("exit 0") != std::string::npos);
  CHECK(fs::exists(dir / "r.html"));
}
