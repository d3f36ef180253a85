#include "formats/rti_hsh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/resident.h"
#include "formats/ptm.h"  // kMaxSide, kMaxTexels
#include "formats/text_parse.h"

namespace surrogate::formats {

namespace {
const char* const kReadStep = "read RTI";
const char* const kWriteStep = "write RTI";
constexpr long long kBasisType = 2;    // RGB: each channel its own coefficients
constexpr long long kElementSize = 1;  // bytes per coefficient

// IEEE-754 float32, little-endian, independent of the host's byte order.
float readFloatLE(const std::uint8_t* p) {
  const std::uint32_t bits = static_cast<std::uint32_t>(p[0]) |
                             (static_cast<std::uint32_t>(p[1]) << 8) |
                             (static_cast<std::uint32_t>(p[2]) << 16) |
                             (static_cast<std::uint32_t>(p[3]) << 24);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

void appendFloatLE(std::string& out, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  for (int i = 0; i < 4; ++i) out += static_cast<char>((bits >> (8 * i)) & 0xFF);
}

long long parseField(HeaderCursor& cur, std::string_view token, const char* what) {
  long long v = 0;
  if (!parseInt(token, &v)) {
    cur.fail(std::string("the ") + what + " \"" + std::string(token.substr(0, 40)) +
             "\" on line " + std::to_string(cur.lineNumber()) + " is not an integer");
  }
  return v;
}
}  // namespace

bool HshFile::operator==(const HshFile& o) const {
  // Compare floats by bits so that a round trip is checked exactly (and NaN == NaN).
  auto sameBits = [](const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
  };
  return width == o.width && height == o.height && terms == o.terms &&
         sameBits(scale, o.scale) && sameBits(bias, o.bias) && coefficients == o.coefficients;
}

RtiHeader parseRtiHeader(const std::uint8_t* data, std::size_t size, const std::string& name) {
  HeaderCursor cur(data, size, name, kReadStep);
  RtiHeader h;
  if (size == 0 || (data[0] != '#' && !(data[0] >= '0' && data[0] <= '9'))) {
    cur.fail("this is not an RTI file: it should start with a \"#HSH1.2\" comment line");
  }
  std::string_view line;
  for (;;) {
    line = cur.line("RTI type");
    if (line.empty() || line[0] != '#') break;
    if (h.report.comments.size() >= 1000) cur.fail("too many comment lines; not an RTI file");
    h.report.comments.emplace_back(line.substr(1));
  }
  const auto type = tokens(line);
  if (type.size() != 1) cur.fail("the line after the comments should hold the RTI type alone");
  const long long rtiType = parseField(cur, type[0], "RTI type");
  if (rtiType != 3) {
    cur.fail("the RTI type is " + std::to_string(rtiType) +
             "; only type 3 (hemispherical harmonics, HSH) can be read, as in RTIViewer");
  }
  const auto dims = tokens(cur.line("size"));
  if (dims.size() != 3) cur.fail("the size line should be \"<width> <height> <channels>\"");
  const long long w = parseField(cur, dims[0], "width");
  const long long ht = parseField(cur, dims[1], "height");
  const long long channels = parseField(cur, dims[2], "channel count");
  if (w < 1 || ht < 1 || w > kMaxSide || ht > kMaxSide ||
      static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(ht) > kMaxTexels) {
    cur.fail("the image size " + std::to_string(w) + " x " + std::to_string(ht) +
             " is out of range; the header is corrupt");
  }
  if (channels != 3) {
    cur.fail("the file has " + std::to_string(channels) + " colour channels; HSH files have 3");
  }
  const auto basis = tokens(cur.line("basis"));
  if (basis.size() != 3) cur.fail("the basis line should be \"<terms> <basis type> <element size>\"");
  long long terms = parseField(cur, basis[0], "number of terms");
  // Every HSH writer (RTIBuilder's hshfitter, relight, RTIViewer's tools) writes "2 1": basis
  // type 2, each colour channel with its own coefficients, and elements of 1 byte. This reader
  // reads that layout; any other declaration is a layout it would misread.
  const long long basisType = parseField(cur, basis[1], "basis type");
  const long long elementSize = parseField(cur, basis[2], "element size");
  if (basisType != kBasisType) {
    cur.fail("the basis type is " + std::to_string(basisType) + "; an HSH file stores each colour "
             "channel's coefficients separately, basis type 2, the only layout RTI viewers read");
  }
  if (elementSize != kElementSize) {
    cur.fail("the element size is " + std::to_string(elementSize) + " bytes; HSH coefficients are "
             "stored as single bytes (element size 1)");
  }
  if (terms == 1) terms = 4;  // RTIViewer's order codes
  if (terms == 2) terms = 9;
  if (terms != 4 && terms != 9 && terms != 16) {
    cur.fail("the file has " + std::to_string(terms) + " terms; HSH files have 4, 9 or 16");
  }
  h.width = static_cast<int>(w);
  h.height = static_cast<int>(ht);
  h.terms = static_cast<int>(terms);
  h.tablesOffset = cur.offset();
  if (size - h.tablesOffset >= 8 * static_cast<std::size_t>(terms)) {
    const std::uint8_t* p = data + h.tablesOffset;
    for (int k = 0; k < terms; ++k) h.scale.push_back(readFloatLE(p + 4 * k));
    for (int k = 0; k < terms; ++k) h.bias.push_back(readFloatLE(p + 4 * (terms + k)));
  }
  h.payloadBytes = 8 * static_cast<std::size_t>(terms) +
                   static_cast<std::size_t>(w) * static_cast<std::size_t>(ht) * 3 *
                       static_cast<std::size_t>(terms);
  return h;
}

HshFile parseRti(const std::uint8_t* data, std::size_t size, const std::string& name,
                 RtiReadReport* report, const ModelBudget& budget) {
  const RtiHeader h = parseRtiHeader(data, size, name);
  const std::size_t available = size - h.tablesOffset;
  if (available < h.payloadBytes) {
    throw Error(ErrorKind::Input, name, kReadStep,
                "the file is truncated: the header announces " + std::to_string(h.width) + " x " +
                    std::to_string(h.height) + " texels with " + std::to_string(h.terms) +
                    " terms (" + std::to_string(h.payloadBytes) + " bytes of data) but only " +
                    std::to_string(available) + " bytes follow");
  }
  // The payload is in the file, so the model is no larger than the file: the budget is about
  // what the caller holds beside it, and files larger than the computer can hold twice.
  const std::uint64_t texels = static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height);
  requireWithinMemory(name, kReadStep,
                      std::to_string(h.width) + "x" + std::to_string(h.height) + " texels of " +
                          std::to_string(h.terms) + " HSH terms",
                      size + (1 + budget.modelCopies) * h.payloadBytes + texels * budget.besidePerTexel, budget.bytes,
                      budget.memoryOption);
  HshFile hsh;
  hsh.width = h.width;
  hsh.height = h.height;
  hsh.terms = h.terms;
  const std::uint8_t* p = data + h.tablesOffset;
  hsh.scale = h.scale;  // complete: the payload check above covers the tables
  hsh.bias = h.bias;
  for (int k = 0; k < h.terms; ++k) {
    if (!std::isfinite(hsh.scale[k]) || !std::isfinite(hsh.bias[k])) {
      throw Error(ErrorKind::Input, name, kReadStep,
                  "scale or bias " + std::to_string(k + 1) + " is not a finite number; the "
                  "file is corrupt");
    }
  }
  const std::uint8_t* bytes = p + 8 * h.terms;
  resizeResident(hsh.coefficients, h.payloadBytes - 8 * static_cast<std::size_t>(h.terms));
  std::copy(bytes, bytes + hsh.coefficients.size(), hsh.coefficients.begin());
  if (report) {
    *report = h.report;
    report->trailingBytes = available - h.payloadBytes;
  }
  return hsh;
}

HshFile readRti(const std::filesystem::path& path, RtiReadReport* report, const ModelBudget& budget) {
  const std::string bytes = readFile(path, kReadStep);
  return parseRti(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                  path.string(), report, budget);
}

void validateHsh(const HshFile& hsh, const std::string& name) {
  auto fail = [&](const std::string& message) {
    throw Error(ErrorKind::Input, name, kWriteStep, "cannot write this RTI: " + message);
  };
  if (hsh.width < 1 || hsh.height < 1 || hsh.width > kMaxSide || hsh.height > kMaxSide ||
      static_cast<std::uint64_t>(hsh.width) * hsh.height > kMaxTexels) {
    fail("the size " + std::to_string(hsh.width) + " x " + std::to_string(hsh.height) +
         " is out of range");
  }
  if (hsh.terms != 4 && hsh.terms != 9 && hsh.terms != 16) fail("terms must be 4, 9 or 16");
  if (hsh.scale.size() != static_cast<std::size_t>(hsh.terms) ||
      hsh.bias.size() != static_cast<std::size_t>(hsh.terms) ||
      hsh.coefficients.size() != hsh.texels() * 3 * hsh.terms) {
    fail("the scale, bias or coefficient data does not match the size and terms");
  }
  for (int k = 0; k < hsh.terms; ++k) {
    if (!std::isfinite(hsh.scale[k]) || !std::isfinite(hsh.bias[k])) {
      fail("scale or bias " + std::to_string(k + 1) + " is not finite");
    }
  }
}

void writeRti(std::ostream& out, const HshFile& hsh, const std::string& name) {
  validateHsh(hsh, name);
  std::string header = "#HSH1.2\n3\n" + std::to_string(hsh.width) + " " +
                       std::to_string(hsh.height) + " 3\n" + std::to_string(hsh.terms) +
                       " 2 1\n";
  for (float s : hsh.scale) appendFloatLE(header, s);
  for (float b : hsh.bias) appendFloatLE(header, b);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(hsh.coefficients.data()),
            static_cast<std::streamsize>(hsh.coefficients.size()));
}

void writeRti(const std::filesystem::path& path, const HshFile& hsh) {
  validateHsh(hsh, path.string());
  AtomicFile file(path);
  writeTemporary(file, kWriteStep, [&](std::ostream& out) { writeRti(out, hsh, path.string()); });
  file.commit();
}

std::string serializeRti(const HshFile& hsh) {
  std::ostringstream out;
  writeRti(out, hsh, "(memory)");
  return out.str();
}

}  // namespace surrogate::formats
