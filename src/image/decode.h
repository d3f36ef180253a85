// Decoding photographs: camera raw and DNG through LibRaw, JPEG through libjpeg(-turbo), PNG
// through libpng, TIFF through libtiff, each called directly so that every message the library
// has about the data reaches Surrogate (none is printed, none is lost).
//
// The folder's front door: including it gives the whole public interface of src/image.
//
//   camera raw, DNG --LibRaw, RawDecodeSettings------------> linear 16-bit RGB     (Transfer::Linear)
//   JPEG, TIFF, PNG --libjpeg / libtiff / libpng, as stored-> 8/16-bit grey or RGB  (Transfer::Srgb)
//
// Every LibRaw setting that changes pixels is fixed by RawDecodeSettings, which the pipeline
// records in the carrier and re-applies on re-execution, so decoding is deterministic:
//
//   RawDecodeSettings settings;                   // AHD, as-shot white balance, linear sRGB
//   DecodeReport report;
//   Image im = decodeImage("IMG_0001.dng", settings, &report);
//   // report.decoder == "LibRaw 0.20.2-Release", report.blackLevel, report.whiteLevel, ...
//
// Errors are surrogate::Error(Input) naming the file, with a sentence a photographer can act
// on ("the file is truncated ..."). No library prints to the terminal.
//
// Decoding is strict: a library's warning that the data is damaged (libjpeg's "Corrupt JPEG
// data: ...", a libpng or libtiff warning, a LibRaw data error) refuses the image with the
// library's words (DamagedImageError), unless the caller accepts damage for that image
// (DecodeOptions::acceptDamage, which the pipeline sets only for an image the user accepted with
// a recorded intervention); the warnings are then in DecodeReport::decoderWarnings.
//
// Sizes are checked before any pixel is decoded: an image whose header declares more than
// DecodeOptions::maxPixels (at most kMaxImagePixels) is refused without allocating its pixels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "image/raw_settings.h"
#include "image/source_kind.h"
#include "image/srgb.h"
#include "image/write.h"

namespace surrogate::image {

// The largest image Surrogate reads: 500 megapixels (a 16-bit RGB copy is 3 GB). No camera
// comes near it (the largest sensors give 150-400 Mpx as multi-shot composites); a header that
// declares more is damaged or crafted, and is refused as bad input.
inline constexpr std::uint64_t kMaxImagePixels = 500'000'000;

// The fewest bytes a Huffman-coded JPEG of width x height pixels can hold. Each 8x8 block of a
// component costs at least one bit (its DC difference, in a sequential scan and in a
// progressive DC scan alike), and the component sampled most finely spans the whole width and at
// least a quarter of the height, or the reverse (sampling factors are 1 to 4): at least
// width x height / 256 blocks. A stream with fewer bytes than this that declares such a size is
// damaged or made to exhaust memory, and is refused before it is decoded. Arithmetic coding has
// no such floor (nor do the viewers decode it); it is left to the memory budget.
inline constexpr std::uint64_t minimumHuffmanJpegBytes(std::uint64_t width, std::uint64_t height) {
  return width * height / 2048;
}

struct ImageProbe {
  int width = 0;   // as decodeImage returns it with default settings
  int height = 0;
  SourceKind kind = SourceKind::Jpeg;
};

// Checks that the file is a readable, complete image and returns its size without decoding
// pixels: JPEG markers up to end-of-image, PNG header and end chunk, TIFF strip table, LibRaw's
// header parse for raw. Missing, empty, truncated or unsupported files are Error(Input), and so
// is a header declaring more than kMaxImagePixels.
// (A raw whose pixel data is damaged inside an intact container is found by decodeImage.)
ImageProbe probeImage(const std::filesystem::path& path);

struct DecodeReport {
  std::string decoder;  // "LibRaw 0.20.2-Release" or "OpenCV 4.6.0"
  int blackLevel = -1;  // camera raw only: the black level subtracted (file's, or the override)
  int whiteLevel = -1;  // camera raw only: the white (saturation) level scaled to 65535
  // Camera raw only: the black level subtracted from each channel (R, G, B, G2): the common
  // level plus the file's per-channel offsets (all equal to blackLevel when overridden).
  std::vector<int> channelBlackLevels;
  std::vector<double> whiteBalanceMultipliers;  // camera raw only: applied R, G, B, G2 (G = 1)
  std::vector<std::string> warnings;            // e.g. no as-shot white balance in the file
  // Only with DecodeOptions::acceptDamage: what the decoding library said about damaged data,
  // in its own words, prefixed by its name ("libjpeg: Corrupt JPEG data: premature end of data
  // segment"); at most a few distinct messages, then "... (N warnings in all)".
  std::vector<std::string> decoderWarnings;
};

struct DecodeOptions {
  // Decode an image whose data the library reports as damaged, as the library can (libjpeg
  // fills what is missing with grey, LibRaw with what it read, libtiff leaves an unreadable
  // strip black), recording its warnings instead of refusing the image.
  bool acceptDamage = false;
  // Refused (Error(Input)) before decoding when its header declares more pixels than this
  // (never more than kMaxImagePixels).
  std::uint64_t maxPixels = kMaxImagePixels;
  // Where an 8-bit JPEG or a camera raw image (16-bit samples in the machine's byte order) is
  // decoded to: asked, once the decoder knows the output's layout, for a buffer of width *
  // height * channels * bytesPerSample bytes (channels of the output: 1 grey, 3 RGB; the
  // samples' transfer) that the decoder writes the samples into directly; nullptr (or no
  // function) for a buffer of the decoder's own. The pipeline passes its stack's slot: no copy,
  // no zeroing of memory about to be written. Other formats decode into their own buffers.
  std::function<std::uint8_t*(int width, int height, int channels, int bytesPerSample, Transfer transfer)>
      destination;
};

// The library reported damaged data and the caller did not accept damage: Error(Input) naming
// the file, with the library's words in the message and in warnings().
class DamagedImageError : public Error {
 public:
  DamagedImageError(const std::string& file, std::string library, std::vector<std::string> warnings);
  const std::string& library() const { return library_; }         // "libjpeg", "libpng", ...
  const std::vector<std::string>& warnings() const { return warnings_; }  // its own words

 private:
  std::string library_;
  std::vector<std::string> warnings_;
};

// An image at its source's depth, as decodePixels gives it: 8-bit sources (JPEG, 8-bit PNG and
// TIFF) one byte a sample in `narrow`, camera raw and 16-bit sources in `wide`; the other is
// empty. The pipeline keeps images this way: a JPEG takes half the memory of its Image.
//
// Decoded into DecodeOptions::destination's buffer, the samples are at `placed`, and the image
// that describes them (narrow for 8-bit samples, wide for 16-bit) has no pixels of its own but
// still gives the size, depth and transfer.
struct DecodedPixels {
  Image8 narrow;
  Image wide;
  std::uint8_t* placed = nullptr;
  bool placedNarrow = false;  // with `placed`: 8-bit samples (else 16-bit)

  bool isNarrow() const { return placed ? placedNarrow : !narrow.pixels.empty(); }
  int width() const { return isNarrow() ? narrow.width : wide.width; }
  int height() const { return isNarrow() ? narrow.height : wide.height; }
  int channels() const { return isNarrow() ? narrow.channels : wide.channels; }
  int bitsPerSample() const { return isNarrow() ? 8 : wide.bitsPerSample; }
  int bytesPerSample() const { return isNarrow() ? 1 : 2; }
  Transfer transfer() const { return isNarrow() ? narrow.transfer : wide.transfer; }
  // The samples' bytes, as stored in memory (16-bit samples in the machine's byte order).
  const void* data() const;
  std::size_t bytes() const;
  // As decodeImage returns it: `wide`, or `narrow` widened by 257.
  Image widened() const;
};

// Decodes the whole image, at the source's depth (see DecodedPixels); otherwise as decodeImage.
DecodedPixels decodePixels(const std::filesystem::path& path, const RawDecodeSettings& settings,
                           DecodeReport* report = nullptr, const DecodeOptions& options = {});

// Decodes the whole image. Camera raw: linear 16-bit RGB (or grey for monochrome sensors).
// Others: as stored (8-bit widened by 257, bitsPerSample kept; grey stays one channel; alpha
// dropped; the EXIF orientation tag is not applied), the same values OpenCV's imread gave
// (IMREAD_UNCHANGED | IMREAD_ANYDEPTH | IMREAD_IGNORE_ORIENTATION), which decoded them before.
// Safe to call from several threads at once.
Image decodeImage(const std::filesystem::path& path, const RawDecodeSettings& settings,
                  DecodeReport* report = nullptr, const DecodeOptions& options = {});

// A JPEG stream held in memory (one plane of a JPEG-compressed PTM, for instance), decoded by
// libjpeg strictly: a fatal error or any warning about damaged data (a truncated stream, a bad
// Huffman code) leaves `samples` empty and says why in `problem`, in libjpeg's words, for the
// caller to word its own error. A header declaring more than maxPixels (or kMaxImagePixels),
// or more pixels than `size` bytes of Huffman-coded data can hold (minimumHuffmanJpegBytes), is
// refused before any sample buffer is allocated. Grey stays one channel; other streams
// come out as RGB; CMYK is refused.
//
//   JpegSamples plane = decodeJpegSamples(bytes, size, expectedWidth * expectedHeight);
//   if (!plane.problem.empty()) throw ...;   // plane.samples[y * width + x] for grey
struct JpegSamples {
  int width = 0, height = 0, components = 0;  // components: 1 (grey) or 3 (RGB)
  std::vector<std::uint8_t> samples;          // rows top first as stored, channels interleaved
  std::string problem;                        // empty when decoded
};
JpegSamples decodeJpegSamples(const std::uint8_t* data, std::size_t size, std::uint64_t maxPixels);

// A PNG or JPEG picture held in memory (one a report shows from a capture or a package),
// decoded as decodeImage decodes such files: structure checked, any warning of damage refusing
// it, at its own depth (8-bit in `narrow`, 16-bit in `wide`). Error(Input) naming `name` when
// it is neither, is incomplete or damaged, or declares more than maxPixels.
DecodedPixels decodePicture(const std::uint8_t* data, std::size_t size, const std::string& name,
                            std::uint64_t maxPixels);

std::string librawVersion();   // "0.20.2-Release" (LibRaw::version())
std::string opencvVersion();   // "4.6.0"
std::string libjpegName();     // "libjpeg-turbo" (the libjpeg JPEGs are decoded with)
std::string libjpegVersion();  // "2.1.5"
std::string libpngVersion();   // "1.6.39" (png_get_libpng_ver)
std::string libtiffVersion();  // "4.5.0" (TIFFGetVersion)

}  // namespace surrogate::image
