// Planning: what of an item's steps is done and still valid (the ledger's lines, the capture's
// carrier and the package as they are now), the plan --dry-run and --verbose say, and the
// ledger as this batch knows it, kept in step with what it and the batches beside it append.
#include <filesystem>
#include <functional>
#include <string>

#include "batch/resume.h"
#include "batch/runner.h"

namespace surrogate::batch {

namespace fs = std::filesystem;

fs::path Runner::packageOf(const WorkItem& item) const {
  return item.isPackage ? fs::path(item.where()) : packagePathFor(item.where(), o_.packagesDir, o_.packageFormat);
}

Ledger Runner::ledgerOf(const std::string& item) const {
  Ledger l;
  if (const auto it = byItem_.find(item); it != byItem_.end())
    for (std::size_t i : it->second) l.entries.push_back(ledger_.entries[i]);
  return l;
}

const LedgerEntry* Runner::lastMatching(const std::string& item, const std::function<bool(const LedgerEntry&)>& wanted) const {
  const auto it = byItem_.find(item);
  if (it == byItem_.end()) return nullptr;
  for (auto i = it->second.rbegin(); i != it->second.rend(); ++i)
    if (wanted(ledger_.entries[*i])) return &ledger_.entries[*i];
  return nullptr;
}

const LedgerEntry* Runner::lastSuccess(const std::string& item, const std::string& step) const {
  return lastMatching(item, [&](const LedgerEntry& e) { return e.step == step && e.succeeded(); });
}

const LedgerEntry* Runner::knownPackage(const std::string& item) const {
  return lastMatching(item, [](const LedgerEntry& e) { return e.succeeded() && !e.packageSha256.empty(); });
}

bool Runner::stillValid(const Job& job, const std::string& step, std::string& why) const {
  const std::string& item = job.item.path;  // the ledger's name of it; the files are at where()
  const Ledger mine = ledgerOf(item);
  if (step == "run") return runStillValid(historyOf(mine, item, "run"), carrierState(job.item.where()), why);
  if (step == "pack")
    return packStillValid(historyOf(mine, item, "pack"), carrierState(job.item.where()),
                          packageState(job.package, knownPackage(item)), why);
  return verifyStillValid(historyOf(mine, item, "verify"), packageState(job.package, knownPackage(item)),
                          o_.reexecute, why);
}

ItemPlan Runner::planOf(const WorkItem& item) const {
  Job job;
  job.item = item;
  job.package = packageOf(item);
  ItemPlan plan;
  plan.item = item;
  std::string before;  // an earlier step that will run: the later ones follow it
  for (const std::string& step : o_.steps) {
    if (!applies(job, step)) continue;
    PlannedStep p;
    p.step = step;
    if (step != "run") p.package = job.package.string();
    std::string why;
    if (before.empty() && stillValid(job, step, why)) {
      p.skipped = true;
    } else {
      p.why = before.empty() ? why : "after " + before;
      before = step;
    }
    plan.steps.push_back(p);
  }
  return plan;
}

void Runner::record(LedgerEntry e) {
  appendToLedger(o_.ledger, e);
  ownUnread_.insert(ownKey(e));
  byItem_[e.capture].push_back(ledger_.entries.size());
  ledger_.entries.push_back(std::move(e));
}

std::string Runner::ownKey(const LedgerEntry& e) {
  return e.capture + '\n' + e.step + '\n' + e.start + '\n' + e.host + '\n' + std::to_string(e.attempt);
}

void Runner::refreshLedger() {
  Ledger fresh;
  ledgerOffset_ = readLedgerSince(o_.ledger, ledgerOffset_, fresh);
  for (LedgerEntry& e : fresh.entries) {
    if (const auto own = ownUnread_.find(ownKey(e)); own != ownUnread_.end()) {
      ownUnread_.erase(own);
      continue;
    }
    byItem_[e.capture].push_back(ledger_.entries.size());
    ledger_.entries.push_back(std::move(e));
  }
}

}  // namespace surrogate::batch
