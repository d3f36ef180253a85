#include <catch2/catch.hpp>

#include <algorithm>

#include "core/parallel.h"
#include "pipeline/decoded_stack.h"

using namespace surrogate;
using pipeline::DecodedStack;

namespace {

constexpr int kCount = 5, kWidth = 37, kHeight = 23;

std::vector<std::uint8_t> narrowImage(int i) {
  std::vector<std::uint8_t> v(std::size_t(kWidth) * kHeight * 3);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = static_cast<std::uint8_t>(k * 31 + i * 7);
  return v;
}

std::vector<std::uint16_t> wideImage(int i) {
  std::vector<std::uint16_t> v(std::size_t(kWidth) * kHeight * 3);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = static_cast<std::uint16_t>(k * 3001 + i * 7);
  return v;
}

std::vector<std::uint16_t> rows(const ImageStack& s, int index, int y0, int y1) {
  std::vector<std::uint16_t> out(std::size_t(s.width()) * s.channels() * (y1 - y0));
  s.readRows(index, y0, y1, out.data());
  return out;
}

}  // namespace

TEST_CASE("a DecodedStack gives 8-bit images widened by 257 and 16-bit ones as stored, in memory or in a file") {
  for (const auto placement : {DecodedStack::Placement::Memory, DecodedStack::Placement::TemporaryFile}) {
    INFO("placement " << (placement == DecodedStack::Placement::Memory ? "memory" : "file"));
    DecodedStack narrow(kCount, {kWidth, kHeight, 3, 1, Transfer::Srgb}, placement);
    DecodedStack wide(kCount, {kWidth, kHeight, 3, 2, Transfer::Linear}, placement);
    parallelFor(kCount, 1, 2, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        narrow.store(static_cast<int>(i), narrowImage(static_cast<int>(i)));
        wide.store(static_cast<int>(i), wideImage(static_cast<int>(i)));
      }
    });
    for (int i = 0; i < kCount; ++i) {
      const std::vector<std::uint8_t> bytes = narrowImage(i);
      std::vector<std::uint16_t> widened(bytes.size());
      for (std::size_t k = 0; k < bytes.size(); ++k) widened[k] = static_cast<std::uint16_t>(bytes[k] * 257);
      CHECK(rows(narrow, i, 0, kHeight) == widened);
      CHECK(rows(wide, i, 0, kHeight) == wideImage(i));
    }
    // A band in the middle, and the stored bytes themselves.
    const std::size_t row = std::size_t(kWidth) * 3;
    const std::vector<std::uint16_t> band = rows(wide, 2, 10, 14);
    CHECK(std::equal(band.begin(), band.end(), wideImage(2).begin() + 10 * row));
    std::vector<std::uint8_t> stored(row * 4);
    narrow.readSamples(3, 5, 9, stored.data());
    CHECK(std::equal(stored.begin(), stored.end(), narrowImage(3).begin() + 5 * row));
    CHECK(narrow.transfer() == Transfer::Srgb);
    CHECK(wide.transfer() == Transfer::Linear);
    // Misuse is an internal error, not a silent wrong read.
    CHECK_THROWS(narrow.readRows(0, 20, 24, std::vector<std::uint16_t>(row * 4).data()));
    CHECK_THROWS(narrow.store(0, wideImage(0)));
    CHECK_THROWS(wide.store(0, std::vector<std::uint16_t>(10)));
    CHECK_THROWS(narrow.store(kCount, narrowImage(0)));
  }
  CHECK(DecodedStack::bytesFor(kCount, {kWidth, kHeight, 3, 1, Transfer::Srgb}) == std::uint64_t(kCount) * kWidth * kHeight * 3);
  CHECK(DecodedStack::bytesFor(kCount, {kWidth, kHeight, 1, 2, Transfer::Srgb}) == std::uint64_t(kCount) * kWidth * kHeight * 2);
}
