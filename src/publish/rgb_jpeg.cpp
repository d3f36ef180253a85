#include "publish/rgb_jpeg.h"

#include <csetjmp>
#include <cstdio>
#include <cstdlib>

#include <jpeglib.h>

#include "core/error.h"

namespace surrogate::publish {

namespace {
struct ErrorJump {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
};

void onError(j_common_ptr info) {
  std::longjmp(reinterpret_cast<ErrorJump*>(info->err)->jump, 1);
}

void ignoreMessage(j_common_ptr, int) {}

// Plain C between setjmp and longjmp: no destructor is skipped. Returns false on failure.
bool compress(jpeg_compress_struct* c, const std::uint8_t* pixels, int width, int height, int quality,
              unsigned char** out, unsigned long* size) {
  ErrorJump* err = reinterpret_cast<ErrorJump*>(c->err);
  if (setjmp(err->jump)) return false;
  jpeg_create_compress(c);
  jpeg_mem_dest(c, out, size);
  c->image_width = static_cast<JDIMENSION>(width);
  c->image_height = static_cast<JDIMENSION>(height);
  c->input_components = 3;
  c->in_color_space = JCS_RGB;
  jpeg_set_defaults(c);
  jpeg_set_colorspace(c, JCS_RGB);  // no YCbCr transform; every component sampled 1x1
  c->dct_method = JDCT_ISLOW;
  c->optimize_coding = FALSE;
  c->write_JFIF_header = FALSE;     // the Adobe marker says "RGB"; a JFIF one would say YCbCr
  jpeg_set_quality(c, quality, TRUE);
  jpeg_start_compress(c, TRUE);
  const std::size_t stride = static_cast<std::size_t>(width) * 3;
  while (c->next_scanline < c->image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(pixels + c->next_scanline * stride);
    jpeg_write_scanlines(c, &row, 1);
  }
  jpeg_finish_compress(c);
  return true;
}
}  // namespace

std::string encodeRgbJpeg(const std::vector<std::uint8_t>& pixels, int width, int height, int quality) {
  jpeg_compress_struct c{};
  ErrorJump err{};
  c.err = jpeg_std_error(&err.pub);
  err.pub.error_exit = onError;
  err.pub.emit_message = ignoreMessage;
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const bool ok = compress(&c, pixels.data(), width, height, quality, &out, &size);
  jpeg_destroy_compress(&c);
  std::string bytes = ok && out ? std::string(reinterpret_cast<const char*>(out), size) : std::string();
  std::free(out);
  if (!ok)
    throw Error(ErrorKind::Internal, "", "publish", "libjpeg could not encode a coefficient plane");
  return bytes;
}

}  // namespace surrogate::publish
