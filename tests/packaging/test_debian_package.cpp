// The Debian package as people use it: made by CPack from this build, checked by lintian,
// unpacked with `dpkg -x` into a temporary folder (no root), and a capture taken through run,
// pack and verify --reexecute by the unpacked program from another working folder. Then the
// installation broken on purpose: a data file missing is exit 1 "reinstall Surrogate", never 5.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/resources.h"
#include "e2e_support.h"

namespace fs = std::filesystem;
using e2e::quote;
using e2e::runShell;

namespace {

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

// The package, made once per test process into a temporary folder of its own.
fs::path debianPackage() {
  static fs::path made;
  if (!made.empty()) return made;
  const fs::path out = e2e::freshDir("deb");
  const e2e::CommandResult r = runShell("cpack --config " + quote(CPACK_CONFIG) + " -B " + quote(out) + " 2>&1");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const std::string arch = trimmed(runShell("dpkg --print-architecture").output);
  made = out / ("surrogate_" + std::string(PROJECT_VERSION_TEXT) + "_" + arch + ".deb");
  REQUIRE(fs::is_regular_file(made));
  return made;
}

// The package unpacked with dpkg -x (as any user can) into a fresh folder; its root.
fs::path unpacked(const std::string& name) {
  const fs::path root = e2e::freshDir(name);
  const e2e::CommandResult r = runShell("dpkg -x " + quote(debianPackage()) + " " + quote(root) + " 2>&1");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  return root;
}

// What runs a command as the account `user` (a uid; "": the account running the test).
std::string asUser(const std::string& user) {
  return user.empty() ? "" : "setpriv --reuid=" + user + " --regid=" + user + " --clear-groups ";
}

// `program ARGS` run in `folder`, with no hint of where the data files are (as `user`, when given).
e2e::CommandResult runIn(const fs::path& folder, const fs::path& program, const std::string& args,
                         const std::string& user = "") {
  // HOME and TMPDIR of its own (the test run's TMPDIR is a folder only its owner may enter).
  return runShell("cd " + quote(folder) + " && " + asUser(user) + "env -u SURROGATE_RESOURCES HOME=" + quote(folder) +
                  " TMPDIR=" + quote(folder) + " " +
                  quote(program) + " " + args + " 2>&1");
}

// A folder an account without root owns, outside the test run's own scratch folder (which only
// its owner may enter), removed at the end. Run as root (as on CI), the test takes the package
// through as `nobody`; run as another user, as that user.
class UnprivilegedFolder {
 public:
  UnprivilegedFolder() {
    char name[] = "/tmp/surrogate-unprivileged-XXXXXX";
    REQUIRE(::mkdtemp(name) != nullptr);
    path_ = name;
    if (::geteuid() == 0) {
      user_ = "65534";  // nobody
      REQUIRE(::chown(name, 65534, 65534) == 0);
    }
  }
  ~UnprivilegedFolder() { fs::remove_all(path_); }
  UnprivilegedFolder(const UnprivilegedFolder&) = delete;
  UnprivilegedFolder& operator=(const UnprivilegedFolder&) = delete;
  const fs::path& path() const { return path_; }
  const std::string& user() const { return user_; }  // "" for the account running the test
  // `command` (a shell command line) in the folder, as the account.
  e2e::CommandResult run(const std::string& command) const {
    return runShell("cd " + quote(path_) + " && " + asUser(user_) + "sh -c " + quote(command) + " 2>&1");
  }

 private:
  fs::path path_;
  std::string user_;
};

// A generated capture (8 DNG originals with JPEG exports) as ./cap in a fresh working folder.
fs::path workWithCapture(const std::string& name) {
  const fs::path work = e2e::freshDir(name);
  const e2e::CommandResult r = runShell("cd " + quote(work) + " && " + std::string(GENERATOR_EXE) +
                                        " --out cap --images 8 --width 320 --height 240 --seed 5 2>&1");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  fs::remove_all(work / "cap/truth");
  return work;
}

}  // namespace

TEST_CASE("the Debian package names its real dependencies, holds the program, data, manual and completion, and lintian finds no error",
          "[packaging]") {
  const fs::path deb = debianPackage();
  const e2e::CommandResult fields = runShell("dpkg-deb -f " + quote(deb) + " Package Version Depends Maintainer");
  INFO(fields.output);
  CHECK(fields.output.find("Package: surrogate\n") != std::string::npos);
  CHECK(fields.output.find("Version: " + std::string(PROJECT_VERSION_TEXT) + "\n") != std::string::npos);
  // dpkg-shlibdeps' list: the libraries the program links, by their Debian package names.
  for (const char* library : {"libraw", "libexiv2", "libxml2", "libxslt1.1", "libarchive", "libssl", "libopencv-core"})
    CHECK(fields.output.find(library) != std::string::npos);

  const std::string listing = runShell("dpkg -c " + quote(deb)).output;
  std::vector<std::string> expected = {"./usr/bin/surrogate", "./usr/share/man/man1/surrogate.1.gz",
                                       "./usr/share/man/man1/surrogate-run.1.gz",
                                       "./usr/share/bash-completion/completions/surrogate",
                                       "./usr/share/doc/surrogate/copyright", "./usr/share/doc/surrogate/changelog.gz"};
  for (const std::string& rel : surrogate::dataFileNames()) expected.push_back("./usr/share/surrogate/" + rel);
  for (const std::string& path : expected) {
    INFO(path << "\n" << listing);
    CHECK(std::regex_search(listing, std::regex(" " + std::regex_replace(path, std::regex("[.+]"), "\\$&") + "\n")));
  }

  // lintian: no error (each ctest case is a process of its own, which makes the package again:
  // the checks of the made package share one case).
  REQUIRE(runShell("command -v lintian").exitCode == 0);  // scripts/install-deps installs it
  const e2e::CommandResult r = runShell("lintian --allow-root " + quote(deb) + " 2>&1");
  INFO(r.output);
  CHECK(r.output.find("E: ") == std::string::npos);
  CHECK(r.exitCode == 0);
}

TEST_CASE("the package unpacked without root runs, packs and verifies a capture from another folder and exits 1 when a data file is missing",
          "[packaging]") {
  SECTION("an account without root unpacks it and takes a capture through run, pack and verify --reexecute") {
    // Unpacked with dpkg -x and used by an account without root, from a working folder of its own.
    const UnprivilegedFolder home;
    const fs::path deb = home.path() / "surrogate.deb";
    fs::copy_file(debianPackage(), deb);
    const fs::path source = workWithCapture("capture");
    fs::create_directories(home.path() / "work");
    fs::copy(source / "cap", home.path() / "work/cap", fs::copy_options::recursive);
    if (!home.user().empty()) REQUIRE(runShell("chown -R 65534:65534 " + quote(home.path())).exitCode == 0);
    {
      const e2e::CommandResult r = home.run("id -u && dpkg -x surrogate.deb unpacked");
      INFO(r.output);
      REQUIRE(r.exitCode == 0);
      if (!home.user().empty()) CHECK(r.output.rfind("65534\n", 0) == 0);
    }
    const fs::path root = home.path() / "unpacked";
    const fs::path program = root / "usr/bin/surrogate";
    const fs::path work = home.path() / "work";

    const e2e::CommandResult version = runIn(work, program, "--version", home.user());
    INFO(version.output);
    REQUIRE(version.exitCode == 0);
    CHECK(version.output.rfind("surrogate " + std::string(PROJECT_VERSION_TEXT) + "\n", 0) == 0);
    // Its own data files, beside its bin folder: not the source tree it was built from.
    CHECK(version.output.find("data files: " + (root / "usr/share/surrogate").string() + "\n") != std::string::npos);

    for (const std::string& step : {std::string("run cap --no-report"), std::string("pack cap -o cap.zip"),
                                    std::string("verify cap.zip --reexecute")}) {
      const e2e::CommandResult r = runIn(work, program, step, home.user());
      INFO(step << "\n" << r.output);
      REQUIRE(r.exitCode == 0);
    }

    // The libraries --version and info --json name are those the run recorded in the carrier.
    const e2e::CommandResult info = runIn(work, program, "info cap --json", home.user());
    REQUIRE(info.exitCode == 0);
    const nlohmann::json described = nlohmann::json::parse(info.output);
    const nlohmann::json& libraries = described.at("version").at("libraries");
    CHECK(described.at("version").at("surrogate") == PROJECT_VERSION_TEXT);
    const std::string carrier = e2e::bytesOf(work / "cap/assembly-files/carrier.xml");
    for (const char* name : {"LibRaw", "Exiv2", "OpenCV", "libxml2", "libxslt", "libarchive", "OpenSSL"}) {
      const auto it = std::find_if(libraries.begin(), libraries.end(),
                                   [&](const nlohmann::json& l) { return l.at("name") == name; });
      INFO(name);
      REQUIRE(it != libraries.end());
      const std::string v = it->at("version");
      CHECK(version.output.find(std::string(name) + " ") != std::string::npos);
      CHECK(version.output.find(v) != std::string::npos);
      // <software name="libxslt" version="1.1.35" .../> in the carrier's header
      CHECK(carrier.find("name=\"" + std::string(name) + "\" version=\"" + v + "\"") != std::string::npos);
    }
  }
  SECTION("a data file missing from the unpacked package is exit 1 reinstall Surrogate, before anything is written") {
    const fs::path root = unpacked("broken");
    const fs::path program = root / "usr/bin/surrogate";
    const fs::path work = workWithCapture("broken-work");
    const fs::path schema = root / "usr/share/surrogate/xsd/mets-1.12.1.xsd";
    fs::remove(schema);
    for (const std::string& step : {std::string("run cap"), std::string("info cap --json"), std::string("verify cap")}) {
      const e2e::CommandResult r = runIn(work, program, step);
      INFO(step << "\n" << r.output);
      CHECK(r.exitCode == 1);
      CHECK(r.output.find("reinstall Surrogate: " + schema.string() + " is missing") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(work / "cap/assembly-files"));  // the run stopped before writing anything
    // --help and --version still answer; --version says what is missing.
    CHECK(runIn(work, program, "run --help").exitCode == 0);
    const e2e::CommandResult version = runIn(work, program, "--version");
    CHECK(version.output.find("MISSING: reinstall Surrogate: " + schema.string()) != std::string::npos);

    // The whole data folder gone: the program does not fall back to the source tree it was built
    // from (a newer program with older schemas would be wrong without a word).
    fs::remove_all(root / "usr/share/surrogate");
    const e2e::CommandResult r = runIn(work, program, "run cap");
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(r.output.find("reinstall Surrogate: its data folder is missing") != std::string::npos);
  }
}
