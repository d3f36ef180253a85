// JPEG through libjpeg(-turbo) directly, with an error manager of our own: libjpeg's warnings
// ("Corrupt JPEG data: premature end of data segment", "... bad Huffman code", ...) go to
// DecoderMessages through emit_message, never to stderr; its fatal errors end the decode with
// its message. Output as OpenCV's imread made it (libjpeg's defaults: islow DCT, fancy
// upsampling; grey stays grey; CMYK/YCCK converted with OpenCV's formula).
#include <algorithm>
#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE and size_t first
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <jpeglib.h>

#include "core/error.h"
#include "image/export_decoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

// libjpeg casts cinfo->err to jpeg_error_mgr*: `pub` must come first.
struct ErrorManager {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char fatal[JMSG_LENGTH_MAX];
  DecoderMessages* messages;
  bool stopOnWarning;
};

// Fatal: keep libjpeg's words and leave the decode (no C++ object lives in the frames between
// the setjmp below and here, so the jump skips no destructor).
void onError(j_common_ptr cinfo) {
  auto* m = reinterpret_cast<ErrorManager*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, m->fatal);
  std::longjmp(m->jump, 1);
}

// Level < 0: a warning about the data (libjpeg goes on); >= 0: trace messages, ignored.
void onMessage(j_common_ptr cinfo, int level) {
  if (level >= 0) return;
  auto* m = reinterpret_cast<ErrorManager*>(cinfo->err);
  cinfo->err->num_warnings++;
  char text[JMSG_LENGTH_MAX];
  (*cinfo->err->format_message)(cinfo, text);
  m->messages->add(text);
  if (m->stopOnWarning) std::longjmp(m->jump, 2);  // refused anyway: no need to decode on
}

void onOutput(j_common_ptr) {}  // nothing is ever printed

struct Job {
  jpeg_decompress_struct cinfo;
  ErrorManager err;
  bool created = false;
};

// The steps that may jump back: plain C, each with its own setjmp. They return 0 after a
// fatal error, 2 after a warning when warnings stop the decode, 1 when done.
int startJob(Job* job, const std::uint8_t* data, std::size_t size) {
  switch (setjmp(job->err.jump)) {
    case 0: break;
    case 2: return 2;
    default: return 0;
  }
  jpeg_create_decompress(&job->cinfo);
  job->created = true;
  jpeg_mem_src(&job->cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&job->cinfo, TRUE);
  return 1;
}

int readPixels(Job* job, std::uint8_t* out, std::size_t stride) {
  switch (setjmp(job->err.jump)) {
    case 0: break;
    case 2: return 2;
    default: return 0;
  }
  jpeg_start_decompress(&job->cinfo);
  // Several rows a call: libjpeg then hands out whole row groups of its upsampler at once.
  constexpr unsigned kRowsPerCall = 16;
  JSAMPROW rows[kRowsPerCall];
  while (job->cinfo.output_scanline < job->cinfo.output_height) {
    const unsigned first = job->cinfo.output_scanline;
    const unsigned n = std::min(kRowsPerCall, job->cinfo.output_height - first);
    for (unsigned r = 0; r < n; ++r) rows[r] = out + static_cast<std::size_t>(first + r) * stride;
    jpeg_read_scanlines(&job->cinfo, rows, n);
  }
  jpeg_finish_decompress(&job->cinfo);
  return 1;
}

struct JobCloser {
  void operator()(Job* job) const {
    if (job->created) jpeg_destroy_decompress(&job->cinfo);  // never fails, never jumps
    delete job;
  }
};

[[noreturn]] void fatal(const fs::path& path, const Job& job) {
  throwInputError(path.string(), kStep,
                  std::string("libjpeg cannot decode it: ") + job.err.fatal +
                      "; the file is damaged: copy it from the card again");
}

// A decompression job whose libjpeg messages go to `messages`; a warning stops it when
// `stopOnWarning` (the image is then refused, or settled by the caller).
std::unique_ptr<Job, JobCloser> newJob(DecoderMessages& messages, bool stopOnWarning) {
  std::unique_ptr<Job, JobCloser> job(new Job());
  job->cinfo.err = jpeg_std_error(&job->err.pub);
  job->err.pub.error_exit = onError;
  job->err.pub.emit_message = onMessage;
  job->err.pub.output_message = onOutput;
  job->err.messages = &messages;
  job->err.stopOnWarning = stopOnWarning;
  job->err.fatal[0] = '\0';
  return job;
}

#define SURROGATE_STR2(x) #x
#define SURROGATE_STR(x) SURROGATE_STR2(x)

}  // namespace

DecodedPixels decodeJpeg(const fs::path& path, const std::uint8_t* data, std::size_t size,
                         const DecodeOptions& options, DecoderMessages& messages) {
  std::unique_ptr<Job, JobCloser> job = newJob(messages, !options.acceptDamage);

  int status = startJob(job.get(), data, size);
  if (status == 0) fatal(path, *job);
  if (status == 2) return {};  // refused by the caller (settle)
  jpeg_decompress_struct& c = job->cinfo;
  checkDeclaredSize(path, c.image_width, c.image_height, options);
  // As OpenCV: grey stays grey, CMYK/YCCK comes out as CMYK (converted below), anything else RGB.
  const int components = c.num_components == 1 ? 1 : c.num_components == 4 ? 4 : 3;
  c.out_color_space = components == 1 ? JCS_GRAYSCALE : components == 4 ? JCS_CMYK : JCS_RGB;
  const int w = static_cast<int>(c.image_width), h = static_cast<int>(c.image_height);
  const int channels = components == 1 ? 1 : 3;
  DecodedPixels out;
  if (options.destination) out.placed = options.destination(w, h, channels, 1, Transfer::Srgb);
  if (out.placed) {
    out.placedNarrow = true;
    out.narrow.width = w;
    out.narrow.height = h;
    out.narrow.channels = channels;
  } else {
    out.narrow = Image8(w, h, channels);
  }
  out.narrow.transfer = Transfer::Srgb;
  std::uint8_t* const samples = out.placed ? out.placed : out.narrow.pixels.data();
  // Grey and RGB are decoded straight into the samples; CMYK into a buffer of its own first.
  std::vector<std::uint8_t> cmyk(components == 4 ? std::size_t(w) * h * 4 : 0);
  std::uint8_t* target = components == 4 ? cmyk.data() : samples;
  status = readPixels(job.get(), target, static_cast<std::size_t>(w) * components);
  if (status == 0) fatal(path, *job);
  if (status == 2) return {};
  if (c.output_width != c.image_width || c.output_height != c.image_height ||
      c.output_components != components)
    throw Error(ErrorKind::Internal, path.string(), kStep, "libjpeg gave another layout than asked for");
  if (components == 4) {
    // OpenCV's icvCvt_CMYK2BGR_8u_C4C3R, to the same values.
    std::uint8_t* rgb = samples;
    const std::size_t n = static_cast<std::size_t>(w) * h;
    for (std::size_t i = 0; i < n; ++i) {
      const int cy = cmyk[4 * i], m = cmyk[4 * i + 1], y = cmyk[4 * i + 2], k = cmyk[4 * i + 3];
      rgb[3 * i] = static_cast<std::uint8_t>(k - ((255 - cy) * k >> 8));
      rgb[3 * i + 1] = static_cast<std::uint8_t>(k - ((255 - m) * k >> 8));
      rgb[3 * i + 2] = static_cast<std::uint8_t>(k - ((255 - y) * k >> 8));
    }
  }
  return out;
}

JpegSamples decodeJpegSamples(const std::uint8_t* data, std::size_t size, std::uint64_t maxPixels) {
  JpegSamples out;
  DecoderMessages messages("libjpeg");
  // strict: a stream libjpeg calls damaged is refused
  std::unique_ptr<Job, JobCloser> job = newJob(messages, true);
  auto refused = [&](int status) {
    out.problem = status == 0 ? std::string(job->err.fatal)
                              : (messages.distinct().empty() ? "damaged data" : messages.distinct()[0]);
    return out;
  };
  int status = startJob(job.get(), data, size);
  if (status != 1) return refused(status);
  jpeg_decompress_struct& c = job->cinfo;
  const std::uint64_t pixels = static_cast<std::uint64_t>(c.image_width) * c.image_height;
  if (pixels > std::min(maxPixels, kMaxImagePixels)) {
    out.problem = "it declares " + std::to_string(c.image_width) + " x " + std::to_string(c.image_height) +
                  " pixels, more than expected";
    return out;
  }
  if (!c.arith_code && size < minimumHuffmanJpegBytes(c.image_width, c.image_height)) {
    out.problem = "it declares " + std::to_string(c.image_width) + " x " + std::to_string(c.image_height) +
                  " pixels in " + std::to_string(size) + " bytes, fewer than the " +
                  std::to_string(minimumHuffmanJpegBytes(c.image_width, c.image_height)) +
                  " any JPEG of that size needs";
    return out;
  }
  if (c.num_components != 1 && c.num_components != 3) {
    out.problem = "it has " + std::to_string(c.num_components) + " colour components (1 or 3 expected)";
    return out;
  }
  const int components = c.num_components;
  c.out_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  const std::size_t stride = static_cast<std::size_t>(c.image_width) * components;
  std::vector<std::uint8_t> samples(stride * c.image_height);
  status = readPixels(job.get(), samples.data(), stride);
  if (status != 1) return refused(status);
  if (c.output_width != c.image_width || c.output_height != c.image_height ||
      c.output_components != components) {
    out.problem = "libjpeg gave another layout than asked for";
    return out;
  }
  out.width = static_cast<int>(c.image_width);
  out.height = static_cast<int>(c.image_height);
  out.components = components;
  out.samples = std::move(samples);
  return out;
}

std::string libjpegName() {
#ifdef LIBJPEG_TURBO_VERSION
  return "libjpeg-turbo";
#else
  return "libjpeg";
#endif
}

std::string libjpegVersion() {
#ifdef LIBJPEG_TURBO_VERSION
  return SURROGATE_STR(LIBJPEG_TURBO_VERSION);
#else
  return std::to_string(JPEG_LIB_VERSION);
#endif
}

}  // namespace surrogate::image
