// JPEG encoding through libjpeg(-turbo) directly (write.h's encodeJpeg and writeJpeg), with
// libjpeg's baseline defaults: the settings OpenCV's imencode used when it wrote these files,
// so the bytes are the ones it gave (tests/image/test_write.cpp compares the two).
#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE and size_t first
#include <cstdlib>
#include <string>

#include <jpeglib.h>

#include "core/error.h"
#include "image/write.h"

namespace surrogate::image {

namespace {

constexpr const char* kStep = "image write";

// libjpeg casts cinfo->err to jpeg_error_mgr*: `pub` must come first.
struct ErrorSink {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void onError(j_common_ptr cinfo) {
  auto* sink = reinterpret_cast<ErrorSink*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, sink->message);
  std::longjmp(sink->jump, 1);
}

void onOutput(j_common_ptr) {}  // an encoder's messages do not change the file

struct Output {
  unsigned char* bytes = nullptr;  // malloc'ed by jpeg_mem_dest
  unsigned long size = 0;
};

// 0 when done, 1 after a libjpeg error (its words in sink->message). Plain C between the
// setjmp and libjpeg's calls: the jump skips no destructor.
int compress(jpeg_compress_struct* c, const Image8& image, int quality, Output* out) {
  if (setjmp(reinterpret_cast<ErrorSink*>(c->err)->jump)) return 1;
  jpeg_create_compress(c);
  jpeg_mem_dest(c, &out->bytes, &out->size);
  c->image_width = static_cast<JDIMENSION>(image.width);
  c->image_height = static_cast<JDIMENSION>(image.height);
  c->input_components = image.channels;
  c->in_color_space = image.channels == 3 ? JCS_RGB : JCS_GRAYSCALE;
  jpeg_set_defaults(c);
  jpeg_set_quality(c, quality, TRUE);  // TRUE: quantisation tables kept to baseline values
  jpeg_start_compress(c, TRUE);
  const std::size_t stride = static_cast<std::size_t>(image.width) * image.channels;
  while (c->next_scanline < c->image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.pixels.data() + c->next_scanline * stride);
    jpeg_write_scanlines(c, &row, 1);
  }
  jpeg_finish_compress(c);
  return 0;
}

}  // namespace

std::string encodeJpeg(const Image8& image, int quality, const std::string& what) {
  if (quality < 1 || quality > 100) throw Error(ErrorKind::Usage, what, kStep, "JPEG quality must be 1 to 100");
  if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    throw Error(ErrorKind::Internal, what, kStep,
                "cannot write an empty image or one with " + std::to_string(image.channels) + " channels");
  jpeg_compress_struct c{};
  ErrorSink sink{};
  c.err = jpeg_std_error(&sink.pub);
  sink.pub.error_exit = onError;
  sink.pub.output_message = onOutput;
  Output out;
  const int failed = compress(&c, image, quality, &out);
  jpeg_destroy_compress(&c);  // also after an error: never fails, never jumps
  std::string bytes;
  if (!failed && out.bytes) bytes.assign(reinterpret_cast<const char*>(out.bytes), out.size);
  std::free(out.bytes);
  if (failed) throw Error(ErrorKind::Internal, what, kStep, std::string("libjpeg could not encode the image: ") + sink.message);
  return bytes;
}

}  // namespace surrogate::image
