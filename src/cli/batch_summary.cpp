#include "cli/batch_summary.h"

#include <iostream>

#include "batch/ledger.h"
#include "batch/standing.h"
#include "core/json.h"
#include "core/text.h"

namespace surrogate::cli {

namespace {

// "3 captures", "1 package", "3 items (2 captures, 1 package)": each item by its kind.
std::string countOf(std::size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

std::string itemsInWords(std::size_t captures, std::size_t packages) {
  if (packages == 0) return countOf(captures, "capture");
  if (captures == 0) return countOf(packages, "package");
  return countOf(captures + packages, "item") + " (" + countOf(captures, "capture") + ", " +
         countOf(packages, "package") + ")";
}

void itemJson(JsonWriter& j, const batch::ItemStanding& s) {
  j.beginObject().key(s.isPackage ? "package" : "capture").value(s.item)
      .key("state").value(s.failed() ? "failed" : "done")
      .key("attempts").value(static_cast<unsigned long long>(s.attempts));
  if (!s.isPackage) j.key("packsMade").value(static_cast<unsigned long long>(s.packsMade));
  j.key("steps").beginArray();
  for (const batch::LedgerEntry* e : s.lastOfStep)
    j.beginObject().key("step").value(e->step).key("exit").value(e->exit).key("message").value(e->message)
        .key("package").value(e->package).key("packageId").value(e->packageId).key("end").value(e->end)
        .key("failedBefore").value(static_cast<unsigned long long>(s.failuresBeforeSuccess(e->step)))
        .endObject();
  j.endArray().endObject();
}

}  // namespace

int printBatchSummary(const std::string& ledgerPath, bool json) {
  const batch::Ledger ledger = batch::readLedger(ledgerPath);
  const std::vector<batch::ItemStanding> items = batch::standings(ledger);
  std::size_t failed = 0, duplicates = 0, packages = 0;
  for (const batch::ItemStanding& s : items) {
    failed += s.failed();
    duplicates += s.packsMade > 1;
    packages += s.isPackage;
  }
  if (json) {
    JsonWriter j;
    j.beginObject().key("ledger").value(ledgerPath)
        .key("items").value(static_cast<unsigned long long>(items.size()))
        .key("done").value(static_cast<unsigned long long>(items.size() - failed))
        .key("failed").value(static_cast<unsigned long long>(failed))
        .key("lines").value(static_cast<unsigned long long>(ledger.entries.size()))
        .key("damagedLines").value(static_cast<unsigned long long>(ledger.damagedLines));
    for (const bool ofPackages : {false, true}) {
      j.key(ofPackages ? "packages" : "captures").beginArray();
      for (const batch::ItemStanding& s : items)
        if (s.isPackage == ofPackages) itemJson(j, s);
      j.endArray();
    }
    j.endObject();
    std::cout << j.str() << "\n";
    return failed ? 1 : 0;
  }
  // Names as one line each: a tab, a line break or a byte that is not UTF-8 in a capture's
  // name shows as \xHH, never as a forged line of the summary.
  std::cout << "Ledger " << escapedText(ledgerPath) << ": " << itemsInWords(items.size() - packages, packages) << ", "
            << (items.size() - failed) << " done, " << failed << " failed (" << ledger.entries.size() << " lines";
  if (ledger.damagedLines) std::cout << ", " << ledger.damagedLines << " torn line(s) left out";
  std::cout << ")\n";
  for (const batch::ItemStanding& s : items) {
    std::cout << (s.failed() ? "  FAIL  " : "  done  ") << escapedText(s.item);
    for (const batch::LedgerEntry* e : s.lastOfStep) {
      std::cout << "; " << e->step << (e->succeeded() ? " ok" : " exit " + std::to_string(e->exit));
      // History, not the standing: the last attempt succeeded.
      if (const std::size_t before = s.failuresBeforeSuccess(e->step); before > 0)
        std::cout << " (after " << countOf(before, "failed attempt") << ")";
    }
    std::cout << "\n";
    for (const batch::LedgerEntry* e : s.lastOfStep)
      if (!e->succeeded()) std::cout << "          " << e->step << ": " << escapedText(e->message) << "\n";
  }
  if (duplicates) std::cout << duplicates << " capture(s) were packed more than once (their carrier changed between packs)\n";
  return failed ? 1 : 0;
}

}  // namespace surrogate::cli
