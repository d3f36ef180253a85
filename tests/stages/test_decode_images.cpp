// Where decodeImages keeps the decoded stack: in memory when it fits --memory, in a temporary
// file only when it does not; and what its views give. The bytes the process writes are read
// from the kernel's own count (/proc/self/io), not from anything the code under test reports;
// the views are compared with the decoded images (image::decodeImage) and with luminance and
// sRGB encoding computed in the test.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../image/damage.h"
#include "generator/capture_generator.h"
#include "pipeline/decoded_stack.h"
#include "image/write.h"
#include "stages/decode_images.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

constexpr int kImages = 6, kWidth = 320, kHeight = 240;
// The JPEGs' samples, one byte each.
constexpr std::uint64_t kStackBytes = std::uint64_t(kImages) * kWidth * kHeight * 3;

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

TEST_CASE("a decoded stack that fits the memory budget stays in memory, 8-bit, and writes nothing to disk") {
  const auto files = generatedJpegs();
  const Decoded d = decodeUnder(files, std::size_t(2) << 30, 2);
  CHECK(d.written == 0);
  CHECK(d.stacks.bytesInMemory == kStackBytes);
  CHECK(d.stacks.decoded->placement() == pipeline::DecodedStack::Placement::Memory);
  CHECK(d.stacks.decoded->format().bytesPerSample == 1);
}

TEST_CASE("the views of the stack give the decoded images and their Rec. 709 luminance") {
  const auto files = generatedJpegs();
  const Decoded d = decodeUnder(files, std::size_t(2) << 30, 2);
  for (int i : {0, kImages - 1}) {
    INFO("image " << i);
    const Image im = image::decodeImage(files[i], image::RawDecodeSettings());
    REQUIRE(im.channels == 3);
    CHECK(allRows(*d.stacks.rgb, i) == im.pixels);
    // Luminance written out here: weights 0.2126, 0.7152, 0.0722, rounded to nearest.
    const std::vector<std::uint16_t> lum = allRows(*d.stacks.luminance, i);
    std::size_t off = 0;
    for (std::size_t p = 0; p < lum.size(); ++p) {
      const double y = 0.2126 * im.pixels[3 * p] + 0.7152 * im.pixels[3 * p + 1] + 0.0722 * im.pixels[3 * p + 2];
      off += std::abs(lum[p] - y) > 1.0 ? 1 : 0;  // the weights in 1/65536 differ by < 0.4 level
    }
    CHECK(off == 0);
  }
}

TEST_CASE("a budget too small for the stacks spills them to a temporary file with the same pixels") {
  const auto files = generatedJpegs();
  // Decoding one image needs 24 bytes per pixel (1.8 MB here): 4 MiB lets it run but leaves
  // less than the stacks' 3.7 MB.
  const std::size_t tiny = std::size_t(4) << 20;
  REQUIRE_FALSE(stages::stackFitsInMemory(kImages, std::uint64_t(kWidth) * kHeight, 3, tiny));
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

TEST_CASE("the stack stays in memory only with room besides it for the rest of the run") {
  const std::uint64_t pixels = 1200 * 800;  // 36 shots of 16-bit RGB: 207 MB
  CHECK(stages::stackFitsInMemory(36, pixels, 6, std::size_t(2) << 30));
  CHECK_FALSE(stages::stackFitsInMemory(36, pixels, 6, std::size_t(400) << 20));
  // The fitted models kept for the derived maps count too: 400 bytes per pixel of them leave
  // too little of 700 MiB.
  CHECK(stages::stackFitsInMemory(36, pixels, 6, std::size_t(700) << 20));
  CHECK_FALSE(stages::stackFitsInMemory(36, pixels, 6, std::size_t(700) << 20, 400));
  // 8-bit JPEG samples take half: 36 x 6 Mpx (648 MB) fit the default 2 GiB with the default
  // models (21 bytes per pixel), where 16-bit ones do not.
  CHECK(stages::stackFitsInMemory(36, 3000 * 2000, stages::storedBytesPerPixel(image::SourceKind::Jpeg),
                                  std::size_t(2) << 30, 21));
  CHECK_FALSE(stages::stackFitsInMemory(36, 3000 * 2000, stages::storedBytesPerPixel(image::SourceKind::CameraRaw),
                                        std::size_t(2) << 30, 21));
}

namespace {

// `count` PNGs of `channels` at `bits` in a fresh folder, with values written out here.
std::vector<fs::path> pngs(const std::string& name, int count, int channels, int bits) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<fs::path> files;
  for (int i = 0; i < count; ++i) {
    Image im(40, 30, channels);
    im.bitsPerSample = bits;
    for (std::size_t k = 0; k < im.pixels.size(); ++k) {
      const unsigned v = static_cast<unsigned>(k * 13 + i * 101);
      im.pixels[k] = static_cast<std::uint16_t>(bits == 8 ? (v % 256) * 257 : (v * 977) % 65536);
    }
    files.push_back(dir / ("IMG_" + std::to_string(i) + ".png"));
    image::writePng(im, files.back());
  }
  return files;
}

}  // namespace

TEST_CASE("grey 8-bit images are kept one byte a pixel and read as RGB with R = G = B") {
  const auto files = pngs("decode-grey", 3, 1, 8);
  const Decoded d = decodeUnder(files, std::size_t(2) << 30, 2);
  CHECK(d.stacks.decoded->format().channels == 1);
  CHECK(d.stacks.decoded->format().bytesPerSample == 1);
  CHECK(d.stacks.bytesInMemory == 3u * 40 * 30);
  for (int i = 0; i < 3; ++i) {
    const std::vector<std::uint16_t> rgb = allRows(*d.stacks.rgb, i), lum = allRows(*d.stacks.luminance, i);
    REQUIRE(rgb.size() == 3 * lum.size());
    for (std::size_t p = 0; p < lum.size(); ++p) {
      const std::uint16_t grey = static_cast<std::uint16_t>(((p * 13 + i * 101) % 256) * 257);
      CHECK(lum[p] == grey);
      CHECK((rgb[3 * p] == grey && rgb[3 * p + 1] == grey && rgb[3 * p + 2] == grey));
      if (lum[p] != grey) break;
    }
  }
}

TEST_CASE("16-bit images are kept as they are, and a capture mixing depths is refused by name") {
  const auto wide = pngs("decode-16", 2, 3, 16);
  const Decoded d = decodeUnder(wide, std::size_t(2) << 30, 1);
  CHECK(d.stacks.decoded->format().bytesPerSample == 2);
  std::vector<std::uint16_t> expected(40 * 30 * 3);
  for (std::size_t k = 0; k < expected.size(); ++k) expected[k] = static_cast<std::uint16_t>(((k * 13 + 101) * 977) % 65536);
  CHECK(allRows(*d.stacks.rgb, 1) == expected);

  std::vector<fs::path> mixed = pngs("decode-mixed", 2, 3, 8);
  mixed.push_back(wide[0]);
  try {
    decodeUnder(mixed, std::size_t(2) << 30, 1);
    FAIL("a 16-bit image among 8-bit ones was decoded");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(std::string(e.what()).find(wide[0].string()) != std::string::npos);
    CHECK(std::string(e.what()).find("16-bit") != std::string::npos);
  }
}

namespace {

// CRC-32 of PNG chunks (ISO 3309, polynomial 0xEDB88320), written out here.
std::uint32_t crc32Of(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

// The PNG with its image data replaced by bytes that do not inflate, its chunk CRC made right:
// the file's structure is sound, its pixels cannot be decoded.
void spoilImageData(const fs::path& png) {
  std::ifstream in(png, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t type = bytes.find("IDAT");
  REQUIRE(type != std::string::npos);
  const std::size_t length = (std::size_t(std::uint8_t(bytes[type - 4])) << 24) |
                             (std::size_t(std::uint8_t(bytes[type - 3])) << 16) |
                             (std::size_t(std::uint8_t(bytes[type - 2])) << 8) | std::uint8_t(bytes[type - 1]);
  for (std::size_t k = 0; k < length; ++k) bytes[type + 4 + k] = static_cast<char>(0xA5 ^ k);
  const std::uint32_t crc = crc32Of(bytes.substr(type, 4 + length));
  for (int k = 0; k < 4; ++k) bytes[type + 4 + length + k] = static_cast<char>(crc >> (24 - 8 * k));
  std::ofstream(png, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

TEST_CASE("while the first image decodes the others decode too, and its failure is the step's error") {
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    // The first image, which gives the stack its format, cannot be decoded: its own error ends
    // the step (the others, decoded meanwhile, do not wait for it for ever).
    std::vector<fs::path> files = pngs("decode-first-fails", 5, 3, 8);
    spoilImageData(files[0]);
    try {
      decodeUnder(files, std::size_t(2) << 30, threads);
      FAIL("a first image whose data does not inflate was decoded");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(std::string(e.what()).find(files[0].string()) != std::string::npos);
    }
    // A later image that cannot be decoded: its error, whichever image finished first.
    files = pngs("decode-later-fails", 5, 3, 8);
    spoilImageData(files[3]);
    try {
      decodeUnder(files, std::size_t(2) << 30, threads);
      FAIL("an image whose data does not inflate was decoded");
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find(files[3].string()) != std::string::npos);
    }
    // Sound images: every one in its place.
    files = pngs("decode-all-sound", 5, 3, 8);
    const Decoded d = decodeUnder(files, std::size_t(2) << 30, threads);
    for (int i = 0; i < 5; ++i) CHECK(allRows(*d.stacks.rgb, i) == image::decodeImage(files[i], {}).pixels);
  }
}

TEST_CASE("the first JPEG, decoded into the stack it makes, fails or is accepted as any other") {
  // A JPEG's decoder asks for its destination once the header is read: the first image makes the
  // stack then, and its damage, found later, is still the step's error (or, accepted, in its slot).
  const std::vector<fs::path> sound = generatedJpegs();
  const fs::path dir = fs::temp_directory_path() / "decode-first-jpeg-damaged";
  fs::create_directories(dir);
  std::vector<fs::path> files;
  for (const fs::path& f : sound) {
    files.push_back(dir / f.filename());
    fs::copy_file(f, files.back(), fs::copy_options::overwrite_existing);
  }
  test::writeBytes(files[0], test::halfJpeg(test::readBytes(sound[0])));
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    pipeline::RunSettings run;
    run.memoryBudget = std::size_t(2) << 30;
    run.threads = threads;
    try {
      stages::decodeImages(files, image::RawDecodeSettings(), run);
      FAIL("a first JPEG libjpeg reports damaged was decoded");
    } catch (const image::DamagedImageError& e) {
      CHECK(e.file() == files[0].string());
    }
    const stages::DecodedStacks d = stages::decodeImages(files, image::RawDecodeSettings(), run, {true});
    image::DecodeOptions accept;
    accept.acceptDamage = true;
    CHECK_FALSE(d.images[0].report.decoderWarnings.empty());
    for (int i = 0; i < kImages; ++i)
      CHECK(allRows(*d.rgb, i) == image::decodeImage(files[i], {}, nullptr, accept).pixels);
  }
}
