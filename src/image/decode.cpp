#include "image/decode.h"

#include <libraw/libraw.h>
#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"

namespace surrogate::image {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "image decode";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::vector<unsigned char> readHead(const fs::path& path, std::size_t n) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throwInputError(path.string(), kStep, "cannot be opened for reading");
  std::vector<unsigned char> head(n);
  f.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(n));
  head.resize(static_cast<std::size_t>(f.gcount()));
  return head;
}

bool startsWith(const std::vector<unsigned char>& h, std::initializer_list<unsigned char> sig) {
  if (h.size() < sig.size()) return false;
  return std::equal(sig.begin(), sig.end(), h.begin());
}

// A JPEG ends with the EOI marker (FF D9), possibly followed by padding some cameras add.
// OpenCV decodes a truncated JPEG with only a warning and grey rows, so check it here.
bool jpegHasEnd(const fs::path& path) {
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = f.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  std::vector<unsigned char> buf(static_cast<std::size_t>(tail));
  f.seekg(size - tail);
  f.read(reinterpret_cast<char*>(buf.data()), tail);
  for (std::size_t i = buf.size(); i >= 2; --i)
    if (buf[i - 2] == 0xFF && buf[i - 1] == 0xD9) return true;
  return false;
}

struct LibRawDeleter {
  void operator()(LibRaw* p) const { delete p; }
};

std::string librawProblem(int code) {
  switch (code) {
    case LIBRAW_FILE_UNSUPPORTED:
      return "LibRaw " + librawVersion() + " cannot decode this camera format (for example CR3 "
             "needs LibRaw 0.21 or later); convert it to DNG with Adobe DNG Converter";
    case LIBRAW_IO_ERROR:
    case LIBRAW_DATA_ERROR:
      return "the raw data is damaged or truncated (" + std::string(libraw_strerror(code)) +
             "); copy the file from the card again";
    case LIBRAW_REQUEST_FOR_NONEXISTENT_IMAGE:
      return "the raw file holds no image";
    default:
      if (code == LIBRAW_UNSUFFICIENT_MEMORY || code == LIBRAW_MEMPOOL_OVERFLOW)
        return "not enough memory to decode it";
      return std::string("LibRaw cannot decode it: ") + libraw_strerror(code);
  }
}

std::unique_ptr<LibRaw, LibRawDeleter> openRaw(const fs::path& path) {
  std::unique_ptr<LibRaw, LibRawDeleter> raw(new LibRaw(LIBRAW_OPTIONS_NONE));
  int rc = raw->open_file(path.c_str());
  if (rc != LIBRAW_SUCCESS) throwInputError(path.string(), kStep, librawProblem(rc));
  return raw;
}

int demosaicCode(const std::string& name) {
  static const std::array<const char*, 5> names = {"linear", "VNG", "PPG", "AHD", "DCB"};
  static const std::array<int, 5> codes = {0, 1, 2, 3, 4};
  for (std::size_t i = 0; i < names.size(); ++i)
    if (name == names[i]) return codes[i];
  throw Error(ErrorKind::Usage, "demosaic=" + name, "options",
              "unknown demosaic algorithm; use linear, VNG, PPG, AHD or DCB");
}

Image decodeRaw(const fs::path& path, const RawDecodeSettings& s, DecodeReport* report) {
  auto raw = openRaw(path);
  auto& p = raw->imgdata.params;
  p.user_qual = demosaicCode(s.demosaic);
  p.use_camera_wb = s.whiteBalance == "camera" ? 1 : 0;
  p.use_auto_wb = 0;
  if (s.whiteBalance == "none") {
    for (int i = 0; i < 4; ++i) p.user_mul[i] = 1.0f;
  }
  p.output_color = s.outputColorSpace == "raw" ? 0 : 1;
  p.highlight = s.highlightMode;
  p.output_bps = 16;
  p.gamm[0] = 1.0;
  p.gamm[1] = 1.0;
  p.no_auto_bright = s.noAutoBright ? 1 : 0;
  p.half_size = s.halfSize ? 1 : 0;
  p.use_rawspeed = 0;

  int rc = raw->unpack();
  if (rc != LIBRAW_SUCCESS) throwInputError(path.string(), kStep, librawProblem(rc));
  rc = raw->dcraw_process();
  if (rc != LIBRAW_SUCCESS) throwInputError(path.string(), kStep, librawProblem(rc));
  int err = 0;
  libraw_processed_image_t* processed = raw->dcraw_make_mem_image(&err);
  if (!processed) throwInputError(path.string(), kStep, librawProblem(err));
  std::unique_ptr<libraw_processed_image_t, void (*)(libraw_processed_image_t*)> guard(
      processed, LibRaw::dcraw_clear_mem);
  if (processed->type != LIBRAW_IMAGE_BITMAP || processed->bits != 16 ||
      (processed->colors != 3 && processed->colors != 1)) {
    throwInputError(path.string(), kStep, "LibRaw returned an image layout Surrogate does not handle");
  }
  Image im(processed->width, processed->height, processed->colors);
  im.bitsPerSample = 16;
  im.transfer = Transfer::Linear;
  std::memcpy(im.pixels.data(), processed->data, im.pixels.size() * sizeof(std::uint16_t));
  if (report) {
    report->decoder = "LibRaw " + librawVersion();
    // The levels as read from the file (processing subtracts the black level and resets it):
    // the common black plus the first per-channel offset, and the white level.
    const auto& levels = raw->imgdata.rawdata.color;
    report->blackLevel = static_cast<int>(levels.black + levels.cblack[0]);
    report->whiteLevel = static_cast<int>(levels.maximum);
    report->whiteBalanceMultipliers.clear();
    for (int i = 0; i < 4; ++i) report->whiteBalanceMultipliers.push_back(raw->imgdata.color.pre_mul[i]);
    if (s.whiteBalance == "camera") {
      report->whiteBalanceMultipliers.clear();
      for (int i = 0; i < 4; ++i) report->whiteBalanceMultipliers.push_back(raw->imgdata.color.cam_mul[i]);
    }
  }
  return im;
}

Image decodeWithOpenCv(const fs::path& path, SourceKind kind, DecodeReport* report) {
  if (kind == SourceKind::Jpeg && !jpegHasEnd(path))
    throwInputError(path.string(), kStep,
                    "the JPEG is truncated (it has no end-of-image marker); copy it again");
  cv::Mat m;
  try {
    m = cv::imread(path.string(), cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH | cv::IMREAD_IGNORE_ORIENTATION);
  } catch (const cv::Exception& e) {
    throwInputError(path.string(), kStep, std::string("cannot be decoded: ") + e.what());
  }
  if (m.empty()) throwInputError(path.string(), kStep, "cannot be decoded: the file is damaged or truncated");
  if (m.depth() != CV_8U && m.depth() != CV_16U)
    throwInputError(path.string(), kStep, "has a pixel type Surrogate does not read (only 8- and 16-bit)");
  cv::Mat rgb;
  switch (m.channels()) {
    case 1: rgb = m; break;
    case 3: cv::cvtColor(m, rgb, cv::COLOR_BGR2RGB); break;
    case 4: cv::cvtColor(m, rgb, cv::COLOR_BGRA2RGB); break;
    default: throwInputError(path.string(), kStep, "has an unsupported number of channels");
  }
  Image im(rgb.cols, rgb.rows, rgb.channels());
  im.transfer = Transfer::Srgb;
  im.bitsPerSample = m.depth() == CV_8U ? 8 : 16;
  for (int y = 0; y < rgb.rows; ++y) {
    std::uint16_t* out = &im.pixels[im.index(0, y)];
    const int n = rgb.cols * rgb.channels();
    if (m.depth() == CV_8U) {
      const std::uint8_t* in = rgb.ptr<std::uint8_t>(y);
      for (int i = 0; i < n; ++i) out[i] = static_cast<std::uint16_t>(in[i] * 257);
    } else {
      std::memcpy(out, rgb.ptr<std::uint16_t>(y), n * sizeof(std::uint16_t));
    }
  }
  if (report) *report = DecodeReport{"OpenCV " + opencvVersion(), -1, -1, {}};
  return im;
}

cv::Mat toMat8or16(const Image& im) {
  const bool eight = im.bitsPerSample <= 8;
  cv::Mat m(im.height, im.width, CV_MAKETYPE(eight ? CV_8U : CV_16U, im.channels));
  for (int y = 0; y < im.height; ++y) {
    const std::uint16_t* in = &im.pixels[im.index(0, y)];
    const int n = im.width * im.channels;
    if (eight) {
      std::uint8_t* out = m.ptr<std::uint8_t>(y);
      for (int i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>((in[i] + 128) / 257);
    } else {
      std::memcpy(m.ptr<std::uint16_t>(y), in, n * sizeof(std::uint16_t));
    }
  }
  if (im.channels == 3) cv::cvtColor(m, m, cv::COLOR_RGB2BGR);
  return m;
}

void encodeTo(const Image& im, const fs::path& path, const std::string& ext, const std::vector<int>& params) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(ext, toMat8or16(im), bytes, params))
    throw Error(ErrorKind::Internal, path.string(), "image write", "OpenCV could not encode the image");
  writeFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace

bool isCameraRawExtension(const fs::path& path) {
  static const char* kRaw[] = {".cr2", ".crw", ".cr3", ".nef", ".nrw", ".arw", ".srf", ".sr2",
                               ".raf", ".rw2", ".orf", ".pef", ".dng", ".srw", ".3fr", ".iiq",
                               ".x3f", ".erf", ".kdc", ".dcr", ".mef", ".mos", ".mrw", ".raw", ".rwl"};
  const std::string ext = lower(path.extension().string());
  for (const char* e : kRaw)
    if (ext == e) return true;
  return false;
}

SourceKind classifyImageFile(const fs::path& path) {
  if (!fs::is_regular_file(path)) throwInputError(path.string(), kStep, "is not a regular file");
  if (fs::file_size(path) == 0) throwInputError(path.string(), kStep, "is empty (0 bytes)");
  const auto head = readHead(path, 16);
  if (isCameraRawExtension(path)) return SourceKind::CameraRaw;
  if (startsWith(head, {0xFF, 0xD8, 0xFF})) return SourceKind::Jpeg;
  if (startsWith(head, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return SourceKind::Png;
  if (startsWith(head, {'I', 'I', 42, 0}) || startsWith(head, {'M', 'M', 0, 42})) return SourceKind::Tiff;
  throwInputError(path.string(), kStep,
                  "is not an image Surrogate reads (camera raw, DNG, JPEG, TIFF or PNG)");
}

ImageProbe probeImage(const fs::path& path) {
  ImageProbe probe;
  probe.kind = classifyImageFile(path);
  if (probe.kind == SourceKind::CameraRaw) {
    auto raw = openRaw(path);
    // open_file reads headers only; a truncated raw is caught by checking the data offset
    // and size against the file length where LibRaw knows them, and by unpack() later.
    probe.width = raw->imgdata.sizes.iwidth ? raw->imgdata.sizes.width : raw->imgdata.sizes.raw_width;
    probe.height = raw->imgdata.sizes.height;
    const auto& d = raw->imgdata.idata;
    if (probe.width <= 0 || probe.height <= 0 || d.colors <= 0)
      throwInputError(path.string(), "image probe", "the raw file holds no decodable image");
    const int rc = raw->unpack();
    if (rc != LIBRAW_SUCCESS) throwInputError(path.string(), "image probe", librawProblem(rc));
    if (raw->imgdata.process_warnings & LIBRAW_WARN_BAD_CAMERA_WB) {
      // Harmless for decoding (white balance falls back); recorded by the decode report.
    }
    return probe;
  }
  // OpenCV has no header-only API: decode once. Exports are small next to raw files.
  const Image im = decodeWithOpenCv(path, probe.kind, nullptr);
  probe.width = im.width;
  probe.height = im.height;
  return probe;
}

Image decodeImage(const fs::path& path, const RawDecodeSettings& settings, DecodeReport* report) {
  const SourceKind kind = classifyImageFile(path);
  if (kind == SourceKind::CameraRaw) return decodeRaw(path, settings, report);
  return decodeWithOpenCv(path, kind, report);
}

std::vector<std::pair<std::string, std::string>> RawDecodeSettings::toParameters() const {
  return {{"demosaic", demosaic},
          {"whiteBalance", whiteBalance},
          {"outputColorSpace", outputColorSpace},
          {"highlightMode", std::to_string(highlightMode)},
          {"outputBits", std::to_string(outputBits)},
          {"gamma", "linear"},
          {"noAutoBright", noAutoBright ? "true" : "false"},
          {"halfSize", halfSize ? "true" : "false"}};
}

RawDecodeSettings RawDecodeSettings::fromParameters(
    const std::vector<std::pair<std::string, std::string>>& params) {
  RawDecodeSettings s;
  auto boolean = [](const std::string& name, const std::string& v) {
    if (v == "true") return true;
    if (v == "false") return false;
    throw Error(ErrorKind::Usage, name + "=" + v, "options", "needs true or false");
  };
  for (const auto& [name, value] : params) {
    if (name == "demosaic") {
      demosaicCode(value);
      s.demosaic = value;
    } else if (name == "whiteBalance") {
      if (value != "camera" && value != "daylight" && value != "none")
        throw Error(ErrorKind::Usage, name + "=" + value, "options", "use camera, daylight or none");
      s.whiteBalance = value;
    } else if (name == "outputColorSpace") {
      if (value != "srgb" && value != "raw")
        throw Error(ErrorKind::Usage, name + "=" + value, "options", "use srgb or raw");
      s.outputColorSpace = value;
    } else if (name == "highlightMode") {
      s.highlightMode = std::stoi(value);
      if (s.highlightMode < 0 || s.highlightMode > 9)
        throw Error(ErrorKind::Usage, name + "=" + value, "options", "use 0 (clip) to 9");
    } else if (name == "outputBits") {
      if (value != "16") throw Error(ErrorKind::Usage, name + "=" + value, "options", "only 16 is supported");
    } else if (name == "gamma") {
      if (value != "linear") throw Error(ErrorKind::Usage, name + "=" + value, "options", "only linear is supported");
    } else if (name == "noAutoBright") {
      s.noAutoBright = boolean(name, value);
    } else if (name == "halfSize") {
      s.halfSize = boolean(name, value);
    } else {
      throw Error(ErrorKind::Usage, name, "options", "is not a raw decoding setting");
    }
  }
  return s;
}

void writePng(const Image& image, const fs::path& path) {
  encodeTo(image, path, ".png", {cv::IMWRITE_PNG_COMPRESSION, 6});
}

void writeJpeg(const Image& image, const fs::path& path, int quality) {
  Image eight = image;
  eight.bitsPerSample = 8;
  encodeTo(eight, path, ".jpg", {cv::IMWRITE_JPEG_QUALITY, quality});
}

Image srgbEncode(const Image& linear) {
  static const std::vector<std::uint16_t> table = [] {
    std::vector<std::uint16_t> t(65536);
    for (int i = 0; i < 65536; ++i) {
      const double v = i / 65535.0;
      const double e = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
      t[i] = static_cast<std::uint16_t>(std::lround(std::clamp(e, 0.0, 1.0) * 65535.0));
    }
    return t;
  }();
  Image out = linear;
  out.transfer = Transfer::Srgb;
  for (std::uint16_t& v : out.pixels) v = table[v];
  return out;
}

std::string librawVersion() { return LibRaw::version(); }
std::string opencvVersion() { return CV_VERSION; }

}  // namespace surrogate::image
