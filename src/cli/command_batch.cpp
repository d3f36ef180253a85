// surrogate batch LIST -o LEDGER [--do run,pack,verify] [--jobs N] [--memory SIZE] [options]
#include <chrono>
#include <cmath>
#include <map>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <thread>

#include "batch/jobs.h"

#include "batch/batch.h"
#include "batch/ledger.h"
#include "batch/work_list.h"
#include "capture/capture.h"
#include "capture/output_rule.h"
#include "cli/args.h"
#include "cli/batch_summary.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "core/error.h"
#include "core/json.h"
#include "core/memory_budget.h"
#include "core/text.h"

namespace surrogate::cli {

namespace {

std::vector<OptionSpec> batchOptions() {
  constexpr OptionGroup kInput = OptionGroup::Input, kOutput = OptionGroup::Output;
  return {
      {"one", true, false, "do only the Nth item of the list (1 is the first; for GNU parallel and Slurm)", "N", kInput},
      {"do", true, false, "the steps, in this order, of run, pack and verify (default run,pack,verify)", "STEPS"},
      {"jobs", true, false, "jobs at a time, each a process of its own (default 1)", "N"},
      {"memory", true, false,
       "memory of each job: it streams within three quarters of it (run --memory), and is stopped (recorded as "
       "such, the others go on) when its resident memory passes it (default: no limit)",
       "SIZE"},
      {"threads", true, false, "worker threads of each job (default: the cores shared among the jobs)", "N"},
      {"retries", true, false, "attempts of a failed step after the first, in this batch (default 1)", "N"},
      {"reexecute", false, false, "verify re-executes the recorded steps (verify --reexecute)"},
      {"dry-run", false, false, "say what would be done for each item, do nothing"},
      {"o", true, false, "the ledger: one JSON line per job, step and attempt, appended (shared by several batches)",
       "LEDGER", kOutput},
      {"output", true, false, "same as -o", "LEDGER", kOutput},
      {"packages", true, false, "write each capture's package into this folder (default: beside the capture), named CAPTURE.zip",
       "DIR", kOutput},
      {"package-format", true, false, "zip (default) or tar: the serialization of each package (CAPTURE.zip or CAPTURE.tar)",
       "FORMAT", kOutput},
      {"no-report", false, false, "run and pack write no finished-files/report.html", "", kOutput},
      {"emit", true, false,
       "print a script that runs this batch on GNU parallel (parallel) or as a Slurm job array (slurm), one --one N a "
       "job or task",
       "ENGINE", kOutput},
      {"summary", false, false,
       "read the ledger (-o LEDGER, or LEDGER alone) and report where each item stands, without doing anything", "",
       kOutput},
      {"json", false, false, "print the result (or --summary) as one JSON object", "", kOutput},
      {"quiet", false, false, "no progress bar and no line per job: one summary line", "", kOutput},
      {"verbose", false, false, "also say each item's plan before the work, and each step's attempts", "", kOutput},
  };
}

int positiveOption(const Args& args, const std::string& name, int fallback, int least) {
  const int n = args.intValue(name, fallback);
  if (n < least)
    throw Error(ErrorKind::Usage, "--" + name, "command line",
                "give a whole number, " + std::to_string(least) + " or more, not " + std::to_string(n));
  return n;
}

std::vector<std::string> stepsOf(const std::string& text) {
  std::vector<std::string> steps;
  std::stringstream in(text);
  std::string s;
  while (std::getline(in, s, ',')) {
    if (std::find(batch::kSteps.begin(), batch::kSteps.end(), s) == batch::kSteps.end())
      throw Error(ErrorKind::Usage, "--do " + text, "command line",
                  "\"" + s + "\" is not a step: give run, pack and/or verify, separated by commas");
    if (std::find(steps.begin(), steps.end(), s) != steps.end())
      throw Error(ErrorKind::Usage, "--do " + text, "command line", "names " + s + " twice");
    steps.push_back(s);
  }
  // They run in their one possible order whatever the order given.
  std::vector<std::string> ordered;
  for (const std::string& k : batch::kSteps)
    if (std::find(steps.begin(), steps.end(), k) != steps.end()) ordered.push_back(k);
  if (ordered.empty()) throw Error(ErrorKind::Usage, "--do", "command line", "give run, pack and/or verify");
  return ordered;
}

std::string duration(double seconds) {
  char text[32];
  if (seconds < 60) std::snprintf(text, sizeof text, "%.1f s", seconds);
  else if (seconds < 3600) std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
  return text;
}

// --emit parallel: a script that runs one `surrogate batch --one N` per item under GNU
// parallel, which keeps its own job log, reruns the failed ones and starts a job only when
// enough memory is free.
//
// parallel joins its command's words into one line for a shell, and reads replacement strings
// ({}, {.}, and {= perl =} as code) in every word: a name in the command (a list
// "l$(touch X).txt", --packages "pk;touch X;", "x{= system(...) =}") would run. So the command
// holds only fixed words and replacement strings; each word that is a name (the program, the
// list, the ledger, --packages) is an input source of one value (::: VALUE), substituted as
// data and quoted by --quote, and the item number is the last source. --null reads every
// source whole, a name with a line break included (parallel splits ::: values at line breaks
// otherwise); the script's own shell reads each value in single quotes. A relative path gets
// "./": no name can then start with '-' (an option) or be ":::" (a source's separator).
void emitParallel(const std::string& list, std::size_t items, const std::vector<std::string>& passOn,
                  int jobs, const std::string& ledger, const std::string& memory) {
  const auto asPath = [](const std::string& path) {
    return std::filesystem::path(path).is_absolute() || path.rfind("./", 0) == 0 ? path : "./" + path;
  };
  std::vector<std::string> sources;
  std::string command;
  const auto word = [&](const std::string& w, bool name) {
    if (!name && shellWord(w) == w) {  // a fixed word: letters, digits, . / , : - = and the like
      command += " " + w;
      return;
    }
    sources.push_back(w);
    command += " {" + std::to_string(sources.size()) + "}";
  };
  word(batch::selfExecutable(), true);
  word("batch", false);
  word(asPath(list), true);
  word("-o", false);
  word(asPath(ledger), true);
  for (std::size_t i = 0; i < passOn.size(); ++i) {
    const bool isPath = i > 0 && passOn[i - 1] == "--packages";
    word(isPath ? asPath(passOn[i]) : passOn[i], isPath);
  }
  command += " --one {" + std::to_string(sources.size() + 1) + "}";
  std::cout << "#!/bin/sh\n"
               "# GNU parallel runs the batch of " << escapedText(list) << ", one `surrogate batch --one N` a job;\n"
               "# run this again to rerun the failed jobs (--resume-failed, from the job log). Names are\n"
               "# given to parallel as data (::: sources, --null, --quote), never as part of its command.\n"
               "seq 1 " << items << " | tr '\\n' '\\000' | parallel --null --jobs " << jobs
            << " --joblog " << shellWord(asPath(ledger) + ".joblog") << " --resume-failed";
  if (!memory.empty()) std::cout << " --memfree " << shellWord(memory);
  std::cout << " --quote \\\n " << command << " \\\n ";
  for (const std::string& source : sources) std::cout << " ::: " << shellWord(source);
  std::cout << " :::: -\n";
}

// The files of a capture's largest folder of photographs (its images, for the time a task
// takes): original-captures/, raw-images/ or jpeg-exports/, whichever holds most.
std::size_t imagesOf(const std::string& capture) {
  std::size_t most = 0;
  for (const char* folder : surrogate::capture::kSourceFolders) {
    std::error_code ec;
    std::size_t n = 0;
    for (std::filesystem::directory_iterator it(std::filesystem::path(capture) / folder, ec), end; !ec && it != end;
         it.increment(ec))
      n += it->is_regular_file(ec);
    most = std::max(most, n);
  }
  return most;
}

// A task's time limit, minutes: the slowest image cost the ledger records (a capture's steps'
// seconds over its images) times the largest capture of the list, three times over for a
// busier node, at least kLeastTaskMinutes; kUnmeasuredTaskMinutes when the ledger has no
// finished capture to measure.
constexpr int kLeastTaskMinutes = 10;
constexpr int kUnmeasuredTaskMinutes = 120;

int taskMinutes(const std::vector<batch::WorkItem>& items, const std::string& ledgerPath, std::string& how) {
  const batch::Ledger ledger = batch::readLedger(ledgerPath);
  std::map<std::string, double> seconds;
  for (const batch::LedgerEntry& e : ledger.entries)
    if (e.succeeded() && !e.adopted) seconds[e.capture] += e.seconds;
  double perImage = 0;
  std::map<std::string, std::string> where;  // the list's items by their ledger name
  for (const batch::WorkItem& item : items) where[item.path] = item.where();
  for (const auto& [capture, s] : seconds)
    if (const std::size_t n = imagesOf(where.count(capture) ? where[capture] : capture); n > 0) perImage = std::max(perImage, s / static_cast<double>(n));
  std::size_t largest = 0;
  for (const batch::WorkItem& item : items) largest = std::max(largest, imagesOf(item.where()));
  if (perImage <= 0 || largest == 0) {
    how = "no finished capture in the ledger to measure: " + std::to_string(kUnmeasuredTaskMinutes) + " minutes";
    return kUnmeasuredTaskMinutes;
  }
  const double minutes = std::ceil(3 * perImage * static_cast<double>(largest) / 60);
  char text[160];
  std::snprintf(text, sizeof text, "%.2f s an image measured in the ledger x %zu images x 3", perImage, largest);
  how = text;
  return std::max(kLeastTaskMinutes, static_cast<int>(minutes));
}

// A value of an #SBATCH line: sbatch splits those lines at blanks, like a shell, and reads a
// double-quoted value whole (a path with spaces, a # that would start a comment).
std::string sbatchValue(const std::string& value) {
  if (value.find_first_of(" \t\"\\#'") == std::string::npos) return value;
  std::string quoted = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

// --emit slurm: a job-array script, one task per item, each a `surrogate batch --one N`
// appending to the shared ledger; requeued tasks start their item again, which skips what is
// done. The task works in the folder the script was made in (relative paths among the passed
// options), entered by the script's shell rather than by #SBATCH --chdir, whose value sbatch
// would split at a space.
void emitSlurm(const std::string& list, const std::vector<batch::WorkItem>& items, const std::vector<std::string>& passOn,
               int jobs, int threads, const std::string& ledger, std::uint64_t memory) {
  namespace fs = std::filesystem;
  const std::string absList = fs::absolute(list).lexically_normal().string();
  const std::string absLedger = fs::absolute(ledger).lexically_normal().string();
  for (const std::string& path : {absList, absLedger, fs::current_path().string()})
    if (path.find_first_of("\n\r") != std::string::npos)
      throw Error(ErrorKind::Usage, escapedText(path), "command line",
                  "a path with a line break cannot be written in a Slurm script; rename it");
  std::string how;
  const int minutes = taskMinutes(items, ledger, how);
  std::cout << "#!/bin/sh\n"
               "# Slurm runs the batch of " << escapedText(absList) << " as a job array, one `surrogate batch --one N` a task\n"
               "# appending to " << escapedText(absLedger) << "; a requeued task does its item again, skipping what is done.\n"
               "# Submit with sbatch; report with: surrogate batch --summary -o " << shellWord(absLedger) << "\n"
               "#SBATCH --job-name=surrogate-batch\n"
               "#SBATCH --array=1-" << items.size() << "%" << jobs << "\n"
               "#SBATCH --cpus-per-task=" << threads << "\n";
  // Slurm's limit a quarter above the job's budget: the job's own stop, with its message in
  // the ledger, comes first.
  if (memory > 0) std::cout << "#SBATCH --mem=" << (memory / 4 * 5 + (1u << 20) - 1) / (1u << 20) << "M\n";
  std::cout << "#SBATCH --time=" << minutes << "\n"
               "#SBATCH --requeue\n"
               "#SBATCH --open-mode=append\n"
               "#SBATCH --output=" << sbatchValue(absLedger + ".slurm-%A_%a.out") << "\n"
               "# time per task: " << how << "\n"
               "cd " << shellWord(fs::current_path().string()) << " || exit 1\n"
               "exec " << shellWord(batch::selfExecutable()) << " batch " << shellWord(absList) << " -o "
            << shellWord(absLedger);
  for (const std::string& a : passOn) std::cout << " " << shellWord(a);
  std::cout << " --one \"$SLURM_ARRAY_TASK_ID\"\n";
}

}  // namespace

int runCommandBatch(int argc, char** argv) {
  const std::vector<OptionSpec> specs = batchOptions();
  Args args(argc, argv, 1, specs);
  if (helpShown(args, specs,
                {"surrogate batch LIST -o LEDGER [--do run,pack,verify] [--jobs N] [--memory SIZE] [options]",
                 "Process a backlog: LIST is a text file (or - for standard input) of capture folders or "
                 "packages, one a line (# starts a comment). Each capture is taken through the steps of --do, each "
                 "step the ordinary command (surrogate run, pack -o CAPTURE.zip, verify) in a process of its own "
                 "holding the capture's lock; a package is verified. LEDGER gets one JSON line per job, step and "
                 "attempt (appended whole under a lock, so that several batches can share it). Running the same "
                 "command again skips what the ledger records as done and what is unchanged since (the carrier's "
                 "and package's SHA-256), retries failures and never packs a capture twice. --summary reads a "
                 "ledger and reports; --emit parallel prints a script for GNU parallel, --emit slurm a Slurm "
                 "job-array script. When steps failed, the exit code is the highest of theirs.",
                 {{"surrogate batch captures.txt -o backlog.jsonl --jobs 2 --memory 4G",
                   "run, pack and verify every capture of the list, two at a time; run it again after a crash to "
                   "finish the rest"},
                  {"surrogate batch captures.txt -o backlog.jsonl --emit slurm > backlog.sbatch",
                   "the same as a Slurm job array, to submit with sbatch backlog.sbatch"}},
                 {{0, "every job done"},
                  {1, "bad input: the list is not a regular file or standard input, or not a text list of paths "
                      "(a NUL byte, over 64 MiB, a line over 4096 bytes), names something that is neither a capture "
                      "nor a package, the ledger is a file no command may write (an original, a package, the list, a "
                      "link, a device) or not a ledger, a step failed on bad input, or " + std::string(kWriteRefused)},
                  {2, "bad usage (a list naming one capture twice, by its real path, or nothing), or a step found an "
                      "invalid package"},
                  {3, "a verify step found a fixity failure"},
                  {4, "a verify --reexecute step did not reproduce the recorded results"},
                  {5, "internal error: a bug, a crash, or a job stopped for passing its memory budget"}}}))
    return 0;
  const auto ledger = outputOption(args);
  if (args.has("summary")) {
    // The ledger with -o, or as the one argument: surrogate batch --summary LEDGER.
    if (ledger ? !args.positional().empty() : args.positional().size() != 1)
      throw Error(ErrorKind::Usage, "", "command line", "give the ledger only: surrogate batch --summary -o LEDGER");
    return printBatchSummary(ledger ? *ledger : args.positional()[0], args.has("json"));
  }
  if (args.positional().size() != 1 || !ledger || ledger->empty())
    throw Error(ErrorKind::Usage, "", "command line",
                "give the list and the ledger: surrogate batch LIST -o LEDGER (see --help)");
  const std::string list = args.positional()[0];
  batch::BatchOptions o;
  o.ledger = *ledger;
  batch::checkLedgerTarget(*ledger, list);  // appending is writing: the output rule, before any job
  o.steps = stepsOf(args.value("do", "run,pack,verify"));
  o.jobs = positiveOption(args, "jobs", 1, 1);
  o.threadsPerJob = positiveOption(args, "threads", 0, 0);
  o.retries = positiveOption(args, "retries", 1, 0);
  if (const auto m = args.value("memory")) o.memory = parseByteSize(*m, "--memory");
  if (const auto p = args.value("packages")) {
    std::error_code ec;
    if (!std::filesystem::is_directory(*p, ec))
      throw Error(ErrorKind::Usage, "--packages " + *p, "command line", "is not a folder; make it first");
    // pack's rule for its -o, checked once for the whole list: a packages folder inside a
    // capture was found only at each capture's pack step, each a failed job.
    if (surrogate::capture::hasSourceFolder(*p))
      throw Error(ErrorKind::Input, "--packages " + *p, "command line",
                  "is a capture folder, where packages would become part of the capture's record; choose a "
                  "folder outside every capture");
    surrogate::capture::checkOutputTarget(*p, "--packages", surrogate::capture::ExistingOutput::Replace,
                                          surrogate::capture::OutputPlace::OutsideCaptures);
    o.packagesDir = *p;
  }
  o.packageFormat = args.value("package-format", "zip");
  if (o.packageFormat != "zip" && o.packageFormat != "tar")
    throw Error(ErrorKind::Usage, "--package-format " + o.packageFormat, "command line",
                "give zip or tar (a package folder, OCFL object or E-ARK SIP is surrogate pack's, one capture at a time)");
  o.reexecute = args.has("reexecute");
  o.noReport = args.has("no-report");
  o.dryRun = args.has("dry-run");
  std::vector<batch::WorkItem> items = batch::readWorkList(list);

  if (const auto engine = args.value("emit")) {
    if (*engine != "parallel" && *engine != "slurm")
      throw Error(ErrorKind::Usage, "--emit " + *engine, "command line",
                  "give parallel (GNU parallel) or slurm (a Slurm job-array script)");
    if (list == "-")
      throw Error(ErrorKind::Usage, "--emit", "command line", "needs the list in a file, which each job reads again");
    std::vector<std::string> passOn;
    for (const auto& [name, value] : args.ordered()) {
      if (name == "emit" || name == "o" || name == "output" || name == "jobs" || name == "quiet" || name == "verbose" || name == "one")
        continue;
      passOn.push_back(optionName(name));
      if (!value.empty()) passOn.push_back(value);
    }
    // Each job's share of the cores, as the batch gives it; a Slurm task, its own core.
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int threads = args.has("threads") ? o.threadsPerJob : *engine == "slurm" ? 1 : std::max(1, cores / o.jobs);
    if (!args.has("threads")) {
      passOn.push_back("--threads");
      passOn.push_back(std::to_string(threads));
    }
    passOn.push_back("--quiet");
    if (*engine == "slurm") emitSlurm(list, items, passOn, o.jobs, threads, *ledger, o.memory);
    else emitParallel(list, items.size(), passOn, o.jobs, *ledger, args.value("memory", ""));
    return 0;
  }
  if (args.has("one")) {
    const int n = positiveOption(args, "one", 1, 1);
    if (static_cast<std::size_t>(n) > items.size())
      throw Error(ErrorKind::Usage, "--one " + std::to_string(n), "command line",
                  "the list holds " + std::to_string(items.size()) + " item(s)");
    items = {items[static_cast<std::size_t>(n - 1)]};
    o.jobs = 1;
  }

  const Verbosity verbosity = verbosityOf(args);
  const bool quiet = verbosity == Verbosity::Quiet || args.has("json");
  const bool verbose = verbosity == Verbosity::Verbose && !args.has("json");
  if (const std::string note = batch::listFolderNote(list, items); !quiet && !note.empty()) std::cout << note << "\n";
  ProgressBar bar(quiet);
  const auto started = std::chrono::steady_clock::now();
  std::size_t worked = 0;
  JsonWriter planJson;
  if (args.has("json") && o.dryRun)
    planJson.beginObject().key("list").value(list).key("ledger").value(*ledger).key("dryRun").value(true)
        .key("items").beginArray();
  o.plan = [&](const batch::ItemPlan& plan) {
    if (args.has("json")) {
      planJson.beginObject().key(plan.item.isPackage ? "package" : "capture").value(plan.item.path).key("steps").beginArray();
      for (const batch::PlannedStep& p : plan.steps) {
        planJson.beginObject().key("step").value(p.step).key("skipped").value(p.skipped);
        if (!p.package.empty()) planJson.key("package").value(p.package);
        if (!p.skipped) planJson.key("why").value(p.why);
        planJson.endObject();
      }
      planJson.endArray().endObject();
      return;
    }
    std::string line = plan.item.path + ":";
    for (const batch::PlannedStep& p : plan.steps) {
      line += " " + p.step;
      if (p.skipped) line += " done (skipped)";
      else line += (p.step == "pack" ? " into " : p.step == "verify" ? " " : "") + p.package + " (" + p.why + ")";
      line += ";";
    }
    if (!plan.steps.empty()) line.pop_back();
    std::cout << escapedText((verbose && !o.dryRun ? "plan  " : "") + line) << "\n";
  };
  if (!o.dryRun && !verbose) o.plan = nullptr;
  o.jobFinished = [&](const batch::JobReport& r) {
    worked += r.workDone;
    if (quiet) return;
    std::ostringstream line;
    line << (r.succeeded ? "done  " : "FAIL  ") << r.item.path << ":";
    for (const batch::StepOutcome& s : r.steps) {
      line << " " << s.step << " ";
      if (s.outcome == "done") line << duration(s.seconds) << (s.peakMemory ? ", " + memorySize(s.peakMemory) : "");
      else if (s.outcome == "failed") line << "FAILED (exit " << s.exit << "): " << s.message;
      else line << s.outcome;
      line << ";";
    }
    std::string text = line.str();
    text.pop_back();
    bar.finish();
    std::cout << escapedText(text) << std::endl;
    if (!verbose) return;
    for (const batch::StepOutcome& s : r.steps)
      if (s.attempts > 0)
        std::cout << "      " << s.step << ": " << s.outcome << " after " << s.attempts
                  << (s.attempts == 1 ? " attempt" : " attempts") << " in this batch\n";
  };
  o.waiting = [&](const batch::WorkItem& item, const std::string& why) {
    if (quiet) return;
    bar.finish();
    std::cout << escapedText("wait  " + item.path + ": " + why + "; the batch comes back to it") << std::endl;
  };
  o.progress = [&](std::size_t finished, std::size_t total) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::string label = "batch: " + std::to_string(finished) + " of " + std::to_string(total) + " jobs finished";
    if (worked > 0 && finished < total)
      label += ", about " + duration(elapsed / static_cast<double>(worked) * static_cast<double>(total - finished)) + " left";
    bar.update(label, static_cast<double>(finished) / static_cast<double>(total));
  };
  const batch::BatchResult r = batch::runBatch(items, o);
  bar.finish();
  if (o.dryRun) {
    if (args.has("json")) std::cout << planJson.endArray().endObject().str() << "\n";
    return 0;
  }
  if (args.has("json")) {
    JsonWriter j;
    j.beginObject().key("list").value(list).key("ledger").value(*ledger)
        .key("items").value(static_cast<unsigned long long>(r.items))
        .key("succeeded").value(static_cast<unsigned long long>(r.succeeded))
        .key("failed").value(static_cast<unsigned long long>(r.failed))
        .key("untouched").value(static_cast<unsigned long long>(r.untouched))
        .key("exitCode").value(r.exitCode).endObject();
    std::cout << j.str() << "\n";
  } else {  // --quiet too: its one summary line
    std::cout << "Batch of " << r.items << ": " << r.succeeded << " done (" << r.untouched
              << " of them done before), " << r.failed << " failed; ledger " << escapedText(*ledger) << "\n";
  }
  return r.exitCode;
}

}  // namespace surrogate::cli
