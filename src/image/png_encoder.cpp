#include "image/png_encoder.h"

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <png.h>
#include <zlib.h>

#include "core/error.h"

namespace surrogate::image {

namespace {

constexpr const char* kStep = "image write";

// libpng reports errors by calling back; the callback jumps back to encodePng's setjmp with
// the message kept here. No C++ object with a destructor lives between the two.
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

// 0 when done, 1 after a libpng error (the message is in sink->message).
int encodeRows(WriteStruct* ws, Sink* sink, const Image& image, bool eightBit, std::uint8_t* row) {
  if (setjmp(sink->jump)) return 1;
  png_structp png = ws->png;
  png_set_write_fn(png, sink, appendBytes, flushNothing);
  png_set_IHDR(png, ws->info, image.width, image.height, eightBit ? 8 : 16,
               image.channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, ws->info);
  for (int y = 0; y < image.height; ++y) {
    packRow(image, y, eightBit, row);
    png_write_row(png, row);
  }
  png_write_end(png, ws->info);
  return 0;
}

}  // namespace

std::string encodePng(const Image& image, const std::string& what) {
  if (image.empty() || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, what, kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  const bool eightBit = image.bitsPerSample <= 8;
  std::string out;
  // Noisy pictures hardly shrink: room for the samples spares the string's regrowth.
  out.reserve(static_cast<std::size_t>(image.width) * image.height * image.channels * (eightBit ? 1 : 2) + 4096);
  std::vector<std::uint8_t> row(static_cast<std::size_t>(image.width) * image.channels * (eightBit ? 1 : 2));
  Sink sink;
  sink.out = &out;
  WriteStruct ws;
  ws.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  if (ws.png) ws.info = png_create_info_struct(ws.png);
  if (!ws.png || !ws.info) throw Error(ErrorKind::Internal, what, kStep, "libpng could not start an encoder");
  if (encodeRows(&ws, &sink, image, eightBit, row.data()) != 0)
    throw Error(ErrorKind::Internal, what, kStep, std::string("libpng could not encode the image: ") + sink.message);
  return out;
}

}  // namespace surrogate::image
