#include "formats/ptm_jpeg.h"

#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/resident.h"
#include "image/decode.h"

namespace surrogate::formats {

namespace {
const char* const kReadStep = "read PTM";
// A plane larger than a terabyte is a damaged header; the bound keeps every sum of sizes
// far from overflowing.
constexpr long long kMaxPlaneBytes = 1ll << 40;
constexpr long long kMaxMotion = 65536;

// "a3", "red" (LRGB) or "green a3" (RGB): how the error messages name plane p.
std::string planeName(std::size_t planes, std::size_t p) {
  static const char* const kColour[3] = {"red", "green", "blue"};
  const std::string k = "a" + std::to_string(p % 6);
  if (planes == 9) return p < 6 ? k : std::string(kColour[p - 6]);
  return std::string(kColour[p / 6]) + " " + k;
}

// One table line: exactly `count` integers in lo..hi.
std::vector<long long> integers(HeaderCursor& cur, std::size_t count, const char* what,
                                long long lo, long long hi) {
  const auto t = tokens(cur.line(what));
  const std::string where = "line " + std::to_string(cur.lineNumber()) + " (" + what + ")";
  if (t.size() != count) {
    cur.fail(where + " should hold " + std::to_string(count) + " integers, found " +
             std::to_string(t.size()) + " items");
  }
  std::vector<long long> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (!parseInt(t[i], &out[i]) || out[i] < lo || out[i] > hi) {
      cur.fail(where + ": item " + std::to_string(i + 1) + " \"" + std::string(t[i].substr(0, 40)) +
               "\" is not an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    }
  }
  return out;
}
}  // namespace

void parseJpegPlaneTable(HeaderCursor& cur, int planes, PtmHeader* header) {
  const std::uint64_t texels = static_cast<std::uint64_t>(header->width) * header->height;
  if (texels > image::kMaxImagePixels) {
    cur.fail("the image size " + std::to_string(header->width) + " x " +
             std::to_string(header->height) + " is larger than the " +
             std::to_string(image::kMaxImagePixels / 1000000) +
             " million texels this program decodes from JPEG planes; the header is corrupt");
  }
  const std::size_t n = static_cast<std::size_t>(planes);
  header->report.jpegQuality =
      static_cast<int>(integers(cur, 1, "compression parameter", 0, 1 << 30)[0]);
  const auto transform = integers(cur, n, "transforms", 0, 3);
  const auto motionX = integers(cur, n, "motion vectors, x", -kMaxMotion, kMaxMotion);
  const auto motionY = integers(cur, n, "motion vectors, y", -kMaxMotion, kMaxMotion);
  const auto order = integers(cur, n, "decoding order", 0, planes - 1);
  const auto reference = integers(cur, n, "reference planes", -1, planes - 1);
  const auto jpegBytes = integers(cur, n, "compressed sizes", 1, kMaxPlaneBytes);
  const auto sideBytes = integers(cur, n, "side information sizes", 0, kMaxPlaneBytes);

  std::vector<bool> seen(n, false);
  for (std::size_t p = 0; p < n; ++p) {
    if (seen[static_cast<std::size_t>(order[p])]) {
      cur.fail("the decoding order gives position " + std::to_string(order[p]) +
               " to two planes; it must number the planes 0.." + std::to_string(planes - 1) +
               " once each");
    }
    seen[static_cast<std::size_t>(order[p])] = true;
  }
  header->jpegPlanes.assign(n, PtmJpegPlane{});
  header->payloadBytes = 0;
  for (std::size_t p = 0; p < n; ++p) {
    PtmJpegPlane& d = header->jpegPlanes[p];
    const std::string plane = "plane " + std::to_string(p) + " (" + planeName(n, p) + ")";
    d.transform = static_cast<int>(transform[p]);
    d.motionX = static_cast<int>(motionX[p]);
    d.motionY = static_cast<int>(motionY[p]);
    d.order = static_cast<int>(order[p]);
    d.reference = static_cast<int>(reference[p]);
    d.jpegBytes = static_cast<std::uint64_t>(jpegBytes[p]);
    d.sideBytes = static_cast<std::uint64_t>(sideBytes[p]);
    if (d.reference == static_cast<int>(p)) cur.fail(plane + " names itself as its reference");
    if (d.reference >= 0 && order[static_cast<std::size_t>(d.reference)] > order[p]) {
      cur.fail(plane + " is predicted from plane " + std::to_string(d.reference) +
               ", which the decoding order places after it");
    }
    // Motion compensation moves the reference by the motion vector; what lies outside the
    // image then is not specified, and no known tool writes it: refused rather than guessed.
    if (d.reference >= 0 && (d.transform & 2) && (d.motionX != 0 || d.motionY != 0)) {
      cur.fail(plane + " is predicted with motion compensation (vector " +
               std::to_string(d.motionX) + ", " + std::to_string(d.motionY) +
               "), which this program does not read");
    }
    if (d.sideBytes % 5 != 0) {
      cur.fail(plane + " has " + std::to_string(d.sideBytes) +
               " bytes of side information, not a multiple of the 5 bytes of one correction");
    }
    header->payloadBytes += static_cast<std::size_t>(d.jpegBytes + d.sideBytes);
  }
}

PtmFile decodeJpegPtm(const PtmHeader& h, const std::uint8_t* payload, std::size_t available,
                      const std::string& name) {
  const std::size_t n = h.jpegPlanes.size();
  const std::size_t w = static_cast<std::size_t>(h.width);
  const std::size_t rows = static_cast<std::size_t>(h.height);
  const std::size_t texels = w * rows;
  if (available < h.payloadBytes || (n != 9 && n != 18)) {
    throw Error(ErrorKind::Internal, name, kReadStep, "the JPEG planes were not checked");
  }
  std::vector<std::size_t> start(n);
  std::vector<std::size_t> sequence(n);
  std::size_t at = 0;
  for (std::size_t p = 0; p < n; ++p) {
    start[p] = at;
    at += static_cast<std::size_t>(h.jpegPlanes[p].jpegBytes + h.jpegPlanes[p].sideBytes);
    sequence[static_cast<std::size_t>(h.jpegPlanes[p].order)] = p;
  }

  PtmFile ptm;
  ptm.format = n == 9 ? PtmFile::Format::Lrgb : PtmFile::Format::Rgb;
  ptm.width = h.width;
  ptm.height = h.height;
  ptm.scale = h.scale;
  ptm.bias = h.bias;
  resizeResident(ptm.coefficients, texels * (n == 9 ? 6 : 18));
  if (n == 9) resizeResident(ptm.rgb, texels * 3);
  // Each plane goes into the model as soon as it is final, and a plane predicted from another
  // reads that one back from the model: one decoded plane is held at a time, not all nine or
  // eighteen (ptmReadBytes counts on it). Plane p of texel t (rows top first) is
  // base[t * stride].
  struct Slot {
    std::uint8_t* base;
    std::size_t stride;
  };
  auto slotOf = [&](std::size_t p) -> Slot {
    if (n == 9) return p < 6 ? Slot{ptm.coefficients.data() + p, 6} : Slot{ptm.rgb.data() + (p - 6), 3};
    return Slot{ptm.coefficients.data() + (p / 6) * texels * 6 + p % 6, 6};
  };

  for (const std::size_t p : sequence) {
    const PtmJpegPlane& d = h.jpegPlanes[p];
    auto fail = [&](const std::string& message) {
      throw Error(ErrorKind::Input, name, kReadStep,
                  "plane " + std::to_string(p) + " (" + planeName(n, p) + "): " + message);
    };
    image::JpegSamples j = image::decodeJpegSamples(
        payload + start[p], static_cast<std::size_t>(d.jpegBytes), texels);
    if (!j.problem.empty()) fail("its JPEG stream cannot be decoded: " + j.problem);
    if (j.width != h.width || j.height != h.height) {
      fail("its JPEG stream is " + std::to_string(j.width) + " x " + std::to_string(j.height) +
           " pixels, the header announces " + std::to_string(h.width) + " x " +
           std::to_string(h.height));
    }
    if (j.components != 1) fail("its JPEG stream is in colour; each plane is a greyscale JPEG");
    std::vector<std::uint8_t> v = std::move(j.samples);
    // Plane rows run bottom-up; the model's rows top-down.
    if (d.reference >= 0) {
      const Slot r = slotOf(static_cast<std::size_t>(d.reference));
      const bool invert = (d.transform & 1) != 0;
      for (std::size_t row = 0; row < rows; ++row) {
        const std::uint8_t* ref = r.base + (rows - 1 - row) * w * r.stride;
        std::uint8_t* out = v.data() + row * w;
        for (std::size_t x = 0; x < w; ++x) {
          const int prediction = invert ? 255 - ref[x * r.stride] : ref[x * r.stride];
          out[x] = static_cast<std::uint8_t>((out[x] + prediction - 128) & 0xFF);
        }
      }
    }
    const std::uint8_t* side = payload + start[p] + d.jpegBytes;
    for (std::size_t e = 0; e < d.sideBytes; e += 5) {
      const std::uint64_t index = (std::uint64_t{side[e]} << 24) | (std::uint64_t{side[e + 1]} << 16) |
                                  (std::uint64_t{side[e + 2]} << 8) | side[e + 3];
      if (index >= texels) {
        fail("side-information entry " + std::to_string(e / 5 + 1) + " corrects texel " +
             std::to_string(index) + ", outside the " + std::to_string(texels) + " texels");
      }
      v[index] = side[e + 4];
    }
    const Slot s = slotOf(p);
    for (std::size_t row = 0; row < rows; ++row) {
      std::uint8_t* out = s.base + (rows - 1 - row) * w * s.stride;
      const std::uint8_t* in = v.data() + row * w;
      for (std::size_t x = 0; x < w; ++x) out[x * s.stride] = in[x];
    }
  }
  return ptm;
}

}  // namespace surrogate::formats
