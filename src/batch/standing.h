// Where each item of a ledger stands, for `batch --summary`: the last attempt of each step
// decides, as it decides for the batch itself (batch/resume.h: a step whose last attempt failed
// is done again), so that the two agree after any history of failures and retries; the failed
// attempts before it stay in the ledger and are counted here as history.
//
//   for (const ItemStanding& s : standings(readLedger("backlog.jsonl"))) if (s.failed()) ...
#pragma once

#include <string>
#include <vector>

#include "batch/ledger.h"

namespace surrogate::batch {

struct ItemStanding {
  std::string item;
  bool isPackage = false;                      // a package item (verify --batch): "package", not "capture"
  std::vector<const LedgerEntry*> lastOfStep;  // one per step met, in the order first met
  std::vector<std::size_t> failuresOfStep;     // each step's failed attempts, its last one included
  std::size_t attempts = 0;                    // lines of this item
  std::size_t packsMade = 0;                   // successful packs that wrote a package (not adopted)
  bool failed() const;                         // some step's last attempt failed
  const LedgerEntry* last(const std::string& step) const;
  // The step's failed attempts before its last one succeeded: 0 when it never failed, or
  // when its last attempt failed (that one is the standing, not history).
  std::size_t failuresBeforeSuccess(const std::string& step) const;
};

// The items in the order of their first line.
std::vector<ItemStanding> standings(const Ledger& ledger);

}  // namespace surrogate::batch
