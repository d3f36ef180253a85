// Verification cost against the number of files: a capture of N small "originals" (default
// 100 000 files of 100 bytes), recorded in a carrier (one CaptureIngest step whose result lists
// every file as an input, as a real run does) and packed by the real packer (archive::
// packCapture: payload, METS+PREMIS and CIDOC-CRM derived by the bundled stylesheets, tag
// manifests), then verified by verify::verifyPackage in a fresh process: wall time and the
// verifier's peak resident memory (VmHWM). Every check runs, the METS re-derivation and
// comparison included. Target (issue 13): 100 000 files verified in under 30 s and 500 MB.
//
//   verify_bench [--files N] [--bytes B] [--formats dir,tar,zip] [--dir DIR] [--keep]
//
// Several sizes show how the cost grows: `for n in 10000 30000 100000; do verify_bench
// --files $n; done` (the time per file should stay about constant).
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "archive/package.h"
#include "carrier/carrier.h"
#include "core/digest.h"
#include "core/error.h"
#include "stages/ingest_stage.h"
#include "verify/verify.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

double seconds(const std::chrono::steady_clock::time_point& t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// N files of `bytes` pseudo-random bytes in CAPTURE/original-captures/, 1000 per folder (as a
// large collection would be kept), and a carrier that records them.
void makeCapture(const fs::path& capture, int files, int bytes) {
  carrier::Carrier c = carrier::newCarrier("Verification benchmark", {{"A. Tester", "creator"}});
  c.header.meta.push_back({"Source-Organization", "Benchmark Museum"});
  c.header.software.push_back({"LibRaw", "0.21.1", "camera raw decoding"});
  // The version this build runs: verify refuses a step recorded at another.
  carrier::Step& ingest = c.addStep(stages::IngestStage::kComponent, stages::IngestStage::info().version);
  ingest.description = "Inventory of the capture";
  ingest.setParam("source", "auto");
  carrier::Result result;
  result.step = ingest.id;
  result.started = result.ended = c.header.created;
  std::uint64_t x = 88172645463325252ULL;
  std::string content(static_cast<std::size_t>(bytes), '\0');
  c.files.reserve(static_cast<std::size_t>(files));
  for (int i = 0; i < files; ++i) {
    char rel[96];
    std::snprintf(rel, sizeof rel, "original-captures/batch-%03d/IMG_%06d.jpg", i / 1000, i + 1);
    for (char& ch : content) {  // xorshift64
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
      ch = static_cast<char>(x);
    }
    const fs::path path = capture / rel;
    if (i % 1000 == 0) fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary).write(content.data(), static_cast<std::streamsize>(content.size()));
    carrier::FileRecord f;
    f.id = "f" + std::to_string(i + 1);  // putFile() would search the list for every file
    f.path = rel;
    f.role = "original";
    f.size = content.size();
    f.sha256 = sha256Hex(content);
    f.format = "JPEG";
    f.mediaType = "image/jpeg";
    c.files.push_back(std::move(f));
    result.add("input").set("file", "f" + std::to_string(i + 1)).set("kind", "image");
  }
  result.add("value").set("name", "images").set("value", std::to_string(files));
  c.data.push_back(std::move(result));
  fs::create_directories(capture / "assembly-files");
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
}

struct Measured {
  double seconds = 0;
  long peakKiB = 0;
  int exitCode = -1;
  std::string firstFailure;
};

// The peak resident memory of this process image in KiB (VmHWM): unlike the rusage figure it
// does not count what the process held before its exec.
long peakKiBOfThisImage() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.compare(0, 6, "VmHWM:") == 0) return std::atol(line.c_str() + 6);
  return 0;
}

// verifyPackage in a fresh process (this program run again with --verify-only), so that its
// peak memory is its own: a forked child counts the pages it shares with this process, whose
// heap still holds what making the capture and packing left. It prints its peak (KiB) on the
// first line, then the first failure.
int verifyOnly(const fs::path& package) {
  int code = 5;
  std::string failure;
  try {
    const verify::Report r = verify::verifyPackage(package, {});
    code = r.exitCode();
    for (const verify::Check& c : r.checks)
      if (!c.passed && failure.empty())
        failure = c.name + ": " + c.what + (c.where.empty() ? "" : " (" + c.where.front() + ")");
  } catch (const std::exception& e) {
    failure = e.what();
  }
  std::printf("%ld\n%s", peakKiBOfThisImage(), failure.c_str());
  return code;
}

Measured verifyInChild(const fs::path& package) {
  int pipeFd[2];
  if (::pipe(pipeFd) != 0) std::abort();
  std::fflush(stdout);
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(pipeFd[0]);
    ::dup2(pipeFd[1], STDOUT_FILENO);
    ::execl("/proc/self/exe", "verify_bench", "--verify-only", package.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(pipeFd[1]);
  Measured m;
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(pipeFd[0], buffer, sizeof buffer)) > 0) m.firstFailure.append(buffer, static_cast<std::size_t>(n));
  ::close(pipeFd[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  m.seconds = seconds(t0);
  const std::size_t newline = m.firstFailure.find('\n');
  m.peakKiB = std::atol(m.firstFailure.substr(0, newline).c_str());
  m.firstFailure.erase(0, newline == std::string::npos ? m.firstFailure.size() : newline + 1);
  m.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--verify-only") return verifyOnly(argv[2]);
  int files = 100000, bytes = 100;
  std::string formats = "dir,tar";
  fs::path dir = fs::temp_directory_path() / "surrogate-verify-bench";
  bool keep = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--files" && hasValue) files = std::atoi(argv[++i]);
    else if (a == "--bytes" && hasValue) bytes = std::atoi(argv[++i]);
    else if (a == "--formats" && hasValue) formats = argv[++i];
    else if (a == "--dir" && hasValue) dir = argv[++i];
    else if (a == "--keep") keep = true;
    else {
      std::fprintf(stderr,
                   "usage: verify_bench [--files N] [--bytes B] [--formats dir,tar,zip] [--dir DIR] [--keep]\n");
      return 2;
    }
  }
  if (files < 1 || bytes < 1) {
    std::fprintf(stderr, "verify_bench: --files and --bytes must be at least 1\n");
    return 2;
  }
  fs::remove_all(dir);
  const fs::path capture = dir / "capture";
  auto t0 = std::chrono::steady_clock::now();
  makeCapture(capture, files, bytes);
  std::printf("capture: %d files of %d bytes, carrier %.1f MB (made in %.1f s)\n", files, bytes,
              double(fs::file_size(capture / "assembly-files/carrier.xml")) / 1e6, seconds(t0));

  int status = 0;
  for (std::size_t start = 0; start < formats.size();) {
    std::size_t comma = formats.find(',', start);
    if (comma == std::string::npos) comma = formats.size();
    const std::string format = formats.substr(start, comma - start);
    start = comma + 1;
    const fs::path out = dir / (format == "dir" ? "bag" : "bag." + format);
    t0 = std::chrono::steady_clock::now();
    try {
      archive::packCapture(capture, out);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "pack failed: %s\n", e.what());
      return 1;
    }
    const double packSeconds = seconds(t0);
    std::uint64_t mets = 0;
    if (format == "dir") mets = fs::file_size(out / "metadata/mets.xml");
    const Measured m = verifyInChild(out);
    std::printf("%-4s pack %7.2f s | verify %7.2f s, peak RSS %7.1f MB, %6.1f us/file, exit %d%s%s\n",
                format.c_str(), packSeconds, m.seconds, double(m.peakKiB) / 1024.0,
                1e6 * m.seconds / files, m.exitCode, mets ? "" : "",
                m.firstFailure.empty() ? "" : ("  FAILED " + m.firstFailure).c_str());
    if (mets) std::printf("     mets.xml %.1f MB\n", double(mets) / 1e6);
    if (m.exitCode != 0) status = 1;
  }
  if (!keep) fs::remove_all(dir);
  return status;
}
