#include "image/png_encoder.h"

#include <algorithm>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include <libdeflate.h>
#include <png.h>

#include "core/error.h"
#include "core/resident.h"
#include "image/write.h"

namespace surrogate::image {

namespace {

constexpr const char* kStep = "image write";

// An iTXt chunk (PNG 1.2, ISO/IEC 15948 11.3.4.5: keyword, compression flag and method, empty
// language tag and translated keyword, text) naming the software, uncompressed. It makes the file
// what PRONOM calls PNG 1.2 (fmt/13, whose signature is an iTXt chunk; without one DROID and
// Siegfried say PNG 1.0, fmt/11: mappings/pronom.md). The same bytes in every file; viewers skip
// ancillary chunks they do not show.
const char kSoftwareText[] = "Software\0\0\0\0\0Surrogate";

// The compressed stream goes into IDAT chunks of at most this many bytes (decoders take any
// size up to 2^31 - 1; libpng's own encoder writes 8 KiB).
constexpr std::size_t kIdatBytes = 1 << 20;

// libpng reports errors by calling back; the callback jumps back to writeContainer's setjmp
// with the message kept here. No C++ object with a destructor lives between the two.
struct Sink {
  std::jmp_buf jump;
  char message[256] = {};
  std::string* out = nullptr;
};

void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message ? message : "unknown error");
  std::longjmp(sink->jump, 1);
}

void onWarning(png_structp, png_const_charp) {}  // an encoder's warnings do not change the file

void appendBytes(png_structp png, png_bytep data, png_size_t size) {
  auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
  sink->out->append(reinterpret_cast<const char*>(data), size);
}

void flushNothing(png_structp) {}

struct WriteStruct {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteStruct() {
    if (png) png_destroy_write_struct(&png, info ? &info : nullptr);
  }
};

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// Row y of `image` as the PNG stores it: 8-bit samples rounded from 16-bit, or 16-bit samples
// big-endian.
void packRow(const Image& image, int y, bool eightBit, std::uint8_t* row) {
  const std::size_t n = static_cast<std::size_t>(image.width) * image.channels;
  const std::uint16_t* in = image.pixels.data() + static_cast<std::size_t>(y) * n;
  if (eightBit) {
    narrowSamples(in, n, row);
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      row[2 * i] = static_cast<std::uint8_t>(in[i] >> 8);
      row[2 * i + 1] = static_cast<std::uint8_t>(in[i] & 0xff);
    }
  }
}

// The image data before compression: each row as its filter type byte (2, Up) and the row's
// bytes minus those of the row above (the first row's, minus zero), modulo 256.
std::vector<std::uint8_t> filteredRows(const Image& image, bool eightBit) {
  const std::size_t rowBytes = static_cast<std::size_t>(image.width) * image.channels * (eightBit ? 1 : 2);
  std::vector<std::uint8_t> out;
  resizeResident(out, static_cast<std::size_t>(image.height) * (rowBytes + 1));
  std::vector<std::uint8_t> above(rowBytes, 0), row(rowBytes);
  for (int y = 0; y < image.height; ++y) {
    packRow(image, y, eightBit, row.data());
    std::uint8_t* f = out.data() + static_cast<std::size_t>(y) * (rowBytes + 1);
    f[0] = 2;
    for (std::size_t i = 0; i < rowBytes; ++i) f[1 + i] = static_cast<std::uint8_t>(row[i] - above[i]);
    row.swap(above);
  }
  return out;
}

// A zlib stream in a buffer of the largest size it could have, of which only `size` bytes are
// written: the buffer is left uninitialised, so that only the pages the stream fills are ever
// backed by memory (a zeroed vector of that size had touched all of it).
struct ZlibStream {
  std::unique_ptr<std::uint8_t[]> bytes;
  std::size_t size = 0;
};

// The zlib stream of `data`, by libdeflate at level 1.
ZlibStream deflated(const std::vector<std::uint8_t>& data, const std::string& what) {
  std::unique_ptr<libdeflate_compressor, CompressorFree> compressor(libdeflate_alloc_compressor(1));
  if (!compressor) throw Error(ErrorKind::Internal, what, kStep, "libdeflate could not start a compressor");
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), data.size());
  ZlibStream out;
  out.bytes.reset(new std::uint8_t[bound]);
  out.size = libdeflate_zlib_compress(compressor.get(), data.data(), data.size(), out.bytes.get(), bound);
  if (out.size == 0) throw Error(ErrorKind::Internal, what, kStep, "libdeflate could not compress the image");
  return out;
}

// 0 when done, 1 after a libpng error (the message is in sink->message). libpng writes the
// signature and header, the iTXt chunk naming the software, and frames the compressed stream
// given as IDAT chunks and the end chunk with their lengths and CRCs (png_write_chunk, its call
// for chunks it does not make itself): its own compression, one row at a time through zlib, is never used.
int writeContainer(WriteStruct* ws, Sink* sink, const Image& image, bool eightBit,
                   const ZlibStream& stream) {
  if (setjmp(sink->jump)) return 1;
  png_structp png = ws->png;
  png_set_write_fn(png, sink, appendBytes, flushNothing);
  png_set_IHDR(png, ws->info, image.width, image.height, eightBit ? 8 : 16,
               image.channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, ws->info);
  static const png_byte itxt[5] = "iTXt", idat[5] = "IDAT", iend[5] = "IEND";
  png_write_chunk(png, itxt, reinterpret_cast<png_const_bytep>(kSoftwareText), sizeof kSoftwareText - 1);
  for (std::size_t at = 0; at < stream.size; at += kIdatBytes)
    png_write_chunk(png, idat, stream.bytes.get() + at, std::min(kIdatBytes, stream.size - at));
  png_write_chunk(png, iend, nullptr, 0);
  return 0;
}

}  // namespace

std::string encodePng(const Image& image, const std::string& what) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, what, kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  const bool eightBit = image.bitsPerSample <= 8;
  const ZlibStream stream = deflated(filteredRows(image, eightBit), what);
  std::string out;
  reserveResident(out, stream.size + (stream.size / kIdatBytes + 1) * 12 + 4096);  // libpng appends the chunks
  Sink sink;
  sink.out = &out;
  WriteStruct ws;
  ws.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  if (ws.png) ws.info = png_create_info_struct(ws.png);
  if (!ws.png || !ws.info) throw Error(ErrorKind::Internal, what, kStep, "libpng could not start an encoder");
  if (writeContainer(&ws, &sink, image, eightBit, stream) != 0)
    throw Error(ErrorKind::Internal, what, kStep, std::string("libpng could not encode the image: ") + sink.message);
  return out;
}

// The header's version: libdeflate has no call that tells.
std::string libdeflateVersion() { return LIBDEFLATE_VERSION_STRING; }

}  // namespace surrogate::image
