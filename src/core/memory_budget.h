// The memory budget (--memory) of the commands that read models and layouts, and the check
// every such reader makes, from the sizes a file declares, before it allocates anything.
//
// A header costs nothing to write: a JPEG-compressed PTM of a few megabytes can declare nine
// planes of 20000 x 20000 texels, 7 GB once decoded. So a reader works out, from the declared
// width, height and planes (and the bytes the file really has), what reading it will take at
// its peak, and refuses the file (Error(Input), exit 1) when that is more than the budget:
//
//   const std::uint64_t needed = fileBytes + texels * planes + ...;
//   requireWithinMemory(file, "read PTM", "20000x20000 texels in 9 JPEG planes", needed, budget);
#pragma once

#include <cstdint>
#include <string>

namespace surrogate {

// The budget when none is given: what `run`, `fit`, `render` and `publish` use by default.
inline constexpr std::uint64_t kDefaultMemoryBudget = 2ull << 30;

// A size as --memory is written (binary units): "512M", "7.2G".
std::string memorySize(std::uint64_t bytes);

// Throws Error(Input) naming `file` when `needed` exceeds `budget`: what the file declares
// (`declared`), what reading it needs, the budget and what to do (--memory SIZE if the
// computer has it; else the header is damaged or crafted). `memoryOption`, when larger than
// `budget`, is the --memory the budget is a part of (a run's audit has what the decoded
// photographs leave): the message then says so, and the size it suggests covers the rest.
void requireWithinMemory(const std::string& file, const std::string& step, const std::string& declared,
                         std::uint64_t needed, std::uint64_t budget, std::uint64_t memoryOption = 0);

}  // namespace surrogate
