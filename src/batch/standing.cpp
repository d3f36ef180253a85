#include "batch/standing.h"

#include <map>

namespace surrogate::batch {

bool ItemStanding::failed() const {
  for (const LedgerEntry* e : lastOfStep)
    if (!e->succeeded()) return true;
  return false;
}

const LedgerEntry* ItemStanding::last(const std::string& step) const {
  for (const LedgerEntry* e : lastOfStep)
    if (e->step == step) return e;
  return nullptr;
}

std::size_t ItemStanding::failuresBeforeSuccess(const std::string& step) const {
  for (std::size_t i = 0; i < lastOfStep.size(); ++i)
    if (lastOfStep[i]->step == step) return lastOfStep[i]->succeeded() ? failuresOfStep[i] : 0;
  return 0;
}

std::vector<ItemStanding> standings(const Ledger& ledger) {
  std::vector<ItemStanding> out;
  std::map<std::string, std::size_t> index;
  for (const LedgerEntry& e : ledger.entries) {
    auto it = index.find(e.capture);
    if (it == index.end()) {
      it = index.emplace(e.capture, out.size()).first;
      out.push_back(ItemStanding{});
      out.back().item = e.capture;
    }
    ItemStanding& s = out[it->second];
    ++s.attempts;
    s.isPackage = s.isPackage || e.packageItem;
    if (e.step == "pack" && e.succeeded() && !e.adopted) ++s.packsMade;
    std::size_t k = 0;
    while (k < s.lastOfStep.size() && s.lastOfStep[k]->step != e.step) ++k;
    if (k == s.lastOfStep.size()) {
      s.lastOfStep.push_back(&e);
      s.failuresOfStep.push_back(0);
    }
    s.lastOfStep[k] = &e;
    s.failuresOfStep[k] += !e.succeeded();
  }
  return out;
}

}  // namespace surrogate::batch
