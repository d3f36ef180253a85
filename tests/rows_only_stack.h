// Test support shared by tests/fit and tests/hrti: the images of a MemoryImageStack behind a
// plain ImageStack, readable only through readRows. Code that reads a stack in memory where it
// is (no band copy) takes the other path with it, the path of a spilled stack.
#pragma once

#include <cstdint>

#include "core/stack.h"

namespace surrogate::test {

class RowsOnlyStack : public ImageStack {
 public:
  explicit RowsOnlyStack(const MemoryImageStack& s) : s_(s) {}
  int size() const override { return s_.size(); }
  int width() const override { return s_.width(); }
  int height() const override { return s_.height(); }
  int channels() const override { return s_.channels(); }
  Transfer transfer() const override { return s_.transfer(); }
  void readRows(int index, int y0, int y1, std::uint16_t* out) const override { s_.readRows(index, y0, y1, out); }

 private:
  const MemoryImageStack& s_;
};

}  // namespace surrogate::test
