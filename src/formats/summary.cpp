#include "formats/summary.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/text.h"
#include "formats/lp.h"
#include "formats/pronom.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

namespace surrogate::formats {

namespace fs = std::filesystem;

namespace {
const char* const kStep = "info";
constexpr std::size_t kHeaderBytes = 1 << 16;  // far more than any valid header

std::string readHead(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path.string(), kStep, "cannot open the file for reading");
  std::string head(kHeaderBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

void checkComplete(FileSummary& s, std::uint64_t headerAndPayload) {
  if (s.fileBytes < headerAndPayload) {
    throwInputError(s.path, kStep,
                    "the file is truncated: its header announces " +
                        std::to_string(headerAndPayload) + " bytes but the file has " +
                        std::to_string(s.fileBytes));
  }
  s.trailingBytes = s.fileBytes - headerAndPayload;
  if (s.trailingBytes)
    s.notes.push_back(std::to_string(s.trailingBytes) + " unexpected bytes follow the data");
}

std::string formatNumber(double v) {
  std::ostringstream o;
  o.precision(9);
  o << v;
  return o.str();
}
}  // namespace

namespace {

FileSummary summarizeContent(const fs::path& path) {
  FileSummary s;
  s.path = path.string();
  std::error_code ec;
  s.fileBytes = fs::file_size(path, ec);
  if (ec) throwInputError(s.path, kStep, "cannot read the file: " + ec.message());
  const std::string head = readHead(path);
  const auto* data = reinterpret_cast<const std::uint8_t*>(head.data());

  if (head.compare(0, 4, "PTM_") == 0) {
    const PtmHeader h = parsePtmHeader(data, head.size(), s.path);
    s.kind = "ptm";
    s.format = h.report.formatLine;
    s.version = h.report.version;
    s.basis = h.format == PtmFile::Format::Lrgb ? "ptm-lrgb" : "ptm-rgb";
    s.width = h.width;
    s.height = h.height;
    s.terms = 6;
    s.scale.assign(h.scale.begin(), h.scale.end());
    s.bias.assign(h.bias.begin(), h.bias.end());
    if (!h.jpegPlanes.empty()) {
      int predicted = 0;
      for (const PtmJpegPlane& p : h.jpegPlanes) predicted += p.reference >= 0;
      s.notes.push_back("JPEG-compressed (compression parameter " +
                        std::to_string(h.report.jpegQuality) + ", " +
                        std::to_string(predicted) + " of " +
                        std::to_string(h.jpegPlanes.size()) +
                        " planes predicted from another): the coefficients are JPEG's "
                        "approximation of the fitted ones");
    }
    if (h.report.sizeOnOneLine)
      s.notes.push_back("width and height share one line: RTIViewer cannot open this file");
    checkComplete(s, h.payloadOffset + static_cast<std::uint64_t>(h.payloadBytes));
    return s;
  }
  if (!head.empty() && head[0] == '#') {
    const RtiHeader h = parseRtiHeader(data, head.size(), s.path);
    s.kind = "rti";
    s.format = "HSH";
    s.version = h.report.comments.empty() ? "" : h.report.comments[0];
    s.basis = h.terms == 4 ? "hsh2" : h.terms == 9 ? "hsh3" : "hsh4";
    s.width = h.width;
    s.height = h.height;
    s.terms = h.terms;
    s.scale.assign(h.scale.begin(), h.scale.end());  // empty if the file ends before them
    s.bias.assign(h.bias.begin(), h.bias.end());
    if (h.terms == 16)
      s.notes.push_back("16-term HSH: some RTIViewer builds display at most 9 terms");
    checkComplete(s, h.tablesOffset + static_cast<std::uint64_t>(h.payloadBytes));
    return s;
  }
  if (lowerCase(path.extension().string()) == ".lp") {
    const std::vector<LightEntry> lights = readLp(path);
    s.kind = "lp";
    s.format = "light positions";
    s.lightCount = static_cast<int>(lights.size());
    double lo = 90, hi = -90;
    for (const LightEntry& l : lights) {
      const double e = std::asin(std::clamp(l.z, -1.0, 1.0)) * 180.0 / M_PI;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
    s.minElevationDegrees = lo;
    s.maxElevationDegrees = hi;
    if (lo <= 0) s.notes.push_back("some lights are at or below the surface plane (lz <= 0)");
    return s;
  }
  throwInputError(s.path, kStep, "is not a .ptm, .rti or .lp file (unrecognised content)");
}

}  // namespace

FileSummary summarize(const fs::path& path) {
  FileSummary s = summarizeContent(path);
  const PronomIdentity id = identifyPronomFile(path);
  s.puid = id.puid;
  s.pronom = id.describe();
  return s;
}

// The layout `surrogate info` gives every kind: "PATH: what it is" first, then one indented
// "label: value" line per fact, the values in one column (as for an image, a capture or a
// package).
std::string FileSummary::toText() const {
  std::ostringstream o;
  o << path << ": ";
  if (kind == "lp")
    o << "light positions (.lp), " << lightCount << (lightCount == 1 ? " light" : " lights") << "\n";
  else
    o << (kind == "ptm" ? "PTM" : "RTI") << " model " << basis << ", " << width << "x" << height << "\n";
  auto line = [&](const std::string& label, const std::string& value) {
    std::string padded = label + ":";
    padded.resize(std::max<std::size_t>(padded.size() + 1, 11), ' ');
    o << "  " << padded << value << "\n";
  };
  line("PRONOM", pronom);
  if (kind == "lp") {
    // Angles to 0.1 degree, as the report shows them; --json has the full values.
    line("elevation", fixedDecimals(minElevationDegrees, 1) + " to " + fixedDecimals(maxElevationDegrees, 1) + " degrees");
  } else {
    line("format", version.empty() ? format : version + ", " + format);
    line("terms", std::to_string(terms) + " per channel");
    auto list = [&](const char* label, const std::vector<double>& v) {
      if (v.empty()) return;
      std::string values;
      for (double x : v) values += (values.empty() ? "" : " ") + formatNumber(x);
      line(label, values);
    };
    list("scale", scale);
    list("bias", bias);
  }
  line("bytes", std::to_string(fileBytes));
  for (const std::string& n : notes) line("note", n);
  std::string text = o.str();
  text.pop_back();  // the caller ends the last line
  return text;
}

std::string FileSummary::toJson() const {
  JsonWriter j;
  j.beginObject().key("file").value(path).key("kind").value(kind).key("format").value(format);
  if (!version.empty()) j.key("version").value(version);
  if (kind == "lp") {
    j.key("lights").value(lightCount).key("minElevationDegrees").value(minElevationDegrees)
        .key("maxElevationDegrees").value(maxElevationDegrees);
  } else {
    j.key("basis").value(basis).key("width").value(width).key("height").value(height)
        .key("terms").value(terms);
    j.key("scale").beginArray();
    for (double x : scale) j.value(x);
    j.endArray().key("bias").beginArray();
    for (double x : bias) j.value(x);
    j.endArray();
    j.key("trailingBytes").value(static_cast<unsigned long long>(trailingBytes));
  }
  j.key("puid").value(puid).key("pronom").value(pronom);
  j.key("bytes").value(static_cast<unsigned long long>(fileBytes));
  j.key("notes").beginArray();
  for (const std::string& n : notes) j.value(n);
  j.endArray().endObject();
  return j.str();
}

}  // namespace surrogate::formats
