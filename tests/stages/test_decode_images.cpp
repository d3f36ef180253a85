// Where decodeImages keeps the decoded stacks: in memory when they fit --memory, in a temporary
// file only when they do not. The bytes the process writes are read from the kernel's own
// count (/proc/self/io), not from anything the code under test reports.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "generator/capture_generator.h"
#include "pipeline/spill_stack.h"
#include "stages/decode_images.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kImages = 6, kWidth = 320, kHeight = 240;
// Both stacks as 16-bit samples: RGB and luminance.
constexpr std::uint64_t kStackBytes = std::uint64_t(kImages) * kWidth * kHeight * (3 + 1) * 2;

// Bytes this process has passed to write(2)-like calls so far (pwrite included).
std::uint64_t bytesWritten() {
  std::ifstream io("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (io >> key >> value)
    if (key == "wchar:") return value;
  FAIL("/proc/self/io has no wchar line");
  return 0;
}

std::vector<fs::path> generatedJpegs() {
  static const fs::path dir = fs::temp_directory_path() / "decode-images-capture";
  if (!fs::exists(dir / "jpeg-exports")) {
    generator::GeneratorOptions o;
    o.images = kImages;
    o.width = kWidth;
    o.height = kHeight;
    o.sphereRadius = 30;
    o.formats = generator::OutputFormats::Jpeg;
    generator::writeCapture(o, dir);
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir / "jpeg-exports")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() == kImages);
  return files;
}

struct Decoded {
  stages::DecodedStacks stacks;
  std::uint64_t written = 0;  // bytes the process wrote while decoding
};

Decoded decodeUnder(const std::vector<fs::path>& files, std::size_t budget, int threads) {
  pipeline::RunSettings run;
  run.memoryBudget = budget;
  run.threads = threads;
  Decoded d;
  const std::uint64_t before = bytesWritten();
  d.stacks = stages::decodeImages(files, image::RawDecodeSettings(), run);
  d.written = bytesWritten() - before;
  return d;
}

std::vector<std::uint16_t> allRows(const ImageStack& s, int index) {
  std::vector<std::uint16_t> out(std::size_t(s.width()) * s.height() * s.channels());
  s.readRows(index, 0, s.height(), out.data());
  return out;
}

}  // namespace

TEST_CASE("decoded stacks that fit the memory budget stay in memory and write nothing to disk") {
  const auto files = generatedJpegs();
  const Decoded d = decodeUnder(files, std::size_t(2) << 30, 2);
  CHECK(d.written == 0);
  CHECK(d.stacks.bytesInMemory == kStackBytes);
  CHECK(dynamic_cast<const pipeline::SpillStack*>(d.stacks.rgb.get()) == nullptr);
  CHECK(dynamic_cast<const pipeline::SpillStack*>(d.stacks.luminance.get()) == nullptr);
}

TEST_CASE("a budget too small for the stacks spills them to a temporary file with the same pixels") {
  const auto files = generatedJpegs();
  // Decoding one image needs 24 bytes per pixel (1.8 MB here): 4 MiB lets it run but leaves
  // less than the stacks' 3.7 MB.
  const std::size_t tiny = std::size_t(4) << 20;
  REQUIRE_FALSE(stages::stacksFitInMemory(kImages, std::uint64_t(kWidth) * kHeight, tiny));
  const Decoded spilled = decodeUnder(files, tiny, 1);
  CHECK(spilled.written >= kStackBytes);
  CHECK(spilled.stacks.bytesInMemory == 0);
  const Decoded held = decodeUnder(files, std::size_t(2) << 30, 2);
  for (int i = 0; i < kImages; ++i) {
    INFO("image " << i);
    CHECK(allRows(*spilled.stacks.rgb, i) == allRows(*held.stacks.rgb, i));
    CHECK(allRows(*spilled.stacks.luminance, i) == allRows(*held.stacks.luminance, i));
  }
  CHECK(spilled.stacks.luminance->transfer() == held.stacks.luminance->transfer());
  CHECK(spilled.stacks.rgb->transfer() == held.stacks.rgb->transfer());
}

TEST_CASE("the stacks stay in memory only with room besides them for the rest of the run") {
  const std::uint64_t pixels = 1200 * 800;  // 36 shots: 276 MB of stacks
  CHECK(stages::stacksFitInMemory(36, pixels, std::size_t(2) << 30));
  CHECK_FALSE(stages::stacksFitInMemory(36, pixels, std::size_t(400) << 20));
  // The fitted models kept for the derived maps count too: 200 bytes per pixel of them leave
  // too little of 700 MiB.
  CHECK(stages::stacksFitInMemory(36, pixels, std::size_t(700) << 20));
  CHECK_FALSE(stages::stacksFitInMemory(36, pixels, std::size_t(700) << 20, 200));
}
