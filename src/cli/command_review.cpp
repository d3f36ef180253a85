// surrogate review CAPTURE [--port N] [--no-browser]: the capture's decisions in a local page
// (src/review). The page's Apply runs here exactly as `surrogate run CAPTURE OPTIONS` would:
// the same parse of the options (requestFrom), the same run (run::runCapture) under the capture's
// lock, the same report afterwards.
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "capture/capture.h"
#include "capture/lock.h"
#include "cli/args.h"
#include "core/identity.h"
#include "cli/commands.h"
#include "cli/option_checks.h"
#include "cli/pipeline_options.h"
#include "core/error.h"
#include "core/temp_dir.h"
#include "core/text.h"
#include "report/report.h"
#include "review/review.h"
#include "run/plan.h"
#include "run/run_commit.h"

extern char** environ;

namespace surrogate::cli {

namespace {

// The page's address, key included, in a file only this account can read (a private temporary
// folder), which sends the browser on to it: what the browser is started with is a program's
// argument, which every account of the computer can read (ps, /proc), and the key must not be
// among them.
std::string launcherFile(const TempDir& folder, const std::string& url) {
  const std::filesystem::path file = folder.path() / "open-review.html";
  std::ofstream out(file);
  // The address is 127.0.0.1, a port and hexadecimal digits: nothing in it needs escaping.
  out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
      << "<meta http-equiv=\"refresh\" content=\"0;url=" << url << "\"><title>Surrogate review</title></head>\n"
      << "<body><p><a href=\"" << url << "\">Open the review page</a></p></body></html>\n";
  out.close();
  if (!out)
    throw Error(ErrorKind::Internal, file.string(), "review",
                "could not write the file that opens the page in the browser; give --no-browser and open the "
                "address printed by hand");
  return file.string();
}

// Opens the page at `url` with the desktop's browser (xdg-open; open on macOS) when there is a
// desktop, without waiting for it, through a launcher file in `launcher` (made here, removed
// with it); says so when there is no desktop.
void openBrowser(const std::string& url, std::optional<TempDir>& launcher, bool quiet) {
#ifdef __APPLE__
  const char* opener = "open";
  const bool desktop = true;
#else
  const char* opener = "xdg-open";
  const bool desktop = std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY");
#endif
  if (!desktop) {
    if (quiet) return;
    std::cout << "  (no desktop here to open a browser in: open the address in a browser on this computer)\n";
    return;
  }
  launcher.emplace("review");
  const std::string target = launcherFile(*launcher, url);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, "/dev/null", O_WRONLY, 0);
  std::string program = opener, address = target;
  char* argv[] = {program.data(), address.data(), nullptr};
  pid_t pid = 0;
  const int failed = posix_spawnp(&pid, opener, &files, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&files);
  if (failed) {
    std::cout << "  (" << opener << " could not be started: open the address in a browser on this computer)\n";
    return;
  }
  std::thread([pid] { waitpid(pid, nullptr, 0); }).detach();
}

}  // namespace

int runCommandReview(int argc, char** argv) {
  const std::vector<OptionSpec> specs = {
      {"operator", true, false, "who takes the decisions (recorded with each; default $USER)", "NAME",
       OptionGroup::Decisions},
      {"threads", true, false, "worker threads for the runs (default: all cores); results do not depend on it", "N"},
      {"memory", true, false, "memory budget for the runs' streaming work (default 2G)", "SIZE"},
      {"port", true, false, "serve the page on this port of 127.0.0.1 (default 0: a free port, printed)", "N",
       OptionGroup::Output},
      {"no-browser", false, false, "do not open the page in the desktop's browser; only print its address", "",
       OptionGroup::Output},
      {"quiet", false, false, "print the page's address only, and errors", "", OptionGroup::Output},
      {"verbose", false, false, "also each step an Apply runs, as it starts", "", OptionGroup::Output},
  };
  Args args(argc, argv, 1, specs);
  const Verbosity verbosity = verbosityOf(args);
  if (helpShown(args, specs,
                {"surrogate review CAPTURE [options]",
                 "Review a capture in a browser page on this computer: every frame with its sphere and "
                 "highlight, the light directions, the checks and the decisions. Drag a sphere's circle, "
                 "click a highlight, leave a frame out with a reason, accept a check, type the title, "
                 "creator, rights and licence; Apply records each as `surrogate run` records the same "
                 "options (who, when, why) and runs what they change. The page is served on 127.0.0.1 "
                 "only, at an address holding a key made for this review (only that address opens it); "
                 "Ctrl+C stops it.",
                 {{"surrogate review stela12", "open the capture stela12 in the desktop's browser"},
                  {"surrogate review stela12 --no-browser --port 8642 --operator \"Ana Silva\"",
                   "serve it on a chosen port, for a browser opened by hand, recording Ana Silva's decisions"}},
                 {{0, "stopped with Ctrl+C (or SIGTERM)"},
                  {1, "the folder is not a capture, or the port given is taken"},
                  {2, "bad usage: an unknown option, a port outside 0..65535"},
                  {5, kInternalError}}}))
    return 0;
  if (args.positional().size() != 1)
    throw Error(ErrorKind::Usage, "", "command line",
                "give exactly one capture folder: surrogate review CAPTURE (see --help)");
  const std::string capture = args.positional()[0];
  refuseCaptureSubfolder(capture, "review");
  capture::requireCaptureFolder(capture);
  const int port = args.intValue("port", 0);
  const int threads = threadsOption(args);
  pipeline::RunSettings base = settingsFrom(args);  // --threads, --memory, --operator checked now

  review::ReviewOptions options;
  options.capture = capture;
  options.port = port;
  options.threads = threads;
  if (const auto who = args.value("operator")) options.leadingOptions = {"--operator", *who};
  options.who = args.value("operator", "");
  if (options.who.empty()) options.who = currentUserName();
  // An Apply: the options parsed as `surrogate run` parses its own, run as it runs, the report
  // written after it under the same lock.
  options.runner = [capture, base, verbosity](const std::vector<std::string>& given, const std::string& revision,
                                              const review::ProgressFunction& pageProgress) {
    // --verbose: each step's label once, as the run reaches it.
    auto lastLabel = std::make_shared<std::string>();
    const review::ProgressFunction progress = [pageProgress, verbosity, lastLabel](const std::string& label, double f) {
      if (verbosity == Verbosity::Verbose && label != *lastLabel) {
        *lastLabel = label;
        std::cout << "  running: " << escapedText(label) << std::endl;
      }
      if (pageProgress) pageProgress(label, f);
    };
    std::vector<std::string> words = {"run", capture};
    words.insert(words.end(), given.begin(), given.end());
    std::vector<char*> argvRun;
    for (std::string& w : words) argvRun.push_back(w.data());
    std::vector<OptionSpec> runSpecs = pipelineOptions(true);
    const Args runArgs(static_cast<int>(argvRun.size()), argvRun.data(), 1, runSpecs);
    run::RunRequest request = requestFrom(runArgs);
    // Recorded as the `surrogate run` command line it stands for (the page shows it before
    // Apply, and the server prints it after): the decisions and the carrier are the same
    // whether they were typed or made in the page, byte for byte apart from times.
    pipeline::RunSettings settings = base;
    settings.who = runArgs.value("operator", "");
    settings.progress = progress;
    capture::CaptureLock lock(capture, "review");
    // A commit a killed command left half-done puts its run's carrier in place when it is
    // finished, a record the page never showed: finished first, so that the page's revision is
    // checked against the record the run would build on (409 when it changed).
    if (run::pendingKind(capture) == run::PendingRecovery::Kind::FinishCommit) run::recoverRun(capture);
    review::requireRevision(capture, revision);  // a commit between the page's check and the lock
    run::runCapture(capture, request, settings, /*takeLock=*/false);
    report::ReportOptions reportOptions;
    reportOptions.threads = settings.threads;
    reportOptions.progress = progress;
    report::writeCaptureReport(capture, reportOptions);
  };
  options.applied = [capture, verbosity](const std::vector<std::string>& given, const std::string& outcome) {
    if (verbosity == Verbosity::Quiet) return;
    std::string line;
    // A command line the user can copy: each word quoted for the shell, control bytes escaped.
    for (const std::string& g : given) line += " " + escapedText(shellWord(g));
    std::cout << (outcome == "applied" ? "applied, as: surrogate run " : "not applied: surrogate run ")
              << escapedText(shellWord(capture)) << line << "\n";
    if (outcome != "applied") std::cout << "  " << escapedText(outcome) << "\n";
    std::cout.flush();
  };

  // Ctrl+C and SIGTERM end the serving, from a thread of their own (httplib's threads inherit
  // the blocked signals, so none of them is interrupted).
  sigset_t stopSignals;
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);
  review::ReviewServer server(std::move(options));
  std::thread waiter([&server, stopSignals] {
    int signal = 0;
    sigwait(&stopSignals, &signal);
    server.stop();
  });

  // With the key (review/access_key.h): only whoever sees this address can use the page.
  const std::string url = server.address();
  std::cout << "Review of " << escapedText(capture) << ": " << url << "\n";
  if (verbosity != Verbosity::Quiet) std::cout << "  open it in a browser on this computer; Ctrl+C stops the review.\n";
  std::optional<TempDir> launcher;  // removed when the review stops
  if (!args.has("no-browser")) openBrowser(url, launcher, verbosity == Verbosity::Quiet);
  std::cout.flush();
  server.serve();
  pthread_kill(waiter.native_handle(), SIGTERM);  // a no-op for the waiter when a signal ended it
  waiter.join();
  if (verbosity != Verbosity::Quiet) std::cout << "Review stopped.\n";
  return 0;
}

}  // namespace surrogate::cli
