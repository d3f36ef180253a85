#include "formats/ptm.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/resident.h"
#include "formats/ptm_jpeg.h"
#include "formats/text_parse.h"

namespace surrogate::formats {

namespace {
const char* const kReadStep = "read PTM";
const char* const kWriteStep = "write PTM";

std::size_t bytesPerTexel(PtmFile::Format f) { return f == PtmFile::Format::Lrgb ? 9 : 18; }

int parseSide(HeaderCursor& cur, std::string_view token, const char* what) {
  long long v = 0;
  if (!parseInt(token, &v)) {
    cur.fail(std::string("the ") + what + " \"" + std::string(token.substr(0, 40)) +
             "\" on line " + std::to_string(cur.lineNumber()) + " is not an integer");
  }
  if (v < 1 || v > kMaxSide) {
    cur.fail(std::string("the ") + what + " " + std::to_string(v) +
             " is outside 1.." + std::to_string(kMaxSide) + "; the header is corrupt");
  }
  return static_cast<int>(v);
}
}  // namespace

const char* formatName(PtmFile::Format format) {
  return format == PtmFile::Format::Lrgb ? "PTM_FORMAT_LRGB" : "PTM_FORMAT_RGB";
}

bool PtmFile::operator==(const PtmFile& o) const {
  return format == o.format && width == o.width && height == o.height && scale == o.scale &&
         bias == o.bias && coefficients == o.coefficients && rgb == o.rgb;
}

PtmHeader parsePtmHeader(const std::uint8_t* data, std::size_t size, const std::string& name) {
  HeaderCursor cur(data, size, name, kReadStep);
  if (size < 4 || std::memcmp(data, "PTM_", 4) != 0) {
    cur.fail("this is not a PTM file: it does not start with \"PTM_\"");
  }
  PtmHeader h;
  h.report.version = std::string(trim(cur.line("version", 64)));
  if (h.report.version != "PTM_1.2" && h.report.version != "PTM_1.1") {
    cur.fail("unsupported PTM version \"" + h.report.version.substr(0, 40) +
             "\"; PTM_1.1 and PTM_1.2 can be read");
  }
  const std::string format(trim(cur.line("format", 256)));
  const bool v12 = h.report.version == "PTM_1.2";
  bool jpeg = false;
  if (format == "PTM_FORMAT_LRGB") {
    h.format = PtmFile::Format::Lrgb;
  } else if (format == "PTM_FORMAT_RGB" && v12) {
    h.format = PtmFile::Format::Rgb;
  } else if ((format == "PTM_FORMAT_JPEG_LRGB" || format == "PTM_FORMAT_JPEG_RGB") && v12) {
    h.format = format == "PTM_FORMAT_JPEG_LRGB" ? PtmFile::Format::Lrgb : PtmFile::Format::Rgb;
    jpeg = true;
  } else if (format.rfind("PTM_FORMAT_", 0) == 0) {
    cur.fail("the PTM format " + format.substr(0, 40) + " (" + h.report.version +
             ") is not supported; PTM_FORMAT_LRGB and PTM_FORMAT_RGB files, raw or JPEG-"
             "compressed (PTM_FORMAT_JPEG_LRGB, PTM_FORMAT_JPEG_RGB), can be read (re-export "
             "the PTM as one of these)");
  } else {
    cur.fail("line 2 should name the PTM format (e.g. PTM_FORMAT_LRGB), found \"" +
             format.substr(0, 40) + "\"");
  }
  h.report.formatLine = format;

  const auto first = tokens(cur.line("width"));
  if (first.size() == 1) {
    h.width = parseSide(cur, first[0], "width");
    const auto second = tokens(cur.line("height"));
    if (second.size() != 1) cur.fail("line 4 should hold the image height alone");
    h.height = parseSide(cur, second[0], "height");
  } else if (first.size() == 2) {
    h.width = parseSide(cur, first[0], "width");
    h.height = parseSide(cur, first[1], "height");
    h.report.sizeOnOneLine = true;
  } else {
    cur.fail("line 3 should hold the image width (and optionally the height)");
  }
  const std::uint64_t texels = static_cast<std::uint64_t>(h.width) * h.height;
  if (texels > kMaxTexels) {
    cur.fail("the image size " + std::to_string(h.width) + " x " + std::to_string(h.height) +
             " is larger than this program accepts (2^31 texels); the header is corrupt");
  }

  const auto scales = tokens(cur.line("scale values"));
  if (scales.size() != 6) {
    cur.fail("line " + std::to_string(cur.lineNumber()) + " should hold 6 scale values, found " +
             std::to_string(scales.size()));
  }
  for (int k = 0; k < 6; ++k) {
    if (!parseDouble(scales[k], &h.scale[k])) {
      cur.fail("scale value " + std::to_string(k + 1) + " \"" +
               std::string(scales[k].substr(0, 40)) + "\" is not a finite number");
    }
  }
  const auto biases = tokens(cur.line("bias values"));
  if (biases.size() != 6) {
    cur.fail("line " + std::to_string(cur.lineNumber()) + " should hold 6 bias values, found " +
             std::to_string(biases.size()));
  }
  for (int k = 0; k < 6; ++k) {
    long long b = -1;
    if (!parseInt(biases[k], &b) || b < 0 || b > 255) {
      cur.fail("bias value " + std::to_string(k + 1) + " \"" +
               std::string(biases[k].substr(0, 40)) + "\" is not an integer in 0..255");
    }
    h.bias[k] = static_cast<int>(b);
  }
  if (jpeg) {
    parseJpegPlaneTable(cur, h.format == PtmFile::Format::Lrgb ? 9 : 18, &h);
  } else {
    h.payloadBytes = static_cast<std::size_t>(texels) * bytesPerTexel(h.format);
  }
  h.payloadOffset = cur.offset();
  return h;
}

std::uint64_t ptmReadBytes(const PtmHeader& h) {
  const std::uint64_t texels = static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height);
  const std::uint64_t model = texels * bytesPerTexel(h.format);
  // A JPEG plane is decoded into a buffer of its own, and libjpeg holds a progressive plane's
  // DCT coefficients (two bytes a texel) until its last scan.
  return h.jpegPlanes.empty() ? model : model + 3 * texels;
}

PtmFile parsePtm(const std::uint8_t* data, std::size_t size, const std::string& name,
                 PtmReadReport* report, const ModelBudget& budget) {
  const PtmHeader h = parsePtmHeader(data, size, name);
  const std::size_t available = size - h.payloadOffset;
  if (available < h.payloadBytes) {
    throw Error(ErrorKind::Input, name, kReadStep,
                "the file is truncated: the header announces " + std::to_string(h.width) + " x " +
                    std::to_string(h.height) + " texels (" + std::to_string(h.payloadBytes) +
                    " bytes of data) but only " + std::to_string(available) + " bytes follow");
  }
  const std::uint64_t declaredTexels = static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height);
  const std::string declared =
      std::to_string(h.width) + "x" + std::to_string(h.height) + " texels (" + h.report.formatLine +
      (h.jpegPlanes.empty() ? "" : ", " + std::to_string(h.jpegPlanes.size()) + " JPEG planes") + ")";
  requireWithinMemory(name, kReadStep, declared, size + ptmReadBytes(h) + declaredTexels * (budget.besidePerTexel + budget.modelCopies * bytesPerTexel(h.format)),
                      budget.bytes, budget.memoryOption);
  if (report) {
    *report = h.report;
    report->trailingBytes = available - h.payloadBytes;
  }
  if (!h.jpegPlanes.empty()) return decodeJpegPtm(h, data + h.payloadOffset, available, name);
  PtmFile ptm;
  ptm.format = h.format;
  ptm.width = h.width;
  ptm.height = h.height;
  ptm.scale = h.scale;
  ptm.bias = h.bias;
  const std::size_t w = static_cast<std::size_t>(h.width);
  const std::size_t texels = w * static_cast<std::size_t>(h.height);
  const std::uint8_t* payload = data + h.payloadOffset;
  // Stored row r is image row height-1-r (the file is bottom-up).
  auto fileRow = [&](std::size_t y) { return static_cast<std::size_t>(h.height) - 1 - y; };
  if (h.format == PtmFile::Format::Lrgb) {
    resizeResident(ptm.coefficients, texels * 6);
    resizeResident(ptm.rgb, texels * 3);
    const bool interleaved = h.report.version == "PTM_1.1";  // 9 bytes per texel
    for (std::size_t y = 0; y < static_cast<std::size_t>(h.height); ++y) {
      const std::size_t src = fileRow(y) * w;
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t t = y * w + x;
        if (interleaved) {
          std::memcpy(&ptm.coefficients[t * 6], payload + (src + x) * 9, 6);
          std::memcpy(&ptm.rgb[t * 3], payload + (src + x) * 9 + 6, 3);
        } else {
          std::memcpy(&ptm.coefficients[t * 6], payload + (src + x) * 6, 6);
          std::memcpy(&ptm.rgb[t * 3], payload + texels * 6 + (src + x) * 3, 3);
        }
      }
    }
  } else {
    resizeResident(ptm.coefficients, texels * 18);
    for (std::size_t c = 0; c < 3; ++c) {
      for (std::size_t y = 0; y < static_cast<std::size_t>(h.height); ++y) {
        std::memcpy(&ptm.coefficients[(c * texels + y * w) * 6],
                    payload + (c * texels + fileRow(y) * w) * 6, w * 6);
      }
    }
  }
  return ptm;
}

PtmFile readPtm(const std::filesystem::path& path, PtmReadReport* report, const ModelBudget& budget) {
  const std::string bytes = readFile(path, kReadStep);
  return parsePtm(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                  path.string(), report, budget);
}

void validatePtm(const PtmFile& ptm, const std::string& name) {
  auto fail = [&](const std::string& message) {
    throw Error(ErrorKind::Input, name, kWriteStep, "cannot write this PTM: " + message);
  };
  if (ptm.width < 1 || ptm.height < 1 || ptm.width > kMaxSide || ptm.height > kMaxSide ||
      static_cast<std::uint64_t>(ptm.width) * ptm.height > kMaxTexels) {
    fail("the size " + std::to_string(ptm.width) + " x " + std::to_string(ptm.height) +
         " is out of range");
  }
  const bool lrgb = ptm.format == PtmFile::Format::Lrgb;
  if (ptm.coefficients.size() != ptm.texels() * (lrgb ? 6 : 18) ||
      ptm.rgb.size() != (lrgb ? ptm.texels() * 3 : 0)) {
    fail("the coefficient or colour data does not match the image size");
  }
  for (int k = 0; k < 6; ++k) {
    if (ptm.bias[k] < 0 || ptm.bias[k] > 255) fail("a bias is outside 0..255");
    const double s = std::fabs(ptm.scale[k]);
    if (!std::isfinite(s) || (s != 0 && (s < 1e-12 || s > 1e12))) {
      fail("scale " + std::to_string(k + 1) + " is not a usable number");
    }
  }
}

void writePtm(std::ostream& out, const PtmFile& ptm, const std::string& name) {
  validatePtm(ptm, name);
  std::string header = "PTM_1.2\n";
  header += formatName(ptm.format);
  header += "\n" + std::to_string(ptm.width) + "\n" + std::to_string(ptm.height) + "\n";
  for (int k = 0; k < 6; ++k) header += (k ? " " : "") + formatFixed(ptm.scale[k]);
  header += "\n";
  for (int k = 0; k < 6; ++k) header += (k ? " " : "") + std::to_string(ptm.bias[k]);
  header += "\n";
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  const std::size_t w = static_cast<std::size_t>(ptm.width);
  const std::size_t texels = ptm.texels();
  auto block = [&](const std::vector<std::uint8_t>& data, std::size_t offset,
                   std::size_t bytesPerTexel) {
    for (int y = ptm.height - 1; y >= 0; --y) {  // bottom row first
      out.write(reinterpret_cast<const char*>(data.data() + offset +
                                              static_cast<std::size_t>(y) * w * bytesPerTexel),
                static_cast<std::streamsize>(w * bytesPerTexel));
    }
  };
  if (ptm.format == PtmFile::Format::Lrgb) {
    block(ptm.coefficients, 0, 6);
    block(ptm.rgb, 0, 3);
  } else {
    for (std::size_t c = 0; c < 3; ++c) block(ptm.coefficients, c * texels * 6, 6);
  }
}

void writePtm(const std::filesystem::path& path, const PtmFile& ptm) {
  validatePtm(ptm, path.string());
  AtomicFile file(path);
  writeTemporary(file, kWriteStep, [&](std::ostream& out) { writePtm(out, ptm, path.string()); });
  file.commit();
}

std::string serializePtm(const PtmFile& ptm) {
  std::ostringstream out;
  writePtm(out, ptm, "(memory)");
  return out.str();
}

}  // namespace surrogate::formats
