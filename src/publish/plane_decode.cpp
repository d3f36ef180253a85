#include "publish/plane_decode.h"

#include <csetjmp>
#include <cstdio>

#include <jpeglib.h>

#include "core/error.h"
#include "image/decode.h"

namespace surrogate::publish {

namespace {
const char* const kStep = "render";

struct DecodeErrors {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
  bool failed = false;
};

void onError(j_common_ptr info) {
  auto* e = reinterpret_cast<DecodeErrors*>(info->err);
  (*info->err->format_message)(info, e->message);
  e->failed = true;
  std::longjmp(e->jump, 1);
}

// Level -1 is a warning about the data (a truncated or corrupt stream that libjpeg would
// patch with grey): the plane would decode to coefficients nobody wrote, so it fails too.
void onMessage(j_common_ptr info, int level) {
  auto* e = reinterpret_cast<DecodeErrors*>(info->err);
  if (level >= 0 || e->failed) return;
  (*info->err->format_message)(info, e->message);
  e->failed = true;
}

enum class Outcome { Decoded, Failed, WrongSize, TooFewBytes };

// Plain C between setjmp and longjmp: no destructor is skipped.
Outcome decompress(jpeg_decompress_struct* d, const std::string& bytes, int width, int height,
                   std::vector<std::uint8_t>* out, int* seenWidth, int* seenHeight) {
  auto* e = reinterpret_cast<DecodeErrors*>(d->err);
  if (setjmp(e->jump)) return Outcome::Failed;
  jpeg_create_decompress(d);
  jpeg_mem_src(d, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(d, TRUE);
  *seenWidth = static_cast<int>(d->image_width);
  *seenHeight = static_cast<int>(d->image_height);
  if (d->image_width != static_cast<JDIMENSION>(width) || d->image_height != static_cast<JDIMENSION>(height))
    return Outcome::WrongSize;
  if (!d->arith_code && bytes.size() < image::minimumHuffmanJpegBytes(d->image_width, d->image_height))
    return Outcome::TooFewBytes;
  d->out_color_space = JCS_RGB;
  d->dct_method = JDCT_ISLOW;  // libjpeg's default and most accurate inverse DCT, fixed so results never vary
  jpeg_start_decompress(d);
  out->resize(static_cast<std::size_t>(width) * height * 3);
  const std::size_t stride = static_cast<std::size_t>(width) * 3;
  while (d->output_scanline < d->output_height && !e->failed) {
    JSAMPROW row = out->data() + d->output_scanline * stride;
    jpeg_read_scanlines(d, &row, 1);
  }
  if (!e->failed) jpeg_finish_decompress(d);
  return e->failed ? Outcome::Failed : Outcome::Decoded;
}
}  // namespace

std::vector<std::uint8_t> decodePlaneJpeg(const std::string& bytes, int width, int height, const std::string& file) {
  jpeg_decompress_struct d{};
  DecodeErrors errors{};
  d.err = jpeg_std_error(&errors.pub);
  errors.pub.error_exit = onError;
  errors.pub.emit_message = onMessage;
  std::vector<std::uint8_t> pixels;
  int seenWidth = 0, seenHeight = 0;
  const Outcome outcome = decompress(&d, bytes, width, height, &pixels, &seenWidth, &seenHeight);
  jpeg_destroy_decompress(&d);
  if (outcome == Outcome::WrongSize)
    throw Error(ErrorKind::Input, file, kStep,
                "is " + std::to_string(seenWidth) + "x" + std::to_string(seenHeight) + " pixels, but info.json gives " +
                    std::to_string(width) + "x" + std::to_string(height) +
                    ": the plane does not belong to this layout; publish the model again");
  if (outcome == Outcome::TooFewBytes)
    throw Error(ErrorKind::Input, file, kStep,
                "declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels in " +
                    std::to_string(bytes.size()) + " bytes, fewer than the " +
                    std::to_string(image::minimumHuffmanJpegBytes(static_cast<std::uint64_t>(width),
                                                                  static_cast<std::uint64_t>(height))) +
                    " any JPEG of that size needs: it is damaged or made to exhaust memory; publish the model again");
  if (outcome == Outcome::Failed)
    throw Error(ErrorKind::Input, file, kStep,
                std::string("is not a JPEG plane that decodes cleanly (libjpeg: ") + errors.message +
                    "); publish the model again");
  return pixels;
}

}  // namespace surrogate::publish
