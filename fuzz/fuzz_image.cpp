// libFuzzer target: the image decoders on arbitrary bytes, through the project's own entry
// points as the pipeline calls them: classification by content, the probe (JPEG marker walk,
// PNG chunks, TIFF directories and strip tables, LibRaw's header parse) and the decode (libjpeg,
// libpng, libtiff, LibRaw), strict and with damage accepted. JPEG, PNG, TIFF, DNG and the other
// raw containers LibRaw reads. Every failure must be a surrogate::Error: anything else (a crash,
// a leak, an exception of another type, a hang) is a finding.
//
// The decoders read files, so each input is written to one file per process (in $TMPDIR) first.
//
// Seed corpus (fuzz/corpus/image): tiny sound files of each kind (JPEG colour, grey and
// progressive with restarts; PNG RGB, RGBA, 16-bit grey; TIFF 16-bit RGB and LZW grey; a DNG
// with lossless-JPEG tiles) and damaged ones made by tests/image/damage.h (half a JPEG with its
// end marker re-appended, flipped bits, a PNG with a broken IDAT CRC, a TIFF with a short strip
// table, a DNG with a corrupt tile, headers declaring 20000x20000), plus two malformed raws from
// tests/data/bad-inputs.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "image/decode.h"

namespace {

// The decoders read files by name: each input is written to one scratch file, whose folder is
// removed when the process ends.
struct ScratchFolder {
  std::filesystem::path dir;
  ScratchFolder() {
    const char* tmp = std::getenv("TMPDIR");
    dir = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
          ("surrogate-fuzz-image-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

const std::filesystem::path& inputFile() {
  static const ScratchFolder scratch;
  static const std::filesystem::path file = scratch.dir / "input";
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace surrogate;
  const std::filesystem::path& file = inputFile();
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)image::probeImage(file);
  } catch (const Error&) {
  }
  // Decoded images are bounded (the fuzzer's memory limit is 2 GB): 4 Mpx.
  image::DecodeOptions options;
  options.maxPixels = 4'000'000;
  for (const bool accept : {false, true}) {
    options.acceptDamage = accept;
    try {
      image::DecodeReport report;
      (void)image::decodeImage(file, image::RawDecodeSettings(), &report, options);
    } catch (const Error&) {
    }
  }
  return 0;
}
