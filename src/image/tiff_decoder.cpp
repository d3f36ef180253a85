// TIFF through libtiff directly. Its messages reach DecoderMessages through per-handle handlers
// (libtiff >= 4.5: TIFFOpenOptionsSetErrorHandlerExtR / ...WarningHandlerExtR, thread-safe) and,
// for the few messages libtiff still gives without a handle, through process-wide handlers that
// write to the calling thread's sink (thread_local) and pass anything else on to the handlers
// they replaced. Never printed.
//
// Pixels: 8- and 16-bit grey (MinIsBlack) and RGB, interleaved, strips or tiles, any
// compression libtiff has: the stored samples, read with TIFFReadEncodedStrip/Tile (as
// OpenCV's imread gave them for files in the usual top-left orientation). Other layouts
// (palette, MinIsWhite, YCbCr, CMYK, 1/2/4-bit, separate planes) through libtiff's RGBA
// interface, as 8-bit RGB (grey for grey photometrics).
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/error.h"
#include "image/export_decoder.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

struct Sink {
  DecoderMessages* messages = nullptr;
  std::string fatal;  // the first error, for a refusal when the file cannot be read at all
  int errors = 0;
};

std::string format(const char* module, const char* fmt, va_list ap) {
  char text[1024];
  std::vsnprintf(text, sizeof text, fmt, ap);
  return module && *module ? std::string(module) + ": " + text : std::string(text);
}

// libtiff tells of tags it has no name for (cameras' and editors' private tags) as warnings;
// they say nothing about the data, which it reads all the same.
bool aboutUnknownTag(const std::string& text) { return text.find("Unknown field with tag") != std::string::npos; }

void record(Sink* sink, const std::string& text, bool error) {
  if (error) {
    if (sink->fatal.empty()) sink->fatal = text;
    ++sink->errors;
    sink->messages->add(text.c_str());
  } else if (!aboutUnknownTag(text)) {
    sink->messages->add(text.c_str());
  }
}

int onError(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  record(static_cast<Sink*>(user), format(module, fmt, ap), true);
  return 1;  // handled: the process-wide handler is not called
}

int onWarning(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  record(static_cast<Sink*>(user), format(module, fmt, ap), false);
  return 1;
}

// Messages libtiff gives without a handle.
thread_local Sink* threadSink = nullptr;
TIFFErrorHandler previousError = nullptr;
TIFFErrorHandler previousWarning = nullptr;

void globalError(const char* module, const char* fmt, va_list ap) {
  if (threadSink) record(threadSink, format(module, fmt, ap), true);
  else if (previousError) previousError(module, fmt, ap);
}

void globalWarning(const char* module, const char* fmt, va_list ap) {
  if (threadSink) record(threadSink, format(module, fmt, ap), false);
  else if (previousWarning) previousWarning(module, fmt, ap);
}

struct ThreadSinkScope {
  explicit ThreadSinkScope(Sink* sink) {
    static std::once_flag once;
    std::call_once(once, [] {
      previousError = TIFFSetErrorHandler(globalError);
      previousWarning = TIFFSetWarningHandler(globalWarning);
    });
    threadSink = sink;
  }
  ~ThreadSinkScope() { threadSink = nullptr; }
};

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};

template <typename T>
T field(TIFF* tif, ttag_t tag, T otherwise) {
  T v = otherwise;
  return TIFFGetFieldDefaulted(tif, tag, &v) == 1 ? v : otherwise;
}

// The block of decoded samples one strip or tile needs, bounded so a crafted table cannot
// make it large: a block is never more than the whole image (or 64 MB).
std::vector<std::uint8_t> blockBuffer(const fs::path& path, std::uint64_t blockBytes, std::uint64_t imageBytes) {
  if (blockBytes == 0 || blockBytes > std::max<std::uint64_t>(imageBytes, 64ull << 20))
    throwInputError(path.string(), kStep,
                    "the TIFF structure is damaged (a strip or tile of " + std::to_string(blockBytes) +
                        " bytes in an image of " + std::to_string(imageBytes) + "); copy it again");
  return std::vector<std::uint8_t>(static_cast<std::size_t>(blockBytes));
}

// Stored samples, 8 or 16 bits, interleaved: `spp` samples per pixel of which the first `keep`
// are kept.
Image readSamples(const fs::path& path, TIFF* tif, int w, int h, int spp, int bits, int keep,
                  const Sink& sink, bool stopOnDamage) {
  const int bytes = bits / 8;
  const std::size_t pixelBytes = static_cast<std::size_t>(spp) * bytes;
  const std::uint64_t imageBytes = std::uint64_t(w) * h * pixelBytes;
  Image im(w, h, keep);
  im.bitsPerSample = bits;
  im.transfer = Transfer::Srgb;
  auto put = [&](const std::uint8_t* row, int x0, int y, int count) {
    std::uint16_t* out = &im.pixels[im.index(x0, y)];
    for (int x = 0; x < count; ++x, row += pixelBytes)
      for (int c = 0; c < keep; ++c) {
        std::uint16_t v;
        if (bytes == 2) std::memcpy(&v, row + 2 * c, 2);
        else v = static_cast<std::uint16_t>(row[c] * 257);
        *out++ = v;
      }
  };
  // A block libtiff cannot decode stops here when damage is refused; with damage accepted its
  // error is recorded and whatever libtiff decoded of it is kept (the rest stays black). libtiff
  // does not always say why (an uncompressed strip shorter than its rows is read raw and just
  // fails), so a failure without a message gets one. Returns true to stop.
  auto failed = [&](tmsize_t n, std::size_t messagesBefore, const char* what, std::uint32_t index,
                    std::uint64_t expected) {
    if (n >= 0 && static_cast<std::uint64_t>(n) >= expected) return false;
    if (sink.messages->count() == messagesBefore) {
      const std::string text = n < 0 ? std::string(what) + " " + std::to_string(index) + " cannot be decoded"
                                     : std::string(what) + " " + std::to_string(index) + " holds " + std::to_string(n) +
                                           " of the " + std::to_string(expected) + " bytes its rows need";
      sink.messages->add(text.c_str());
    }
    return stopOnDamage;
  };
  if (TIFFIsTiled(tif)) {
    const std::uint32_t tw = field<std::uint32_t>(tif, TIFFTAG_TILEWIDTH, 0);
    const std::uint32_t th = field<std::uint32_t>(tif, TIFFTAG_TILELENGTH, 0);
    if (tw == 0 || th == 0) throwInputError(path.string(), kStep, "the TIFF structure is damaged (tiles of no size)");
    std::vector<std::uint8_t> buf = blockBuffer(path, TIFFTileSize64(tif), imageBytes);
    const std::size_t tileRow = static_cast<std::size_t>(tw) * pixelBytes;
    for (std::uint32_t ty = 0; ty < static_cast<std::uint32_t>(h); ty += th)
      for (std::uint32_t tx = 0; tx < static_cast<std::uint32_t>(w); tx += tw) {
        std::fill(buf.begin(), buf.end(), 0);
        const std::size_t before = sink.messages->count();
        const std::uint32_t index = TIFFComputeTile(tif, tx, ty, 0, 0);
        // Size -1: the block as its byte count says. (With an explicit size, libtiff reads an
        // uncompressed block raw, past a byte count that is too short.)
        const tmsize_t n = TIFFReadEncodedTile(tif, index, buf.data(), static_cast<tmsize_t>(-1));
        if (failed(n, before, "tile", index, buf.size()) || (stopOnDamage && sink.messages->count() > 0)) return im;
        const int rows = static_cast<int>(std::min<std::uint32_t>(th, h - ty));
        const int cols = static_cast<int>(std::min<std::uint32_t>(tw, w - tx));
        for (int r = 0; r < rows; ++r) put(buf.data() + r * tileRow, static_cast<int>(tx), static_cast<int>(ty) + r, cols);
      }
    return im;
  }
  std::uint32_t rowsPerStrip = field<std::uint32_t>(tif, TIFFTAG_ROWSPERSTRIP, static_cast<std::uint32_t>(h));
  rowsPerStrip = std::clamp<std::uint32_t>(rowsPerStrip, 1, static_cast<std::uint32_t>(h));
  std::vector<std::uint8_t> buf = blockBuffer(path, TIFFStripSize64(tif), imageBytes);
  const std::size_t rowBytes = static_cast<std::size_t>(w) * pixelBytes;
  const std::uint32_t strips = TIFFNumberOfStrips(tif);
  if (std::uint64_t(strips) * rowsPerStrip < static_cast<std::uint64_t>(h)) {
    const std::string text = "the strip table holds " + std::to_string(strips) + " strips of " +
                             std::to_string(rowsPerStrip) + " rows for an image of " + std::to_string(h) + " rows";
    sink.messages->add(text.c_str());
    if (stopOnDamage) return im;
  }
  for (std::uint32_t s = 0; s < strips && std::uint64_t(s) * rowsPerStrip < static_cast<std::uint64_t>(h); ++s) {
    std::fill(buf.begin(), buf.end(), 0);
    const int y0 = static_cast<int>(s * rowsPerStrip);
    const int rows = static_cast<int>(std::min<std::uint32_t>(rowsPerStrip, h - y0));
    const std::size_t before = sink.messages->count();
    const tmsize_t n = TIFFReadEncodedStrip(tif, s, buf.data(), static_cast<tmsize_t>(-1));
    if (failed(n, before, "strip", s, std::uint64_t(rows) * rowBytes) || (stopOnDamage && sink.messages->count() > 0))
      return im;
    for (int r = 0; r < rows && (r + 1) * rowBytes <= buf.size(); ++r) put(buf.data() + r * rowBytes, 0, y0 + r, w);
  }
  return im;
}

// Any other layout, through libtiff's RGBA interface (8 bits per sample, top-left first).
Image readRgba(const fs::path& path, TIFF* tif, int w, int h, bool grey, bool stopOnDamage) {
  char why[1024] = "";
  if (!TIFFRGBAImageOK(tif, why))
    throwInputError(path.string(), kStep, std::string("unsupported TIFF layout (libtiff: ") + why +
                                              "); export it as 8- or 16-bit RGB or greyscale");
  std::vector<std::uint32_t> raster(static_cast<std::size_t>(w) * h, 0);
  TIFFReadRGBAImageOriented(tif, static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), raster.data(),
                            ORIENTATION_TOPLEFT, stopOnDamage ? 1 : 0);
  Image im(w, h, grey ? 1 : 3);
  im.bitsPerSample = 8;
  im.transfer = Transfer::Srgb;
  for (std::size_t i = 0; i < raster.size(); ++i) {
    const std::uint32_t p = raster[i];
    if (grey) {
      im.pixels[i] = static_cast<std::uint16_t>(TIFFGetR(p) * 257);
    } else {
      im.pixels[3 * i] = static_cast<std::uint16_t>(TIFFGetR(p) * 257);
      im.pixels[3 * i + 1] = static_cast<std::uint16_t>(TIFFGetG(p) * 257);
      im.pixels[3 * i + 2] = static_cast<std::uint16_t>(TIFFGetB(p) * 257);
    }
  }
  return im;
}

// 8-bit images back to their bytes (the readers above widen as they go: the samples are
// multiples of 257, so the division is exact); 16-bit ones as they are.
DecodedPixels atSourceDepth(Image im) {
  DecodedPixels out;
  if (im.bitsPerSample != 8) {
    out.wide = std::move(im);
    return out;
  }
  out.narrow = Image8(im.width, im.height, im.channels);
  out.narrow.transfer = im.transfer;
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    out.narrow.pixels[i] = static_cast<std::uint8_t>(im.pixels[i] / 257);
  return out;
}

}  // namespace

DecodedPixels decodeTiff(const fs::path& path, const DecodeOptions& options, DecoderMessages& messages) {
  Sink sink;
  sink.messages = &messages;
  ThreadSinkScope scope(&sink);
  std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions*)> opts(TIFFOpenOptionsAlloc(), TIFFOpenOptionsFree);
  TIFFOpenOptionsSetErrorHandlerExtR(opts.get(), onError, &sink);
  TIFFOpenOptionsSetWarningHandlerExtR(opts.get(), onWarning, &sink);
  // "m": no memory-mapping, so a file shrinking while it is read gives an error, not a fault.
  std::unique_ptr<TIFF, TiffCloser> tif(TIFFOpenExt(path.c_str(), "rm", opts.get()));
  if (!tif)
    throwInputError(path.string(), kStep,
                    "libtiff cannot read it" + (sink.fatal.empty() ? std::string() : ": " + sink.fatal) +
                        "; the file is damaged: copy it again");
  const bool stop = !options.acceptDamage;
  if (stop && messages.count() > 0) return {};  // a warning reading the directory: refused

  const auto w = field<std::uint32_t>(tif.get(), TIFFTAG_IMAGEWIDTH, 0);
  const auto h = field<std::uint32_t>(tif.get(), TIFFTAG_IMAGELENGTH, 0);
  if (w == 0 || h == 0) throwInputError(path.string(), kStep, "the image declares no size (0 pixels wide or high)");
  checkDeclaredSize(path, w, h, options);
  const int bits = field<std::uint16_t>(tif.get(), TIFFTAG_BITSPERSAMPLE, 1);
  const int spp = field<std::uint16_t>(tif.get(), TIFFTAG_SAMPLESPERPIXEL, 1);
  const int photometric = field<std::uint16_t>(tif.get(), TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  const int planar = field<std::uint16_t>(tif.get(), TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  const int sampleFormat = field<std::uint16_t>(tif.get(), TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  if (sampleFormat != SAMPLEFORMAT_UINT || bits > 16)
    throwInputError(path.string(), kStep,
                    "unsupported pixel type: Surrogate reads 8- and 16-bit integer images only");

  const bool stored = (bits == 8 || bits == 16) && planar == PLANARCONFIG_CONTIG &&
                      ((photometric == PHOTOMETRIC_MINISBLACK && spp >= 1) ||
                       (photometric == PHOTOMETRIC_RGB && spp >= 3));
  const bool grey = photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_MINISWHITE;
  Image im = stored ? readSamples(path, tif.get(), static_cast<int>(w), static_cast<int>(h), spp, bits,
                                  photometric == PHOTOMETRIC_RGB ? 3 : 1, sink, stop)
                    : readRgba(path, tif.get(), static_cast<int>(w), static_cast<int>(h), grey, stop);
  return atSourceDepth(std::move(im));
}

std::string libtiffVersion() {
  // "LIBTIFF, Version 4.5.0\nCopyright ..." -> "4.5.0"
  const std::string text = TIFFGetVersion();
  const auto at = text.find("Version ");
  if (at == std::string::npos) return text.substr(0, text.find('\n'));
  const auto end = text.find_first_of("\n ", at + 8);
  return text.substr(at + 8, end == std::string::npos ? std::string::npos : end - at - 8);
}

}  // namespace surrogate::image
