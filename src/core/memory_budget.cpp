#include "core/memory_budget.h"

#include <cstdio>

#include "core/error.h"

namespace surrogate {

std::string memorySize(std::uint64_t bytes) {
  const char* units[] = {"K", "M", "G", "T", "P", "E"};
  double v = static_cast<double>(bytes) / 1024;
  int u = 0;
  while (v >= 1024 && u < 5) {
    v /= 1024;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, v < 10 ? "%.1f%s" : "%.0f%s", v, units[u]);
  return text;
}

void requireWithinMemory(const std::string& file, const std::string& step, const std::string& declared,
                         std::uint64_t needed, std::uint64_t budget, std::uint64_t memoryOption) {
  if (needed <= budget) return;
  const bool part = memoryOption > budget;
  // The next whole gigabyte above what is needed, a value --memory takes as it is. A part of
  // --memory grows with it, at most in proportion (a fit has three quarters of what the held
  // photographs leave: pipeline/context.h), so the suggestion is scaled by the whole over the part.
  const double scale = part ? static_cast<double>(memoryOption) / static_cast<double>(budget) : 1.0;
  const std::uint64_t gib = static_cast<std::uint64_t>(static_cast<double>(needed) * scale) / (1ull << 30) + 1;
  throwInputError(file, step,
                  "declares " + declared + ": reading and using it needs about " + memorySize(needed) +
                      " of memory, more than " +
                      (part ? "the " + memorySize(budget) + " left of --memory " + memorySize(memoryOption)
                            : "the budget of " + memorySize(budget) + " (--memory)") +
                      ". Give --memory " + std::to_string(gib) +
                      "G or more if the computer has that much memory; if the model is not that "
                      "large, its header is damaged or was made to exhaust memory");
}

}  // namespace surrogate
