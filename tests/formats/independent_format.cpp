// The independent .ptm and .rti reader, writer and closed-form renderer
// (tests/formats/independent_format.h): nothing here calls src/formats or src/fit.
#include "independent_format.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "../fit/reference_basis.h"

namespace ref = surrogate::reference;

namespace indep {

std::string decimal(double v) {  // plain decimal, no exponent, trailing zeros dropped
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

Bytes writePtm(const Ptm& p) {
  Bytes out = "PTM_1.2\n";
  out += p.lrgb ? "PTM_FORMAT_LRGB\n" : "PTM_FORMAT_RGB\n";
  out += std::to_string(p.width) + "\n" + std::to_string(p.height) + "\n";
  for (int k = 0; k < 6; ++k) out += (k ? " " : "") + decimal(p.scale[k]);
  out += "\n";
  for (int k = 0; k < 6; ++k) out += (k ? " " : "") + std::to_string(p.bias[k]);
  out += "\n";
  for (std::size_t c = 0; c < p.coef.size(); ++c)  // LRGB: one block; RGB: red, green, blue
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int k = 0; k < 6; ++k) out += static_cast<char>(p.coef[c][p.height - 1 - r][x][k]);
  if (p.lrgb)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int c = 0; c < 3; ++c) out += static_cast<char>(p.colour[p.height - 1 - r][x][c]);
  return out;
}

// Splits "a b c" on single spaces; an empty token (double, leading or trailing space) fails.
std::vector<std::string> singleSpaced(const std::string& line, const char* what) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t sp = line.find(' ', start);
    out.push_back(line.substr(start, sp == std::string::npos ? std::string::npos : sp - start));
    if (out.back().empty()) throw Failure(std::string(what) + ": empty token in \"" + line + "\"");
    if (sp == std::string::npos) break;
    start = sp + 1;
  }
  return out;
}

long integer(const std::string& s, const char* what) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
    throw Failure(std::string(what) + " is not a plain integer: \"" + s + "\"");
  return std::stol(s);
}

Ptm readPtm(const Bytes& b) {
  Ptm p;
  std::size_t pos = 0;
  for (auto& line : p.headerLines) {
    const std::size_t nl = b.find('\n', pos);
    if (nl == std::string::npos) throw Failure("header ends early");
    line = b.substr(pos, nl - pos);
    if (line.find('\r') != std::string::npos) throw Failure("'\\r' in the header");
    pos = nl + 1;
  }
  if (p.headerLines[0] != "PTM_1.2") throw Failure("line 1 is not PTM_1.2");
  if (p.headerLines[1] == "PTM_FORMAT_LRGB") {
    p.lrgb = true;
  } else if (p.headerLines[1] == "PTM_FORMAT_RGB") {
    p.lrgb = false;
  } else {
    throw Failure("unexpected format line " + p.headerLines[1]);
  }
  p.width = static_cast<int>(integer(p.headerLines[2], "width (alone on line 3)"));
  p.height = static_cast<int>(integer(p.headerLines[3], "height (alone on line 4)"));
  const auto scales = singleSpaced(p.headerLines[4], "scale line");
  const auto biases = singleSpaced(p.headerLines[5], "bias line");
  if (scales.size() != 6 || biases.size() != 6) throw Failure("need 6 scales and 6 biases");
  for (int k = 0; k < 6; ++k) {
    if (scales[k].find_first_not_of("-.0123456789") != std::string::npos)
      throw Failure("scale \"" + scales[k] + "\" is not plain decimal notation");
    p.scale[k] = std::stod(scales[k]);
    p.bias[k] = static_cast<int>(integer(biases[k], "bias"));
    if (p.bias[k] > 255) throw Failure("bias above 255");
  }
  const std::size_t texels = static_cast<std::size_t>(p.width) * p.height;
  const std::size_t payload = texels * (p.lrgb ? 9 : 18);
  if (b.size() - pos != payload)
    throw Failure("payload is " + std::to_string(b.size() - pos) + " bytes, the header says " +
                  std::to_string(payload));
  p.allocate();
  auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(b[pos + i]); };
  std::size_t i = 0;
  for (std::size_t c = 0; c < p.coef.size(); ++c)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int k = 0; k < 6; ++k) p.coef[c][p.height - 1 - r][x][k] = byte(i++);
  if (p.lrgb)
    for (int r = 0; r < p.height; ++r)
      for (int x = 0; x < p.width; ++x)
        for (int c = 0; c < 3; ++c) p.colour[p.height - 1 - r][x][c] = byte(i++);
  return p;
}

void putFloat(Bytes& out, float f) {  // IEEE-754 binary32, little-endian
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  for (int i = 0; i < 4; ++i) out += static_cast<char>((u >> (8 * i)) & 0xFFu);
}

float getFloat(const Bytes& b, std::size_t at) {
  std::uint32_t u = 0;
  for (int i = 0; i < 4; ++i) u |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[at + i])) << (8 * i);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

Bytes writeRti(const Rti& r) {
  Bytes out = "#HSH1.2\n3\n" + std::to_string(r.width) + " " + std::to_string(r.height) +
              " 3\n" + std::to_string(r.terms) + " 2 1\n";
  for (float s : r.scale) putFloat(out, s);
  for (float s : r.bias) putFloat(out, s);
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < r.terms; ++k) out += static_cast<char>(r.coef[y][x][c][k]);
  return out;
}

Rti readRti(const Bytes& b) {
  Rti r;
  if (b.compare(0, 8, "#HSH1.2\n") != 0) throw Failure("does not start with \"#HSH1.2\\n\"");
  std::size_t pos = 0;
  std::vector<std::string> fields;  // the three non-comment lines
  while (fields.size() < 3) {
    const std::size_t nl = b.find('\n', pos);
    if (nl == std::string::npos) throw Failure("header ends early");
    const std::string line = b.substr(pos, nl - pos);
    r.headerLines.push_back(line);
    pos = nl + 1;
    if (line.find('\r') != std::string::npos) throw Failure("'\\r' in the header");
    if (!line.empty() && line[0] == '#') {
      if (!fields.empty()) throw Failure("a comment line after the RTI type line");
      continue;  // leading comment lines, "#HSH1.2" first
    }
    fields.push_back(line);
  }
  if (integer(fields[0], "RTI type") != 3) throw Failure("RTI type is not 3 (HSH)");
  const auto size = singleSpaced(fields[1], "size line");
  const auto basis = singleSpaced(fields[2], "basis line");
  if (size.size() != 3 || basis.size() != 3) throw Failure("size and basis lines need 3 fields");
  r.width = static_cast<int>(integer(size[0], "width"));
  r.height = static_cast<int>(integer(size[1], "height"));
  if (integer(size[2], "channels") != 3) throw Failure("channels is not 3");
  r.terms = static_cast<int>(integer(basis[0], "terms"));
  if (r.terms != 4 && r.terms != 9 && r.terms != 16) throw Failure("terms not 4, 9 or 16");
  if (basis[1] != "2" || basis[2] != "1") throw Failure("basis type and element size not \"2 1\"");
  const std::size_t payload = 8 * static_cast<std::size_t>(r.terms) +
                              static_cast<std::size_t>(r.width) * r.height * 3 * r.terms;
  if (b.size() - pos != payload)
    throw Failure("payload is " + std::to_string(b.size() - pos) + " bytes, the header says " +
                  std::to_string(payload));
  for (int k = 0; k < r.terms; ++k) r.scale.push_back(getFloat(b, pos + 4 * k));
  for (int k = 0; k < r.terms; ++k) r.bias.push_back(getFloat(b, pos + 4 * (r.terms + k)));
  pos += 8 * r.terms;
  r.allocate();
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < r.terms; ++k) r.coef[y][x][c][k] = static_cast<std::uint8_t>(b[pos++]);
  return r;
}

double ptmValue(const Ptm& p, int x, int y, int c, double lx, double ly, double lz) {
  const auto uv = ref::ptmArguments(lx, ly, lz);
  double l = 0;
  for (int k = 0; k < 6; ++k) l += p.a(p.lrgb ? 0 : c, x, y, k) * ref::ptmTerm(k, uv[0], uv[1]);
  return p.lrgb ? p.colour[y][x][c] * l / 255.0 : l;
}

double rtiValue(const Rti& r, int x, int y, int c, double lx, double ly, double lz) {
  double v = 0;
  for (int k = 0; k < r.terms; ++k) v += r.a(x, y, c, k) * ref::hshTerm(k, lx, ly, lz);
  return 255.0 * v;
}

}  // namespace indep
