// The ledger: its lines are JSON another parser reads (nlohmann's), appends from several
// processes never interleave, a torn last line costs only itself, and a ledger is read bounded
// and written only when it is one (never a FIFO, a device, the list, a link or another file).
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "batch/ledger.h"
#include "batch/standing.h"
#include "batch/work_list.h"
#include "core/error.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace surrogate::batch;

namespace {
fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("batch-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

LedgerEntry sample(const std::string& capture, const std::string& step, int exit) {
  LedgerEntry e;
  e.capture = capture;
  e.step = step;
  e.exit = exit;
  e.start = "2026-12-05T05:01:02.345Z";
  e.end = "2026-12-05T05:01:04.000Z";
  e.seconds = 1.655;
  e.message = "a \"quoted\" message\nwith a line break and \xc3\xa9";
  e.package = "/data/stela 12.zip";
  e.packageId = "urn:surrogate:package:abc";
  e.carrierSha256 = std::string(64, 'a');
  e.packageSha256 = std::string(64, 'b');
  e.packageSize = 123456789012ull;
  e.packageMtimeNs = 1'764'911'000'123'456'789;
  e.peakMemory = 300ull << 20;
  e.memoryBudget = 1ull << 30;
  e.host = "node1";
  e.version = "1.0";
  return e;
}
}  // namespace

TEST_CASE("a ledger line is one line of JSON with the documented keys") {
  const LedgerEntry e = sample("cap", "pack", 0);
  const std::string line = ledgerLine(e);
  REQUIRE(line.find('\n') == std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(line);
  CHECK(j["capture"] == "cap");
  CHECK(j["step"] == "pack");
  CHECK(j["attempt"] == 1);
  CHECK(j["exit"] == 0);
  CHECK(j["message"] == e.message);
  CHECK(j["package"] == "/data/stela 12.zip");
  CHECK(j["packageId"] == "urn:surrogate:package:abc");
  CHECK(j["packageSize"].get<std::uint64_t>() == 123456789012ull);
  CHECK(j["packageMtimeNs"].get<std::int64_t>() == 1'764'911'000'123'456'789);
  CHECK(j["peakMemory"].get<std::uint64_t>() == 300ull << 20);
  CHECK(j["version"] == "1.0");
  CHECK(j["start"] == "2026-12-05T05:01:02.345Z");

  LedgerEntry back;
  REQUIRE(parseLedgerLine(line, back));
  CHECK(back.message == e.message);
  CHECK(back.packageMtimeNs == e.packageMtimeNs);
  CHECK(back.carrierSha256 == e.carrierSha256);
  CHECK_FALSE(parseLedgerLine("{\"capture\":\"x\"}", back));  // no step, no exit
  CHECK_FALSE(parseLedgerLine("{\"capture\":\"x\",\"step\":\"run\",\"exit\":0", back));  // torn
}

TEST_CASE("ledgerTime is UTC ISO 8601 with milliseconds") {
  const std::string t = ledgerTime();
  REQUIRE(t.size() == 24);
  CHECK(t[4] == '-');
  CHECK(t[10] == 'T');
  CHECK(t[19] == '.');
  CHECK(t.back() == 'Z');
}

TEST_CASE("appends of long lines from several processes at once never interleave") {
  const fs::path ledger = freshFolder("shared") / "ledger.jsonl";
  constexpr int kProcesses = 6, kLines = 60;
  std::vector<pid_t> children;
  for (int p = 0; p < kProcesses; ++p) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      int status = 0;
      try {
        for (int i = 0; i < kLines; ++i) {
          LedgerEntry e = sample("capture-" + std::to_string(p), "run", 0);
          e.attempt = i + 1;
          // Longer than PIPE_BUF (4096): one write() alone would not be atomic on every file system.
          e.message = std::string(9000, static_cast<char>('a' + p));
          appendToLedger(ledger, e);
        }
      } catch (...) {
        status = 1;
      }
      ::_exit(status);
    }
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
  }
  const Ledger read = readLedger(ledger);
  CHECK(read.damagedLines == 0);
  REQUIRE(read.entries.size() == kProcesses * kLines);
  std::map<std::string, std::set<int>> attempts;
  for (const LedgerEntry& e : read.entries) {
    const char expected = static_cast<char>('a' + std::stoi(e.capture.substr(8)));
    CHECK(e.message == std::string(9000, expected));
    attempts[e.capture].insert(e.attempt);
  }
  for (const auto& [capture, numbers] : attempts) CHECK(numbers.size() == kLines);
}

TEST_CASE("a torn last line is left out and the next append starts a line of its own") {
  const fs::path ledger = freshFolder("torn") / "ledger.jsonl";
  appendToLedger(ledger, sample("one", "run", 0));
  {
    std::ofstream f(ledger, std::ios::app | std::ios::binary);
    f << "{\"capture\":\"two\",\"step\":\"pa";  // a process killed in its write
  }
  appendToLedger(ledger, sample("three", "verify", 3));
  const Ledger read = readLedger(ledger);
  CHECK(read.damagedLines == 1);
  REQUIRE(read.entries.size() == 2);
  CHECK(read.entries[0].capture == "one");
  CHECK(read.entries[1].capture == "three");
  CHECK(read.entries[1].exit == 3);
}

TEST_CASE("readLedgerSince reads what was appended since its last read and leaves a torn line for later") {
  const fs::path ledger = freshFolder("since") / "ledger.jsonl";
  Ledger seen;
  CHECK(readLedgerSince(ledger, 0, seen) == 0);  // absent: nothing, from the start
  appendToLedger(ledger, sample("one", "run", 0));
  appendToLedger(ledger, sample("two", "run", 0));
  std::uint64_t at = readLedgerSince(ledger, 0, seen);
  CHECK(at == fs::file_size(ledger));
  REQUIRE(seen.entries.size() == 2);
  CHECK(readLedgerSince(ledger, at, seen) == at);  // nothing new
  CHECK(seen.entries.size() == 2);
  {
    std::ofstream f(ledger, std::ios::app | std::ios::binary);
    f << "{\"capture\":\"three\",\"step\":\"pa";  // a process killed in its write
  }
  CHECK(readLedgerSince(ledger, at, seen) == at);  // not a whole line yet: left for later
  CHECK(seen.damagedLines == 0);
  appendToLedger(ledger, sample("four", "pack", 0));  // starts a line of its own
  at = readLedgerSince(ledger, at, seen);
  CHECK(at == fs::file_size(ledger));
  CHECK(seen.damagedLines == 1);
  REQUIRE(seen.entries.size() == 3);
  CHECK(seen.entries[2].capture == "four");
  CHECK(seen.entries[2].step == "pack");
  // The same entries as one read of the whole file.
  const Ledger whole = readLedger(ledger);
  REQUIRE(whole.entries.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(ledgerLine(whole.entries[i]) == ledgerLine(seen.entries[i]));
  CHECK(whole.damagedLines == 1);
}

TEST_CASE("an absent ledger is empty and standings give each item's last attempt per step") {
  const fs::path dir = freshFolder("standings");
  CHECK(readLedger(dir / "none.jsonl").entries.empty());
  Ledger l;
  l.entries = {sample("a", "run", 5), sample("a", "run", 0), sample("a", "pack", 0), sample("b", "run", 1)};
  l.entries[2].adopted = false;
  const auto s = standings(l);
  REQUIRE(s.size() == 2);
  CHECK(s[0].item == "a");
  CHECK(s[0].attempts == 3);
  CHECK_FALSE(s[0].failed());
  CHECK(s[0].packsMade == 1);
  CHECK(s[0].last("run")->exit == 0);
  CHECK(s[1].failed());
}

TEST_CASE("a work list drops comments and blank lines and CRLF and trailing slashes and refuses a repeated item") {
  std::istringstream in("# captures of 2026\n\n/data/stela12\r\n  /data/stela13/  \n/data/old.zip\n");
  const auto items = readWorkList(in, "list.txt");
  REQUIRE(items.size() == 3);
  CHECK(items[0].path == "/data/stela12");
  CHECK(items[0].number == 1);
  CHECK(items[1].path == "/data/stela13");
  CHECK(items[2].number == 3);
  CHECK(items[2].isPackage);
  CHECK_FALSE(items[0].isPackage);
  std::istringstream twice("/data/a\n/data/b\n/data/a/\n");
  try {
    readWorkList(twice, "list.txt");
    FAIL("a repeated capture was taken");
  } catch (const Error& e) {
    CHECK(e.message().find("line 3") != std::string::npos);
    CHECK(e.message().find("repeats line 1") != std::string::npos);
  }
}

TEST_CASE("a work list saved with a byte-order mark or in UTF-16 is read and a binary list is refused") {
  std::istringstream bom("\xEF\xBB\xBF/data/stela12\r\n/data/stela13\r\n");
  const auto items = readWorkList(bom, "list.txt");
  REQUIRE(items.size() == 2);
  CHECK(items[0].path == "/data/stela12");
  // "/d\r\n#x\r\n/e" in UTF-16LE with its mark, as PowerShell's > writes it.
  std::string utf16 = "\xFF\xFE";
  for (char c : std::string("/d\r\n#x\r\n/e")) utf16 += std::string{c, '\0'};
  std::istringstream wide(utf16);
  const auto fromWide = readWorkList(wide, "list.txt");
  REQUIRE(fromWide.size() == 2);
  CHECK(fromWide[0].path == "/d");
  CHECK(fromWide[1].path == "/e");
  std::istringstream odd(std::string("\xFF\xFE/\0d", 5));  // a lone byte: not UTF-16
  CHECK_THROWS_AS(readWorkList(odd, "list.txt"), Error);
  std::istringstream binary(std::string("/data/a\n/da\0ta\n", 15));
  try {
    readWorkList(binary, "list.txt");
    FAIL("a path with a NUL byte was taken");
  } catch (const Error& e) {
    CHECK(e.message().find("line 2 holds a NUL byte") != std::string::npos);
  }
}

TEST_CASE("a capture's package is NAME.zip beside it or in --packages") {
  CHECK(packagePathFor("/data/stela12", "") == fs::path("/data/stela12.zip"));
  CHECK(packagePathFor("/data/stela12/", "") == fs::path("/data/stela12.zip"));
  CHECK(packagePathFor("stela12", "/archive/in") == fs::path("/archive/in/stela12.zip"));
}

TEST_CASE("two captures of one name cannot share a packages folder") {
  std::istringstream in("/data/2025/stela12\n/data/2026/stela12\n");
  const auto items = readWorkList(in, "list.txt");
  CHECK_NOTHROW(requireDistinctPackages(items, ""));  // beside each capture: two files
  try {
    requireDistinctPackages(items, "/archive/in");
    FAIL("two captures were given one package");
  } catch (const Error& e) {
    CHECK(e.file() == "/data/2026/stela12");
    CHECK(e.message().find("/archive/in/stela12.zip, as item 1 (/data/2025/stela12)") != std::string::npos);
  }
}

TEST_CASE("a ledger in a folder that does not exist is reported before any job") {
  const fs::path dir = freshFolder("unwritable");
  try {
    requireWritableLedger(dir / "no-such-folder" / "ledger.jsonl");
    FAIL("an unwritable ledger was accepted");
  } catch (const Error& e) {
    CHECK(e.file() == (dir / "no-such-folder" / "ledger.jsonl").string());
  }
  requireWritableLedger(dir / "ledger.jsonl");
  CHECK(fs::exists(dir / "ledger.jsonl"));
  CHECK(fs::file_size(dir / "ledger.jsonl") == 0);
}

namespace {
// The exit code of `read` done in a child process that SIGALRM ends after `seconds`: a reader
// that waits on a FIFO fails the test (exit 124) instead of hanging it. 0 when `read` threw
// Error(Input), 1 when it returned, 2 for any other throw.
int inChild(const std::function<void()>& read, unsigned seconds = 5) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::alarm(seconds);
    try {
      read();
      ::_exit(1);
    } catch (const Error& e) {
      ::_exit(e.kind() == ErrorKind::Input ? 0 : 2);
    } catch (...) {
      ::_exit(2);
    }
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 124;
}

// True when `action` throws Error(Input) whose message holds `words`.
bool refusedWith(const std::function<void()>& action, const std::string& words) {
  try {
    action();
  } catch (const Error& e) {
    INFO(e.file() << ": " << e.message());
    return e.kind() == ErrorKind::Input && e.message().find(words) != std::string::npos;
  }
  return false;
}
}  // namespace

TEST_CASE("a ledger that is a FIFO or a device is refused at once, without waiting or reading it") {
  const fs::path dir = freshFolder("special");
  const fs::path fifo = dir / "fifo.jsonl";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const fs::path& ledger : {fifo, fs::path("/dev/zero"), fs::path("/dev/full")}) {
    INFO(ledger);
    CHECK(inChild([&] { readLedger(ledger); }) == 0);
    CHECK(inChild([&] {
            Ledger l;
            readLedgerSince(ledger, 0, l);
          }) == 0);
    CHECK(inChild([&] { requireWritableLedger(ledger); }) == 0);
    CHECK(inChild([&] { appendToLedger(ledger, sample("one", "run", 0)); }) == 0);
    CHECK(inChild([&] { checkLedgerTarget(ledger, dir / "list.txt"); }) == 0);
  }
  CHECK(refusedWith([&] { readLedger(dir); }, "a folder"));
}

TEST_CASE("a ledger line past the bound is read as damaged and a long message is cut when written") {
  const fs::path ledger = freshFolder("long") / "ledger.jsonl";
  appendToLedger(ledger, sample("one", "run", 0));
  LedgerEntry huge = sample("two", "run", 1);
  huge.message = std::string(3 * kMaxLedgerLineBytes, 'x');
  {
    std::ofstream f(ledger, std::ios::app | std::ios::binary);
    // A whole, valid line, longer than any the writer makes: not held, counted damaged.
    f << "{\"capture\":\"two\",\"step\":\"run\",\"exit\":1,\"message\":\"" << huge.message << "\"}\n";
  }
  appendToLedger(ledger, huge);  // written with its message cut
  appendToLedger(ledger, sample("three", "run", 0));
  const Ledger read = readLedger(ledger);
  CHECK(read.damagedLines == 1);
  REQUIRE(read.entries.size() == 3);
  CHECK(read.entries[0].capture == "one");
  CHECK(read.entries[1].capture == "two");
  CHECK(read.entries[1].message.size() < kMaxLedgerMessageBytes + 100);
  CHECK(read.entries[1].message.find("more bytes left out") != std::string::npos);
  CHECK(read.entries[2].capture == "three");
}

TEST_CASE("a ledger larger than the bound is refused without being read") {
  const fs::path ledger = freshFolder("large") / "ledger.jsonl";
  appendToLedger(ledger, sample("one", "run", 0));
  fs::resize_file(ledger, kMaxLedgerBytes + 1);  // sparse: no disk, no time
  CHECK(refusedWith([&] { readLedger(ledger); }, "larger than"));
  Ledger l;
  CHECK(refusedWith([&] { readLedgerSince(ledger, 0, l); }, "larger than"));
  CHECK(l.entries.empty());
}

TEST_CASE("a ledger is appended to only when it is one: never the list, a link, another name or another file") {
  const fs::path dir = freshFolder("target");
  const fs::path list = dir / "list.txt", ledger = dir / "ledger.jsonl";
  std::ofstream(list) << "/data/stela12\n";
  std::ofstream(dir / "notes.txt") << "the photographer's notes\n";
  checkLedgerTarget(ledger, list);  // absent: made by the batch
  appendToLedger(ledger, sample("one", "run", 0));
  checkLedgerTarget(ledger, list);  // a ledger
  checkLedgerTarget(ledger, "-");
  {
    std::ofstream(dir / "torn.jsonl") << "{\"capture\":\"two\",\"step\":\"pa";  // a writer killed in its first line
    checkLedgerTarget(dir / "torn.jsonl", list);
    std::ofstream(dir / "empty.jsonl");
    checkLedgerTarget(dir / "empty.jsonl", list);
  }
  fs::create_symlink(ledger, dir / "link.jsonl");
  fs::create_hard_link(ledger, dir / "hard.jsonl");
  fs::create_symlink(list, dir / "list-link.txt");
  const std::string before = [&] {
    std::ifstream f(ledger, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  CHECK(refusedWith([&] { checkLedgerTarget(list, list); }, "the list of the batch"));
  CHECK(refusedWith([&] { checkLedgerTarget(list, dir / "list-link.txt"); }, "the list of the batch"));
  CHECK(refusedWith([&] { checkLedgerTarget(dir / "notes.txt", list); }, "is not a ledger"));
  CHECK(refusedWith([&] { checkLedgerTarget(dir / "link.jsonl", list); }, "symbolic link"));
  CHECK(refusedWith([&] { checkLedgerTarget(dir / "hard.jsonl", list); }, "hard links"));
  CHECK(refusedWith([&] { checkLedgerTarget(dir, list); }, "a folder"));
  CHECK(refusedWith([&] { appendToLedger(dir / "link.jsonl", sample("x", "run", 0)); }, "symbolic link"));
  CHECK(refusedWith([&] { appendToLedger(dir / "hard.jsonl", sample("x", "run", 0)); }, "hard links"));
  CHECK(refusedWith([&] { requireWritableLedger(dir / "link.jsonl"); }, "symbolic link"));
  const std::string after = [&] {
    std::ifstream f(ledger, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  CHECK(after == before);
}
