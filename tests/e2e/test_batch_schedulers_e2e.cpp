// surrogate batch under the schedulers people use: GNU parallel (Debian's `parallel`) running
// the script `batch --emit parallel` writes, and a Slurm job array (Debian's munge and
// slurm-wlm on one host) with a task killed and requeued.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "batch_e2e_support.h"
#include "e2e_support.h"
#include "ledger_lines.h"

namespace fs = std::filesystem;
using e2e::quote;
using nlohmann::json;
using namespace batch_e2e;

TEST_CASE("GNU parallel runs the script batch --emit parallel writes and reruns only the failed job", "[batch]") {
  if (e2e::runShell("parallel --version").exitCode != 0) {
    WARN("GNU parallel is not installed (scripts/install-deps installs Debian's parallel): test skipped");
    return;
  }
  const fs::path dir = e2e::freshDir("batch-parallel");
  const fs::path list = makeCaptures(dir, 3);
  // A fourth line that is not a capture yet: its job fails, the others do not wait for it.
  std::ofstream(list, std::ios::app) << (dir / "late").string() << "\n";
  fs::create_directories(dir / "late");
  const fs::path ledger = dir / "ledger.jsonl";
  const auto emitted = e2e::surrogate("batch " + quote(list) + " -o " + quote(ledger) +
                                      " --jobs 2 --memory 1G --no-report --emit parallel");
  REQUIRE(emitted.exitCode == 0);
  CHECK(emitted.output.find("--joblog") != std::string::npos);
  CHECK(emitted.output.find("--resume-failed") != std::string::npos);
  CHECK(emitted.output.find("--memfree 1G") != std::string::npos);
  CHECK(emitted.output.find(" --one {") != std::string::npos);  // the item number, the last input source
  CHECK(emitted.output.find("--null") != std::string::npos);
  CHECK(emitted.output.find("--quote") != std::string::npos);
  std::ofstream(dir / "run.sh") << emitted.output;
  const auto first = e2e::runShell("cd " + quote(dir) + " && HOME=" + quote(dir) + " sh run.sh");
  INFO(first.output);
  CHECK(first.exitCode == 1);  // parallel: the number of failed jobs
  std::vector<json> lines = ledgerLines(ledger);
  for (int i = 1; i <= 3; ++i) CHECK(count(lines, (dir / ("cap" + std::to_string(i))).string(), "verify", 0) == 1);
  CHECK(count(lines, (dir / "late").string(), "run", 0) == 0);
  const std::size_t linesBefore = lines.size();
  // The capture arrives; the script run again reruns the failed job only.
  fs::remove_all(dir / "late");
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + quote(dir / "late") +
                        " --images 6 --width 200 --height 150 --sphere-radius 25 --seed 9").exitCode == 0);
  fs::remove_all(dir / "late" / "truth");
  const auto second = e2e::runShell("cd " + quote(dir) + " && HOME=" + quote(dir) + " sh run.sh");
  INFO(second.output);
  CHECK(second.exitCode == 0);
  lines = ledgerLines(ledger);
  CHECK(lines.size() == linesBefore + 3);  // late's run, pack and verify; nothing else again
  CHECK(count(lines, (dir / "late").string(), "verify", 0) == 1);
  // parallel's own job log: one line per job and run (a header, 4 jobs, then the one rerun).
  std::ifstream joblog(ledger.string() + ".joblog");
  std::size_t jobLines = 0;
  std::string line;
  while (std::getline(joblog, line)) ++jobLines;
  CHECK(jobLines == 1 + 4 + 1);
  CHECK(e2e::surrogate("batch --summary -o " + quote(ledger)).exitCode == 0);
}

namespace {

// A single-host Slurm cluster in a scratch folder: munged with its own key and socket,
// slurmctld and slurmd (Debian's munge and slurm-wlm) on two free ports, stopped (by their
// process ids) when the test ends. `error` says why it could not start.
class SlurmCluster {
  // The cluster's folder directly under /tmp, whatever TMPDIR says: slurmstepd makes a Unix
  // socket in SlurmdSpoolDir, whose path may not pass 108 bytes (under scripts/test's TMPDIR
  // it was 115, and every batch launch failed).
  static fs::path shortScratchDir() {
    std::string path = "/tmp/surrogate-slurm-XXXXXX";
    if (!::mkdtemp(path.data())) throw std::runtime_error("cannot make a folder for the Slurm cluster in /tmp");
    return path;
  }

 public:
  SlurmCluster() : dir_(shortScratchDir()) {
    for (const char* tool : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "sinfo"})
      if (e2e::runShell(std::string("command -v ") + tool + " || test -x /usr/sbin/" + tool).exitCode != 0) {
        error = std::string(tool) + " is not installed (scripts/install-deps installs Debian's slurm-wlm and munge)";
        return;
      }
    fs::create_directories(dir_ / "munge");
    fs::permissions(dir_ / "munge", fs::perms::owner_all, fs::perm_options::replace);
    for (const char* sub : {"state", "spool", "log"}) fs::create_directories(dir_ / sub);
    const std::string d = quote(dir_);
    if (e2e::runShell("dd if=/dev/urandom of=" + d + "/munge/munge.key bs=1024 count=1 2>/dev/null && chmod 600 " + d +
                      "/munge/munge.key").exitCode != 0) {
      error = "cannot make a munge key";
      return;
    }
    const auto munge = e2e::runShell("PATH=\"$PATH:/usr/sbin\" munged -f --key-file=" + d + "/munge/munge.key --socket=" + d +
                                     "/munge/socket --pid-file=" + d + "/munge/munged.pid --log-file=" + d +
                                     "/log/munged.log --seed-file=" + d + "/munge/seed");
    if (munge.exitCode != 0) {
      error = "munged did not start: " + munge.output;
      return;
    }
    mungeStarted_ = true;
    const std::string host = trimmed(e2e::runShell("hostname -s").output);
    const std::string user = trimmed(e2e::runShell("id -un").output);
    const int port = 20000 + static_cast<int>(::getpid() % 20000);
    const long memoryMb = sysconf(_SC_PHYS_PAGES) / 1024 * sysconf(_SC_PAGESIZE) / 1024;
    std::ofstream conf(dir_ / "slurm.conf");
    conf << "ClusterName=surrogate-test\nSlurmctldHost=" << host << "(127.0.0.1)\n"
         << "SlurmctldPort=" << port << "\nSlurmdPort=" << port + 1 << "\n"
         << "AuthType=auth/munge\nAuthInfo=socket=" << dir_.string() << "/munge/socket\nCredType=cred/munge\n"
         << "SlurmUser=" << user << "\nSlurmdUser=" << user << "\n"
         << "StateSaveLocation=" << dir_.string() << "/state\nSlurmdSpoolDir=" << dir_.string() << "/spool\n"
         << "SlurmctldPidFile=" << dir_.string() << "/slurmctld.pid\nSlurmdPidFile=" << dir_.string() << "/slurmd.pid\n"
         << "SlurmctldLogFile=" << dir_.string() << "/log/slurmctld.log\nSlurmdLogFile=" << dir_.string() << "/log/slurmd.log\n"
         << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
         << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core_Memory\n"
         << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
         << "MpiDefault=none\nReturnToService=2\nJobRequeue=1\nSchedulerParameters=sched_interval=1\n"
         << "NodeName=" << host << " NodeAddr=127.0.0.1 CPUs=" << sysconf(_SC_NPROCESSORS_ONLN)
         << " RealMemory=" << memoryMb / 2 << " State=UNKNOWN\n"
         << "PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n";
    conf.close();
    env_ = "export SLURM_CONF=" + quote(dir_ / "slurm.conf") + " PATH=\"$PATH:/usr/sbin\"; ";
    if (e2e::runShell(env_ + "slurmctld -i -f " + quote(dir_ / "slurm.conf")).exitCode != 0 ||
        e2e::runShell(env_ + "slurmd -f " + quote(dir_ / "slurm.conf")).exitCode != 0) {
      error = "slurmctld or slurmd did not start: " + e2e::bytesOf(dir_ / "log/slurmctld.log") +
              e2e::bytesOf(dir_ / "log/slurmd.log");
      return;
    }
    for (int i = 0; i < 100; ++i) {
      if (trimmed(run("sinfo -h -o %T").output) == "idle") return;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    error = "the node did not become idle in 20 s: " + run("sinfo").output + e2e::bytesOf(dir_ / "log/slurmd.log");
  }

  ~SlurmCluster() {
    run("scancel --user=$(id -un)");
    // Only the daemons this test started, by the process ids they wrote.
    for (const char* pidFile : {"slurmd.pid", "slurmctld.pid", "munge/munged.pid"}) {
      const std::string pid = trimmed(e2e::bytesOf(dir_ / pidFile));
      if (!pid.empty() && pid.find_first_not_of("0123456789") == std::string::npos) {
        ::kill(std::stoi(pid), SIGTERM);
        for (int i = 0; i < 50 && ::kill(std::stoi(pid), 0) == 0; ++i)
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  e2e::CommandResult run(const std::string& command) const { return e2e::runShell(env_ + command); }

  // The daemons' last log lines, to say why a job did not start.
  std::string logTail() const {
    return e2e::runShell("tail -n 15 " + quote(dir_ / "log/slurmd.log") + " " + quote(dir_ / "log/slurmctld.log")).output;
  }

  std::string error;

 private:
  static std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  }
  fs::path dir_;
  std::string env_;
  bool mungeStarted_ = false;
};

}  // namespace

TEST_CASE("a Slurm job array does the batch with one task killed and requeued and the ledger shows each capture done once",
          "[batch][slurm]") {
  // The captures, list and ledger under a folder with a space (sbatch splits #SBATCH values
  // at blanks); the cluster's own files apart (SlurmCluster: a short path).
  const fs::path dir = e2e::freshDir("batch slurm");
  SlurmCluster cluster;
  if (!cluster.error.empty()) {
    WARN("single-host Slurm cluster could not start, test skipped: " << cluster.error);
    return;
  }
  const fs::path list = makeCaptures(dir, 6);
  const fs::path ledger = dir / "ledger.jsonl";
  const auto emitted = e2e::runShell("cd " + quote(dir) + " && " + SURROGATE_EXE + " batch " + quote(list) + " -o " +
                                     quote(ledger) + " --jobs 2 --memory 512M --no-report --emit slurm");
  REQUIRE(emitted.exitCode == 0);
  CHECK(emitted.output.find("#SBATCH --array=1-6%2") != std::string::npos);
  CHECK(emitted.output.find("#SBATCH --mem=640M") != std::string::npos);
  CHECK(emitted.output.find("#SBATCH --requeue") != std::string::npos);
  // Task 1's first attempt does the run step, then hangs where a slow pack would be, so that
  // the test kills it while it runs whatever the machine's speed (polling for a short task in
  // the R state missed it on a fast machine). The requeued attempt must take the capture on
  // from there: its run not redone, one pack.
  const std::string script = emitted.output;
  const std::size_t execAt = script.find("\nexec ");
  REQUIRE(execAt != std::string::npos);
  std::string command = script.substr(execAt + 6);
  command = command.substr(0, command.find('\n'));
  const fs::path hanging = dir / "task1-hanging";
  std::ofstream(dir / "array.sh") << script.substr(0, execAt + 1)
                                  << "if [ \"$SLURM_ARRAY_TASK_ID\" = 1 ] && [ \"${SLURM_RESTART_COUNT:-0}\" = 0 ]; then\n  "
                                  << command << " --do run\n  touch " << quote(hanging) << "\n  sleep 600\nfi\n"
                                  << script.substr(execAt + 1);
  const auto submitted = cluster.run("cd " + quote(dir) + " && sbatch --parsable " + quote(dir / "array.sh"));
  INFO(submitted.output);
  REQUIRE(submitted.exitCode == 0);
  const std::string job = submitted.output.substr(0, submitted.output.find_first_of(";\n"));
  bool requeued = false;
  bool launchFailed = false;
  for (int i = 0; i < 1200 && !requeued && !launchFailed; ++i) {
    if (fs::exists(hanging)) requeued = cluster.run("scontrol requeue " + job + "_1").exitCode == 0;
    else std::this_thread::sleep_for(std::chrono::milliseconds(100));
    launchFailed = cluster.run("squeue -h -o %r").output.find("launch failed") != std::string::npos;
  }
  INFO(cluster.run("squeue").output << cluster.logTail());
  REQUIRE(!launchFailed);
  REQUIRE(requeued);
  bool released = false;
  for (int i = 0; i < 300 && !released; ++i) {
    // Once the kill is complete, the task waits for its begin time: moved to now.
    if (cluster.run("squeue -h -j " + job + "_1 -o %r").output.find("BeginTime") != std::string::npos)
      released = cluster.run("scontrol update jobid=" + job + "_1 StartTime=now").exitCode == 0;
    if (!released) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  CHECK(released);
  bool finished = false;
  for (int i = 0; i < 600 && !finished; ++i) {
    finished = cluster.run("squeue -h -j " + job).output.empty();
    if (!finished) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  REQUIRE(finished);
  CHECK(cluster.run("scontrol show job " + job + "_1").output.find("Restarts=1") != std::string::npos);
  // The tasks' output where the script's quoted #SBATCH --output put it, space and all.
  CHECK(fs::exists(dir / ("ledger.jsonl.slurm-" + job + "_1.out")));
  CHECK(fs::exists(dir / ("ledger.jsonl.slurm-" + job + "_6.out")));

  const auto summary = e2e::surrogate("batch --summary -o " + quote(ledger) + " --json");
  INFO(summary.output << e2e::bytesOf(ledger));
  CHECK(summary.exitCode == 0);
  const json s = json::parse(summary.output);
  CHECK(s["items"] == 6);
  CHECK(s["done"] == 6);
  CHECK(s["failed"] == 0);
  const std::vector<json> lines = ledgerLines(ledger);
  for (int i = 1; i <= 6; ++i) {
    const std::string cap = (dir / ("cap" + std::to_string(i))).string();
    CHECK(count(lines, cap, "run", 0) == 1);
    CHECK(count(lines, cap, "pack", 0) == 1);
    CHECK(count(lines, cap, "verify", 0) == 1);
  }
}
