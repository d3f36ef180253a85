// PNG through libpng directly: its warnings (a chunk's CRC error, benign errors such as extra
// compressed data, a palette index out of range) reach DecoderMessages through png_set_error_fn,
// never stderr; its errors end the decode with its message. Output as OpenCV's imread made it:
// palette -> RGB, grey of 1/2/4 bits -> 8 bits, grey+alpha -> RGB, 16 bits kept, alpha dropped.
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <png.h>

#include "core/error.h"
#include "image/export_decoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

struct Source {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t pos;
};

struct Sink {
  std::jmp_buf jump;
  char fatal[256];
  DecoderMessages* messages;
  bool stopOnWarning;
};

// Neither returns to libpng with a C++ object alive between it and the setjmp below.
void onError(png_structp png, png_const_charp text) {
  auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
  std::snprintf(sink->fatal, sizeof sink->fatal, "%s", text ? text : "(no text)");
  std::longjmp(sink->jump, 1);
}

void onWarning(png_structp png, png_const_charp text) {
  auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
  sink->messages->add(text);
  if (sink->stopOnWarning) std::longjmp(sink->jump, 2);
}

void readBytes(png_structp png, png_bytep out, png_size_t n) {
  auto* src = static_cast<Source*>(png_get_io_ptr(png));
  if (n > src->size - src->pos) png_error(png, "the file ends inside a chunk");
  std::memcpy(out, src->data + src->pos, n);
  src->pos += n;
}

struct Job {
  png_structp png = nullptr;
  png_infop info = nullptr;
  png_infop end = nullptr;
  Sink sink;
  Source source;
  png_uint_32 width = 0, height = 0;
  int bitDepth = 0, colorType = 0, channels = 0;  // channels: what OpenCV made of it (1, 3 or 4)
  ~Job() {
    if (png) png_destroy_read_struct(&png, info ? &info : nullptr, end ? &end : nullptr);
  }
};

// 0 after an error, 2 after a warning when warnings stop the decode, 1 when done.
int readHeader(Job* job) {
  switch (setjmp(job->sink.jump)) {
    case 0: break;
    case 2: return 2;
    default: return 0;
  }
  png_structp png = job->png;
  png_set_read_fn(png, &job->source, readBytes);
  // CRC errors become warnings (then refused, or with damage accepted, the data is used as
  // it is); benign errors are warnings too. The sRGB-profile check is about colour-management
  // metadata Surrogate does not use, not about the data.
  png_set_crc_action(png, PNG_CRC_WARN_USE, PNG_CRC_WARN_DISCARD);
  png_set_benign_errors(png, 1);
#ifdef PNG_SKIP_sRGB_CHECK_PROFILE
  png_set_option(png, PNG_SKIP_sRGB_CHECK_PROFILE, PNG_OPTION_ON);
#endif
  png_read_info(png, job->info);
  png_get_IHDR(png, job->info, &job->width, &job->height, &job->bitDepth, &job->colorType, nullptr,
               nullptr, nullptr);
  return 1;
}

int readPixels(Job* job, png_bytep* rows) {
  switch (setjmp(job->sink.jump)) {
    case 0: break;
    case 2: return 2;
    default: return 0;
  }
  png_structp png = job->png;
  if (job->bitDepth == 16) png_set_swap(png);  // little-endian host: native 16-bit samples
  if (job->channels < 4) png_set_strip_alpha(png);
  else png_set_tRNS_to_alpha(png);
  if (job->colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if ((job->colorType & PNG_COLOR_MASK_COLOR) == 0 && job->bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (job->channels > 1 && (job->colorType & PNG_COLOR_MASK_COLOR) == 0) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, job->info);
  png_read_image(png, rows);
  png_read_end(png, job->end);
  return 1;
}

[[noreturn]] void fatal(const fs::path& path, const Job& job) {
  throwInputError(path.string(), kStep,
                  std::string("libpng cannot decode it: ") + job.sink.fatal +
                      "; the file is damaged: copy it again");
}

}  // namespace

DecodedPixels decodePng(const fs::path& path, const std::uint8_t* data, std::size_t size,
                        const DecodeOptions& options, DecoderMessages& messages) {
  auto job = std::make_unique<Job>();
  job->sink.fatal[0] = '\0';
  job->sink.messages = &messages;
  job->sink.stopOnWarning = !options.acceptDamage;
  job->source = {data, size, 0};
  job->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job->sink, onError, onWarning);
  if (job->png) job->info = png_create_info_struct(job->png);
  if (job->png) job->end = png_create_info_struct(job->png);
  if (!job->png || !job->info || !job->end)
    throw Error(ErrorKind::Internal, path.string(), kStep, "libpng could not start (out of memory)");

  int status = readHeader(job.get());
  if (status == 0) fatal(path, *job);
  if (status == 2) return {};
  checkDeclaredSize(path, job->width, job->height, options);
  if (job->bitDepth > 8 && job->bitDepth != 16)  // libpng refuses these itself; a guard
    throwInputError(path.string(), kStep, "unsupported PNG bit depth " + std::to_string(job->bitDepth));
  // The channels OpenCV's imread gave (IMREAD_UNCHANGED): RGB or palette with transparency, and
  // anything with alpha, as 4 (the 4th is dropped below); other colour as 3; grey as 1.
  switch (job->colorType) {
    case PNG_COLOR_TYPE_RGB:
    case PNG_COLOR_TYPE_PALETTE:
      job->channels = png_get_valid(job->png, job->info, PNG_INFO_tRNS) ? 4 : 3;
      break;
    case PNG_COLOR_TYPE_GRAY_ALPHA:
    case PNG_COLOR_TYPE_RGB_ALPHA: job->channels = 4; break;
    default: job->channels = 1;
  }
  const int bytesPerSample = job->bitDepth == 16 ? 2 : 1;
  const std::size_t stride = static_cast<std::size_t>(job->width) * job->channels * bytesPerSample;
  std::vector<std::uint8_t> pixels(stride * job->height);
  std::vector<png_bytep> rows(job->height);
  for (png_uint_32 y = 0; y < job->height; ++y) rows[y] = pixels.data() + y * stride;
  status = readPixels(job.get(), rows.data());
  if (status == 0) fatal(path, *job);
  if (status == 2) return {};
  if (png_get_rowbytes(job->png, job->info) != stride)
    throw Error(ErrorKind::Internal, path.string(), kStep, "libpng gave another row layout than asked for");

  const int w = static_cast<int>(job->width), h = static_cast<int>(job->height);
  const int kept = job->channels == 4 ? 3 : job->channels;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  DecodedPixels out;
  if (bytesPerSample == 1) {
    if (kept == job->channels) {
      out.narrow.pixels = std::move(pixels);  // already the layout: no copy
    } else {
      out.narrow.pixels.resize(n * kept);
      for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < kept; ++c) out.narrow.pixels[i * kept + c] = pixels[i * job->channels + c];
    }
    out.narrow.width = w;
    out.narrow.height = h;
    out.narrow.channels = kept;
    out.narrow.transfer = Transfer::Srgb;
    return out;
  }
  out.wide = Image(w, h, kept);
  out.wide.bitsPerSample = 16;
  out.wide.transfer = Transfer::Srgb;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < kept; ++c) std::memcpy(&out.wide.pixels[i * kept + c], pixels.data() + 2 * (i * job->channels + c), 2);
  return out;
}

std::string libpngVersion() { return png_get_libpng_ver(nullptr); }

}  // namespace surrogate::image
