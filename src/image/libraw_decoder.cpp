#include "image/libraw_decoder.h"

#include <libraw/libraw.h>
#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <string>

#include "core/error.h"
#include "image/decoder_messages.h"
#include "image/raw_signature.h"
#include "image/tiff_structure.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

// What LibRaw reported through its data-error callback while reading pixel data. The end of
// the file (offset -1) ends LibRaw's decode with an error too; corrupt data (a value out of
// range, a broken code) it reports once and decodes on, which is damage to refuse or accept.
struct DataErrors {
  bool endOfFile = false;
  DecoderMessages corrupt{"LibRaw"};
};

void collectDataError(void* data, const char* /*file*/, const int offset) {
  auto* errors = static_cast<DataErrors*>(data);
  if (offset < 0) {
    errors->endOfFile = true;
    return;
  }
  char text[128];
  std::snprintf(text, sizeof text, "corrupt raw data (first found near byte %d of the file)", offset);
  errors->corrupt.add(text);
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// LibRaw's code as a sentence the photographer can act on.
std::string describe(int code, const fs::path& path) {
  const std::string libraw = "LibRaw " + std::string(LibRaw::version());
  switch (code) {
    case LIBRAW_FILE_UNSUPPORTED: {
      const RawContainer container = rawContainerOf(path);
      if (container == RawContainer::Cr3 || lowerExtension(path) == ".cr3")
        return libraw + " cannot decode this camera format (CR3 needs LibRaw >= 0.21); convert "
                        "it to DNG with Adobe DNG Converter, or use the camera's JPEG/TIFF exports";
      if (container != RawContainer::None)
        return libraw + " cannot read it: the file is truncated or damaged, or its camera is "
                        "newer than this LibRaw; copy it from the card again, or convert it to "
                        "DNG with Adobe DNG Converter";
      return libraw + " cannot decode this camera format; convert it to DNG with Adobe DNG "
                      "Converter, or use the camera's JPEG/TIFF exports";
    }
    case LIBRAW_IO_ERROR:
    case LIBRAW_DATA_ERROR:
      return "the file is truncated or its raw data is damaged (" + libraw + ": " +
             libraw_strerror(code) + "); copy it from the card again";
    case LIBRAW_REQUEST_FOR_NONEXISTENT_IMAGE:
      return "the raw file holds no image";
    case LIBRAW_TOO_BIG:
      return "the image is larger than " + libraw + " accepts";
    case LIBRAW_UNSUFFICIENT_MEMORY:
    case LIBRAW_MEMPOOL_OVERFLOW:
      return "there is not enough memory to decode it (" + std::string(libraw_strerror(code)) + ")";
    default:
      return libraw + " cannot decode it: " + libraw_strerror(code);
  }
}

// A LibRaw error code, or the end of the file reached while reading pixel data: refused.
// (Corrupt data LibRaw decoded on is settled after decoding: refused, or accepted and reported.)
void check(int code, const fs::path& path, const DataErrors& errors) {
  if (errors.endOfFile)
    throwInputError(path.string(), kStep,
                    "the file is truncated: LibRaw reached its end while reading the raw data; "
                    "copy it from the card again");
  if (code != LIBRAW_SUCCESS) throwInputError(path.string(), kStep, describe(code, path));
}

// LibRaw 0.20 decodes a DNG whose tiles lie past the end of the file (a pruned or truncated
// copy) to a black image without any error; the TIFF tables tell.
void refuseTruncatedTiff(const fs::path& path) {
  if (rawContainerOf(path) == RawContainer::Tiff && readTiffStructure(path).truncated)
    throwInputError(path.string(), kStep,
                    "the file is truncated: its raw image data extends past the end of the file; "
                    "copy it from the card again");
}

struct Decoder {
  std::unique_ptr<LibRaw> raw = std::make_unique<LibRaw>(LIBRAW_OPTIONS_NONE);
  DataErrors errors;

  explicit Decoder(const fs::path& path) {
    refuseTruncatedTiff(path);
    raw->set_dataerror_handler(collectDataError, &errors);
    check(raw->open_file(path.c_str()), path, errors);
  }
};

int demosaicCode(const std::string& name) {
  static const char* kNames[] = {"linear", "VNG", "PPG", "AHD", "DCB"};  // LibRaw user_qual 0..4
  for (int i = 0; i < 5; ++i)
    if (name == kNames[i]) return i;
  throw Error(ErrorKind::Usage, "demosaic=" + name, "raw decode settings",
              "unknown demosaic algorithm; use linear, VNG, PPG, AHD or DCB");
}

// Every field of libraw_output_params_t that shapes pixels, set explicitly rather than left
// at LibRaw's defaults, so a future LibRaw changing a default cannot change the result silently.
void apply(const RawDecodeSettings& s, libraw_output_params_t& p) {
  p.user_qual = demosaicCode(s.demosaic);
  p.dcb_iterations = s.dcbIterations;
  p.dcb_enhance_fl = s.dcbEnhance ? 1 : 0;
  p.med_passes = s.medianPasses;
  p.four_color_rgb = s.fourColorRgb ? 1 : 0;
  p.green_matching = s.greenMatching ? 1 : 0;
  p.threshold = static_cast<float>(s.noiseThreshold);

  p.use_auto_wb = 0;
  p.use_camera_wb = s.whiteBalance == "camera" ? 1 : 0;
  for (float& m : p.user_mul) m = s.whiteBalance == "none" ? 1.0f : 0.0f;  // 0: not set
  p.output_color = s.outputColorSpace == "raw" ? 0 : 1;
  p.use_camera_matrix = s.colorMatrix == "embedded" ? 3 : s.colorMatrix == "builtin" ? 0 : 1;
  p.highlight = s.highlightMode;

  p.user_black = s.blackLevel;
  p.user_sat = s.whiteLevel;
  p.adjust_maximum_thr = static_cast<float>(s.adjustMaximumThreshold);
  p.no_auto_bright = s.noAutoBright ? 1 : 0;
  p.bright = 1.0f;

  p.user_flip = s.orientation == "camera" ? -1 : 0;
  p.half_size = s.halfSize ? 1 : 0;
  p.use_fuji_rotate = 1;
  p.shot_select = 0;
  p.auto_bright_thr = 0.01f;
  p.dark_frame = nullptr;
  p.bad_pixels = nullptr;

  p.output_bps = 16;
  p.gamm[0] = 1.0;  // linear: values proportional to light
  p.gamm[1] = 1.0;
  for (double& a : p.aber) a = 1.0;  // no chromatic-aberration scaling
  p.exp_correc = 0;
  p.fbdd_noiserd = 0;
  p.no_auto_scale = 0;
  p.no_interpolation = 0;
  p.use_rawspeed = 0;
  p.use_dngsdk = 0;
}

void fillReport(const LibRaw& raw, const RawDecodeSettings& s, DecodeReport& report) {
  report = DecodeReport{};
  report.decoder = "LibRaw " + std::string(LibRaw::version());
  // rawdata.color keeps the levels as read (processing subtracts the black and resets it):
  // the common black plus the first per-channel offset, and the white level.
  const auto& asRead = raw.imgdata.rawdata.color;
  report.blackLevel = s.blackLevel >= 0 ? s.blackLevel : static_cast<int>(asRead.black + asRead.cblack[0]);
  report.whiteLevel = s.whiteLevel >= 0 ? s.whiteLevel : static_cast<int>(asRead.maximum);
  // Per channel: the common level, the per-channel offsets, and a black pattern of at most
  // 2x2 cells (DNG BlackLevelRepeatDim) folded onto the Bayer colours as LibRaw does.
  unsigned channel[4];
  for (int c = 0; c < 4; ++c) channel[c] = asRead.black + asRead.cblack[c];
  const unsigned ph = asRead.cblack[4], pw = asRead.cblack[5];
  const unsigned filters = raw.imgdata.idata.filters;
  if (ph == 1 && pw == 1) {
    for (unsigned& c : channel) c += asRead.cblack[6];
  } else if (ph >= 1 && ph <= 2 && pw >= 1 && pw <= 2 && filters >= 1000) {
    bool done[4] = {false, false, false, false};
    for (unsigned r = 0; r < 2; ++r)
      for (unsigned c = 0; c < 2; ++c) {
        const unsigned colour = filters >> ((((r << 1) & 14) | (c & 1)) << 1) & 3;  // LibRaw FC()
        if (done[colour]) continue;
        done[colour] = true;
        channel[colour] += asRead.cblack[6 + (r % ph) * pw + (c % pw)];
      }
  }
  for (int c = 0; c < 4; ++c)
    report.channelBlackLevels.push_back(s.blackLevel >= 0 ? s.blackLevel : static_cast<int>(channel[c]));
  // After processing, pre_mul holds the multipliers applied, normalised to the smallest.
  const float* applied = raw.imgdata.color.pre_mul;
  const float smallest = *std::min_element(applied, applied + 3);
  for (int c = 0; c < 4; ++c)
    report.whiteBalanceMultipliers.push_back(smallest > 0 ? applied[c] / smallest : applied[c]);
  if (raw.imgdata.process_warnings & LIBRAW_WARN_BAD_CAMERA_WB)
    report.warnings.push_back("the file has no usable as-shot white balance; LibRaw used the "
                              "camera's daylight multipliers");
  if (raw.imgdata.process_warnings & LIBRAW_WARN_FALLBACK_TO_AHD)
    report.warnings.push_back("LibRaw does not offer the requested demosaic for this sensor; AHD was used");
}

}  // namespace

DecodedPixels decodeCameraRaw(const fs::path& path, const RawDecodeSettings& settings, DecodeReport* report,
                              const DecodeOptions& options) {
  Decoder d(path);
  // Before LibRaw allocates anything for pixels: the visible size against the caller's limit,
  // the stored mosaic (with its margins) against Surrogate's.
  checkDeclaredSize(path, d.raw->imgdata.sizes.width, d.raw->imgdata.sizes.height, options);
  checkDeclaredSize(path, d.raw->imgdata.sizes.raw_width, d.raw->imgdata.sizes.raw_height, DecodeOptions{});
  apply(settings, d.raw->imgdata.params);
  check(d.raw->unpack(), path, d.errors);
  if (!options.acceptDamage) settle(d.errors.corrupt, path, options, report);  // refused: no need to go on
  // LibRaw's demosaic runs OpenMP threads of its own, as many as the cores, in every thread
  // that decodes: with the pipeline already decoding --threads images at a time
  // (stages/decode_images.cpp), they oversubscribe the cores, and `--threads 1` used 1.3 of them
  // (a batch of 2 jobs then reached 1.53x the throughput of 1). One OpenMP thread per decoding
  // thread: its ICV is per thread, so this leaves any other caller's setting alone.
  omp_set_num_threads(1);
  check(d.raw->dcraw_process(), path, d.errors);
  // What dcraw_make_mem_image would allocate and fill (the layout, then copy_mem_image), but
  // into the caller's buffer when it gives one: a raw image is 36 MB at 6 Mpx, and each copy
  // of it costs fresh memory.
  int width = 0, height = 0, colors = 0, bits = 0;
  d.raw->get_mem_image_format(&width, &height, &colors, &bits);
  if (bits != 16 || (colors != 3 && colors != 1) || width <= 0 || height <= 0)
    throwInputError(path.string(), kStep,
                    "LibRaw returned an image layout Surrogate does not handle (" + std::to_string(colors) +
                        " colours, " + std::to_string(bits) + " bits)");
  DecodedPixels out;
  if (options.destination) out.placed = options.destination(width, height, colors, 2, Transfer::Linear);
  if (out.placed) {  // `wide` only describes them
    out.wide.width = width;
    out.wide.height = height;
    out.wide.channels = colors;
  } else {
    out.wide = Image(width, height, colors);
  }
  out.wide.bitsPerSample = 16;
  out.wide.transfer = Transfer::Linear;
  void* samples = out.placed ? static_cast<void*>(out.placed) : static_cast<void*>(out.wide.pixels.data());
  check(d.raw->copy_mem_image(samples, width * colors * 2, 0), path, d.errors);
  if (report) fillReport(*d.raw, settings, *report);
  settle(d.errors.corrupt, path, options, report);
  return out;
}

ImageProbe probeCameraRaw(const fs::path& path) {
  Decoder d(path);
  const auto& sizes = d.raw->imgdata.sizes;
  if (sizes.width == 0 || sizes.height == 0 || d.raw->imgdata.idata.colors <= 0)
    throwInputError(path.string(), "image probe", "the raw file holds no decodable image");
  ImageProbe probe;
  probe.kind = SourceKind::CameraRaw;
  probe.width = sizes.width;
  probe.height = sizes.height;
  return probe;
}

std::string librawVersion() { return LibRaw::version(); }

}  // namespace surrogate::image
