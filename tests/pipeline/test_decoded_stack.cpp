#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <cstring>
#include <random>

#include "core/parallel.h"
#include "fit/fit.h"
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
    // Rows of bytes held where they are, in memory only; 16-bit rows are read as copies.
    const bool memory = placement == DecodedStack::Placement::Memory;
    CHECK(narrow.heldRow(1, 4) == nullptr);
    CHECK(wide.heldByteRow(1, 4) == nullptr);
    CHECK(wide.heldRow(1, 4) == nullptr);
    if (memory) {
      REQUIRE(narrow.heldByteRow(1, 4) != nullptr);
      CHECK(std::equal(narrow.heldByteRow(1, 4), narrow.heldByteRow(1, 4) + row, narrowImage(1).begin() + 4 * row));
    } else {
      CHECK(narrow.heldByteRow(1, 4) == nullptr);
    }
    // Misuse is an internal error, not a silent wrong read.
    CHECK_THROWS(narrow.readRows(0, 20, 24, std::vector<std::uint16_t>(row * 4).data()));
    CHECK_THROWS(narrow.store(0, wideImage(0)));
    CHECK_THROWS(wide.store(0, std::vector<std::uint16_t>(10)));
    CHECK_THROWS(narrow.store(kCount, narrowImage(0)));
  }
  CHECK(DecodedStack::bytesFor(kCount, {kWidth, kHeight, 3, 1, Transfer::Srgb}) == std::uint64_t(kCount) * kWidth * kHeight * 3);
  CHECK(DecodedStack::bytesFor(kCount, {kWidth, kHeight, 1, 2, Transfer::Srgb}) == std::uint64_t(kCount) * kWidth * kHeight * 2);
}

TEST_CASE("a DecodedStack in memory is written in place through its slots, one in a file has none") {
  DecodedStack stack(kCount, {kWidth, kHeight, 3, 1, Transfer::Srgb}, DecodedStack::Placement::Memory);
  const std::size_t row = std::size_t(kWidth) * 3;
  REQUIRE(stack.imageBytes() == row * kHeight);
  // Slots are distinct, in order, and each exactly one image long.
  for (int i = 0; i + 1 < kCount; ++i) CHECK(stack.slot(i + 1) - stack.slot(i) == std::ptrdiff_t(row * kHeight));
  // Before it is marked stored, an image written into its slot cannot be read: a decoder that
  // failed halfway leaves nothing that passes for an image.
  const std::vector<std::uint8_t> image = narrowImage(4);
  std::copy(image.begin(), image.end(), stack.slot(4));
  std::vector<std::uint16_t> out(row * kHeight);
  CHECK_THROWS(stack.readRows(4, 0, kHeight, out.data()));
  stack.markStored(4);
  std::vector<std::uint8_t> stored(row * kHeight);
  stack.readSamples(4, 0, kHeight, stored.data());
  CHECK(stored == image);
  CHECK(rows(stack, 4, 7, 8)[5] == image[7 * row + 5] * 257);
  // store() copies into the same place.
  stack.store(1, narrowImage(1));
  CHECK(std::equal(stack.slot(1), stack.slot(1) + row * kHeight, narrowImage(1).begin()));
  CHECK_THROWS(stack.slot(kCount));
  CHECK_THROWS(stack.markStored(-1));
  // Held rows are the stored bytes themselves, once stored, and only then.
  CHECK(stack.heldSamples(4, 7, 9) == stack.slot(4) + 7 * row);
  CHECK_THROWS(stack.heldSamples(0, 0, 1));  // never stored
  CHECK_THROWS(stack.heldSamples(4, 5, kHeight + 1));

  DecodedStack spilled(kCount, {kWidth, kHeight, 3, 1, Transfer::Srgb}, DecodedStack::Placement::TemporaryFile);
  CHECK(spilled.slot(0) == nullptr);
  CHECK_THROWS(spilled.markStored(0));
  CHECK_THROWS(spilled.readSamples(0, 0, 1, stored.data()));  // never stored
  spilled.store(2, narrowImage(2));
  CHECK(spilled.heldSamples(2, 0, kHeight) == nullptr);  // in the file: read it with readSamples
}

namespace {
// The bytes of a model's scales or biases, to compare models whole.
template <typename Values>
void appendBytes(const Values& values, std::vector<std::uint8_t>* out) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(values.data());
  out->insert(out->end(), bytes, bytes + values.size() * sizeof(values[0]));
}
}  // namespace

TEST_CASE("the fits give the same model from bytes held in memory, from a stack in a file and from 16-bit images") {
  // 211 pixels a row: three whole blocks of the per-channel products and a ragged end.
  constexpr int n = 12, w = 211, h = 9;
  std::mt19937 random(5);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::vector<std::uint8_t>> images(n, std::vector<std::uint8_t>(std::size_t(w) * h * 3));
  for (auto& image : images)
    for (auto& b : image) b = static_cast<std::uint8_t>(byte(random));
  std::vector<std::array<double, 3>> lights;
  for (int i = 0; i < n; ++i) {
    const double azimuth = 2 * M_PI * i / n, elevation = (30.0 + 20.0 * (i % 3)) * M_PI / 180;
    lights.push_back({std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)});
  }
  const DecodedStack::Format format{w, h, 3, 1, Transfer::Srgb};
  DecodedStack held(n, format, DecodedStack::Placement::Memory);
  DecodedStack spilled(n, format, DecodedStack::Placement::TemporaryFile);
  std::vector<Image> widened;
  for (int i = 0; i < n; ++i) {
    held.store(i, images[i]);
    spilled.store(i, images[i]);
    widened.push_back(widen(images[i].data(), w, h, 3, Transfer::Srgb));
  }
  const MemoryImageStack wide(std::move(widened));
  REQUIRE(held.heldByteRow(0, 0) != nullptr);
  REQUIRE(spilled.heldByteRow(0, 0) == nullptr);
  REQUIRE(wide.heldRow(0, 0) != nullptr);

  for (const fit::Basis basis : {fit::Basis::PtmLrgb, fit::Basis::PtmRgb, fit::Basis::Hsh2, fit::Basis::Hsh3}) {
    INFO("basis " << fit::basisName(basis));
    auto fitted = [&](const ImageStack& stack, int threads, fit::FitStatistics* stats) {
      fit::FitOptions options;
      options.basis = basis;
      options.threads = threads;
      if (basis == fit::Basis::PtmLrgb || basis == fit::Basis::PtmRgb) {
        const formats::PtmFile ptm = fit::fitPtm(stack, lights, options, stats);
        std::vector<std::uint8_t> out = ptm.coefficients;
        out.insert(out.end(), ptm.rgb.begin(), ptm.rgb.end());
        appendBytes(ptm.scale, &out);
        appendBytes(ptm.bias, &out);
        return out;
      }
      const formats::HshFile hsh = fit::fitHsh(stack, lights, options, stats);
      std::vector<std::uint8_t> out = hsh.coefficients;
      appendBytes(hsh.scale, &out);
      appendBytes(hsh.bias, &out);
      return out;
    };
    fit::FitStatistics fromWide, fromHeld, fromFile, fromHeldOneThread;
    const std::vector<std::uint8_t> reference = fitted(wide, 2, &fromWide);
    CHECK(fitted(held, 2, &fromHeld) == reference);
    CHECK(fitted(spilled, 2, &fromFile) == reference);
    CHECK(fitted(held, 1, &fromHeldOneThread) == reference);
    for (const fit::FitStatistics* stats : {&fromHeld, &fromFile, &fromHeldOneThread}) {
      CHECK(std::memcmp(&stats->rmse, &fromWide.rmse, sizeof(double)) == 0);
      CHECK(stats->perImageRmse == fromWide.perImageRmse);
    }
    CHECK(fromWide.rmse > 0);
  }
}
