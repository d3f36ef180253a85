// What reading a .ptm or .rti may take in memory (core/memory_budget.h): the budget, and what
// the caller will hold beside the model for each texel (render its picture, publish its planes),
// so that a model is refused from its header when reading it and using it would not fit, before
// anything is allocated.
//
//   ModelBudget budget{memory, 12};            // render: its picture and the file's stream
//   PtmFile ptm = readPtm(path, nullptr, budget);
#pragma once

#include <cstdint>

#include "core/memory_budget.h"

namespace surrogate::formats {

struct ModelBudget {
  std::uint64_t bytes = kDefaultMemoryBudget;  // --memory
  std::uint64_t besidePerTexel = 0;            // bytes the caller holds per texel besides the model
  std::uint64_t modelCopies = 0;               // and copies of the model's size (publish's planes)
  std::uint64_t memoryOption = 0;              // the --memory `bytes` is a part of, for messages
};

}  // namespace surrogate::formats
