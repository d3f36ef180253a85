// Damaged, missing and non-image files: an Error(Input) naming the file or valid metadata,
// never a crash; and reading from several threads at once.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "core/error.h"
#include "meta/metadata.h"

using namespace surrogate;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data" / name; }

fs::path scratchDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("surrogate-test-meta-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

template <typename Call>
void requireInputErrorNaming(const fs::path& file, Call&& call) {
  try {
    call();
    FAIL("no error for " << file);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == file.string());
  }
}
}  // namespace

TEST_CASE("malformed files give an Error naming the file or valid metadata, never a crash") {
  // Measured with Exiv2 0.27.6: issue_1097, _839, _843, _857 are refused ("corrupted image
  // metadata", "Offset out of range"); the others open with no tags.
  int refused = 0;
  for (const auto& entry : fs::directory_iterator(fixture("bad-inputs"))) {
    if (entry.path().extension() == ".md") continue;
    INFO(entry.path().filename().string());
    try {
      const meta::CameraMetadata m = meta::readMetadata(entry.path());
      CHECK_FALSE(m.make);
    } catch (const Error& e) {
      ++refused;
      CHECK(e.kind() == ErrorKind::Input);
      CHECK(e.file() == entry.path().string());
    }
  }
  CHECK(refused == 4);
}

TEST_CASE("missing files, text files and broken sidecars are refused by name") {
  const fs::path dir = scratchDir("errors");
  requireInputErrorNaming(dir / "missing.jpg", [&] { meta::readMetadata(dir / "missing.jpg"); });
  std::ofstream(dir / "text.jpg") << "not an image";
  requireInputErrorNaming(dir / "text.jpg", [&] { meta::readMetadata(dir / "text.jpg"); });
  std::ofstream(dir / "broken.xmp") << "<x:xmpmeta><rdf:RDF><unclosed";
  requireInputErrorNaming(dir / "broken.xmp", [&] { meta::readXmpSidecar(dir / "broken.xmp"); });
  std::ofstream(dir / "notes.xmp") << "shot on a Tuesday";
  requireInputErrorNaming(dir / "notes.xmp", [&] { meta::readXmpSidecar(dir / "notes.xmp"); });
  requireInputErrorNaming(dir / "missing.xmp", [&] { meta::readXmpSidecar(dir / "missing.xmp"); });
  fs::remove_all(dir);
}

TEST_CASE("metadata read from several threads at once is the same as read alone") {
  const fs::path files[] = {fixture("raw-metadata/DSC_3079.jpg"), fixture("raw-metadata/Canon-R6-pruned.CR3"),
                            fixture("raw-metadata/exiv2-nikon-d70.jpg"),
                            fixture("raw-metadata/StaffPhotographer-Example.xmp")};
  std::vector<meta::CameraMetadata> alone;
  for (const fs::path& f : files) alone.push_back(meta::readMetadata(f));
  std::vector<std::vector<meta::CameraMetadata>> seen(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int round = 0; round < 5; ++round)
        for (const fs::path& f : files) seen[t].push_back(meta::readMetadata(f));
    });
  for (std::thread& t : threads) t.join();
  for (const auto& results : seen)
    for (std::size_t i = 0; i < results.size(); ++i) {
      const meta::CameraMetadata& a = results[i];
      const meta::CameraMetadata& b = alone[i % 4];
      CHECK(a.model == b.model);
      CHECK(a.lens == b.lens);
      CHECK(a.iso == b.iso);
      CHECK(a.xmpPacket == b.xmpPacket);
    }
}
