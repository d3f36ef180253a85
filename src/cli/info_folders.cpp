// surrogate info on a package (archive::describePackage) or a capture folder
// (capture::describeCapture), as text or JSON.
#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "archive/bag.h"
#include "archive/package.h"
#include "archive/package_summary.h"
#include "capture/capture.h"
#include "capture/capture_summary.h"
#include "capture/lock.h"
#include "cli/info_print.h"
#include "core/text.h"
#include "run/run_commit.h"
#include "verify/held_bag.h"

namespace surrogate::cli {

namespace fs = std::filesystem;

namespace {

// A path as one shell word (core's shellWord), never starting with '-', which would read as an
// option.
std::string shellPath(const std::string& path) {
  return shellWord(!path.empty() && path[0] == '-' ? "./" + path : path);
}

// The commands that verify the package: fixity and records, and for a Surrogate package the
// re-execution of its recorded steps.
std::vector<std::string> verifyCommands(const fs::path& path, bool surrogate) {
  const std::string word = shellPath(path.string());
  std::vector<std::string> out = {"surrogate verify " + word};
  if (surrogate) out.push_back("surrogate verify " + word + " --reexecute");
  return out;
}

void printPackageJson(const fs::path& path, const archive::PackageSummary& s) {
  JsonWriter j;
  j.beginObject().key("kind").value("package").key("format").value(s.format)
      .key("surrogatePackage").value(s.surrogate)
      .key("files").value(static_cast<unsigned long long>(s.files))
      .key("bytes").value(static_cast<unsigned long long>(s.bytes));
  j.key("bagInfo").beginArray();
  for (const auto& [label, value] : s.bagInfo)
    j.beginObject().key("label").value(label).key("value").value(value).endObject();
  j.endArray().key("manifests").beginArray();
  for (const std::string& m : s.manifests) j.value(m);
  j.endArray().key("roles").beginArray();
  for (const archive::RoleTotal& t : s.roles)
    j.beginObject().key("role").value(t.role).key("files").value(static_cast<unsigned long long>(t.files))
        .key("bytes").value(static_cast<unsigned long long>(t.bytes)).endObject();
  j.endArray().key("results").beginArray();
  for (const auto& [file, bytes] : s.results)
    j.beginObject().key("path").value(file).key("bytes").value(static_cast<unsigned long long>(bytes)).endObject();
  j.endArray();
  if (s.carrier) {
    j.key("carrier");
    carrierJson(j, *s.carrier);
  } else if (!s.carrierProblem.empty()) {
    j.key("carrierProblem").value(s.carrierProblem);
  }
  j.key("verify").beginArray();
  for (const std::string& c : verifyCommands(path, s.surrogate)) j.value(c);
  j.endArray().endObject();
  std::cout << j.str() << "\n";
}

void printPackageText(const fs::path& path, const archive::PackageSummary& s) {
  std::cout << path.string() << ": " << (s.surrogate ? "Surrogate package" : "BagIt bag, not a Surrogate package")
            << " (" << s.format << ")\n";
  if (s.surrogate) {
    std::cout << "  identifier: " << s.bagInfoValue("Surrogate-Package-Identifier") << "\n"
              << "  capture:    " << s.bagInfoValue("Surrogate-Capture-Identifier") << "\n";
    if (const std::string previous = s.bagInfoValue("Surrogate-Previous-Package-Identifier"); !previous.empty())
      std::cout << "  revises:    " << previous << "\n";
    std::cout << "  packed:     " << s.bagInfoValue("Surrogate-Packaging-Time") << " by "
              << s.bagInfoValue("Bag-Software-Agent") << "\n";
    // Fields Surrogate does not write from the carrier: the holder's (pack --bag-info, or added
    // later), as verify lists them.
    if (s.carrier) {
      const archive::PackageInfo own = archive::packageInfo(*s.carrier, "", "");
      for (const auto& [label, value] : s.bagInfo)
        if (!archive::isSurrogateLabel(label, own))
          std::cout << "  holder's:   " << escapedText(label + ": " + value, true) << " (added by the holder)\n";
    }
  } else {
    for (const auto& [label, value] : s.bagInfo) std::cout << "  " << label << ": " << value << "\n";
  }
  std::cout << "  holds:      " << s.files << " files, " << archive::humanSize(s.bytes) << " (manifests:";
  for (const std::string& m : s.manifests) std::cout << " " << m;
  std::cout << ")\n";
  std::size_t width = 14;  // the longest role and a space
  for (const archive::RoleTotal& t : s.roles) width = std::max(width, t.role.size() + 1);
  for (const archive::RoleTotal& t : s.roles) {
    std::string name = t.role;
    name.resize(width, ' ');
    std::cout << "    " << name << t.files << (t.files == 1 ? " file,  " : " files, ") << archive::humanSize(t.bytes)
              << "\n";
  }
  if (!s.results.empty()) {
    std::cout << "  results:\n";
    for (const auto& [file, bytes] : s.results) std::cout << "    " << file << "  " << archive::humanSize(bytes) << "\n";
  }
  if (s.carrier) {
    std::cout << "  carrier (data/assembly-files/carrier.xml):\n";
    printCarrierText(*s.carrier);
  } else if (!s.carrierProblem.empty()) {
    std::cout << "  carrier:    cannot be read: " << s.carrierProblem << "\n";
  }
  std::cout << "  to verify it:\n";
  for (const std::string& c : verifyCommands(path, s.surrogate)) std::cout << "    " << c << "\n";
}

// How the shots are held: "8 originals in original-captures/, 8 JPEG exports"; for a capture
// of JPEG exports alone, the exports are the originals the pipeline reads (docs/user-guide.md).
std::string shotsText(const capture::CaptureSummary& s) {
  if (!s.hasOriginals())
    return "exports in " + std::string(capture::kExportsDir) + "/, no raw originals: the exports "
           "are the originals the pipeline reads";
  return std::to_string(s.originals) + " originals in " + s.originalsDir + "/" +
         (s.exports ? ", " + std::to_string(s.exports) + " exports in " + capture::kExportsDir + "/" : "");
}

// The commands that take the capture's lock and, before anything else, finish or discard what
// a killed command left (run::recoverRun).
constexpr const char* kRecoveringCommands = "the next run, lights, pack, audit or Apply in review";

// What a command cut short in a commit left, and what the next command will do with it
// (run::pendingRecovery); empty when nothing is pending.
struct PendingText {
  std::string state, text;
};
std::optional<PendingText> pendingText(const fs::path& capture) {
  const std::optional<run::PendingRecovery> p = run::pendingRecovery(capture);
  if (!p) return std::nullopt;
  // A command working on the capture now has a staging folder (and, in its commit, a journal)
  // of its own: its work in progress, not something left behind.
  if (const std::optional<std::string> holder = capture::captureHolder(capture))
    return PendingText{"in-progress", "a command is working on the capture now (" + escapedText(*holder) +
                                          "): the record shown is the one before it, until it commits"};
  switch (p->kind) {
    case run::PendingRecovery::Kind::FinishCommit: {
      if (!p->stagedProblem.empty())
        return PendingText{"finish-commit",
                           "a run was stopped while it committed its results, and its staged record (" +
                               std::string(capture::kWorkDir) + "/staging/" + capture::kCarrierPath +
                               ") cannot be read (" + escapedText(p->stagedProblem) + "): " + kRecoveringCommands +
                               " stops on it; restore the capture from a backup or package"};
      const std::string which =
          p->run ? escapedText("run " + p->run->id + " (" + p->run->command + ", started " + p->run->started + ")")
                 : "a run";
      return PendingText{"finish-commit",
                         which + " was stopped while it committed its results (its journal is " +
                             std::string(capture::kWorkDir) + "/commit): " + kRecoveringCommands +
                             " first finishes that commit, and its results and record become the capture's; until "
                             "then the record shown here is the one before it"};
    }
    case run::PendingRecovery::Kind::ClearJournal:
      return PendingText{"clear-journal", "a commit was stopped after it had moved everything into place: " +
                                              std::string(kRecoveringCommands) + " removes its journal (" +
                                              capture::kWorkDir + "/commit); nothing else changes"};
    case run::PendingRecovery::Kind::DiscardStaging:
      return PendingText{"discard-staging", "a run was stopped before its commit: " + std::string(kRecoveringCommands) +
                                                " discards its partial results (" + capture::kWorkDir +
                                                "/staging); the capture stays as recorded"};
  }
  return std::nullopt;
}

}  // namespace

void printPackage(const fs::path& path, bool json) {
  // An OCFL object or E-ARK SIP: the bag it holds, described as the package's.
  const std::unique_ptr<verify::HeldBag> held = verify::openHeldBag(path);
  archive::PackageSummary s = archive::describePackage(held ? held->bag : path);
  if (held) s.format = json ? held->format : held->layout;
  if (json) printPackageJson(path, s);
  else printPackageText(path, s);
}

void printCapture(const fs::path& path, bool json) {
  const capture::CaptureSummary s = capture::describeCapture(path);
  if (json) {
    JsonWriter j;
    j.beginObject().key("kind").value("capture").key("shots").value(static_cast<int>(s.shots))
        .key("originals").value(s.originals).key("exports").value(s.exports)
        .key("originalsFolder").value(s.originalsFolder)
        .key("width").value(s.width).key("height").value(s.height)
        .key("lp").value(s.lp.value_or(""));
    j.key("pendingCommit");
    if (const auto pending = pendingText(path))
      j.beginObject().key("state").value(pending->state).key("description").value(pending->text).endObject();
    else j.null();
    if (s.processed) {
      j.key("carrier");
      carrierJson(j, carrier::loadCarrier(path / capture::kCarrierPath));
    }
    j.endObject();
    std::cout << j.str() << "\n";
    return;
  }
  std::cout << path.string() << ": capture folder\n"
            << "  shots:     " << s.shots << " (" << shotsText(s) << ")\n"
            << "  image:     " << s.width << "x" << s.height << " " << s.format << "\n"
            << "  lights:    " << (s.lp ? "given by " + *s.lp + " (dome capture)" : "to be detected from the spheres")
            << "\n";
  for (const std::string& lp : s.unusedLp)
    std::cout << "  note:      " << lp << " is kept as a file of the capture but not used; for "
              << "a dome capture whose lights it gives, run with --lp " << lp << "\n";
  if (const auto pending = pendingText(path)) std::cout << "  pending:   " << pending->text << "\n";
}

}  // namespace surrogate::cli
