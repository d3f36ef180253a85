// Test support: an independent reader of the web layout, written from docs/formats.md ("The
// web layout") and sharing no code with src/publish: a small JSON parser for info.json, the
// planes decoded with OpenCV, coefficient = (byte / 255 - bias) * scale, and the basis of
// each type in the viewers' order (PTM: 1, u, v, u^2, uv, v^2; HSH: the RTIViewer table of
// tests/fit/reference_basis.h). renderAt gives 8-bit display values as `surrogate render` does.
// A plane stored as Deep Zoom tiles (plane_j.dzi and plane_j_files/LEVEL/COL_ROW.jpg, docs/formats.md,
// "Deep Zoom tiles") is assembled from the tiles of its full-size level, each tile checked for
// its size and its overlap.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "../fit/reference_basis.h"

namespace webtest {

// JSON: objects, arrays, strings (no escapes beyond \" and \\), numbers, true/false/null.
struct Json {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  double number = 0;
  std::string text;
  std::vector<Json> items;
  std::map<std::string, Json> members;

  const Json& operator[](const std::string& key) const {
    auto it = members.find(key);
    if (it == members.end()) throw std::runtime_error("info.json has no \"" + key + "\"");
    return it->second;
  }
  bool has(const std::string& key) const { return members.count(key) > 0; }
};

class JsonParser {
 public:
  explicit JsonParser(const std::string& s) : s_(s) {}
  Json parseDocument() {
    Json v = parseValue();
    skipSpace();
    if (i_ != s_.size()) fail("text after the value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("JSON: " + what + " at " + std::to_string(i_));
  }
  void skipSpace() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    skipSpace();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  std::string parseString() {
    expect('"');
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\') ++i_;
      out += s_[i_++];
    }
    expect('"');
    return out;
  }
  Json parseValue() {
    skipSpace();
    if (i_ >= s_.size()) fail("unexpected end");
    Json v;
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      v.kind = Json::Kind::Object;
      if (eat('}')) return v;
      do {
        skipSpace();
        std::string key = parseString();
        expect(':');
        v.members[key] = parseValue();
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      ++i_;
      v.kind = Json::Kind::Array;
      if (eat(']')) return v;
      do v.items.push_back(parseValue());
      while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.kind = Json::Kind::String;
      v.text = parseString();
    } else if (s_.compare(i_, 4, "true") == 0 || s_.compare(i_, 5, "false") == 0) {
      v.kind = Json::Kind::Bool;
      v.number = s_[i_] == 't';
      i_ += s_[i_] == 't' ? 4 : 5;
    } else if (s_.compare(i_, 4, "null") == 0) {
      i_ += 4;
    } else {
      std::size_t used = 0;
      v.kind = Json::Kind::Number;
      v.number = std::stod(s_.substr(i_, 40), &used);
      i_ += used;
    }
    return v;
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

// Standard base64 (RFC 4648); padding and line breaks skipped.
inline std::string decodeBase64(const std::string& text) {
  static const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  int bits = 0, value = 0;
  for (char ch : text) {
    const std::size_t d = digits.find(ch);
    if (d == std::string::npos) continue;
    value = (value << 6 | static_cast<int>(d)) & 0xffffff;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((value >> bits) & 0xff);
    }
  }
  return out;
}

// The JPEG bytes of every "data:image/jpeg;base64,..." string in `text`, in order.
inline std::vector<std::string> jpegDataUris(const std::string& text) {
  const std::string prefix = "\"data:image/jpeg;base64,";
  std::vector<std::string> out;
  for (std::size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    const std::size_t begin = at + prefix.size();
    out.push_back(decodeBase64(text.substr(begin, text.find('"', begin) - begin)));
  }
  return out;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A .dzi's attributes (TileSize, Overlap, Format, Width, Height), found by name.
struct DeepZoomInfo {
  int tileSize = 0, overlap = 0, width = 0, height = 0;
  std::string format;
  int levels = 0;  // 1 + halvings (rounding up) until the image fits in one tile
};

inline std::string xmlAttribute(const std::string& xml, const std::string& name) {
  const std::string key = name + "=\"";
  const std::size_t at = xml.find(key);
  if (at == std::string::npos) throw std::runtime_error(".dzi has no " + name);
  const std::size_t begin = at + key.size();
  return xml.substr(begin, xml.find('"', begin) - begin);
}

inline DeepZoomInfo readDzi(const std::filesystem::path& dzi) {
  const std::string xml = slurp(dzi);
  if (xml.find("http://schemas.microsoft.com/deepzoom/2008") == std::string::npos)
    throw std::runtime_error(dzi.string() + " is not a Deep Zoom descriptor");
  DeepZoomInfo d;
  d.tileSize = std::stoi(xmlAttribute(xml, "TileSize"));
  d.overlap = std::stoi(xmlAttribute(xml, "Overlap"));
  d.format = xmlAttribute(xml, "Format");
  d.width = std::stoi(xmlAttribute(xml, "Width"));
  d.height = std::stoi(xmlAttribute(xml, "Height"));
  int w = d.width, h = d.height;
  d.levels = 1;
  while (w > d.tileSize || h > d.tileSize) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    ++d.levels;
  }
  return d;
}

// The size of level `level` (levels - 1 is the full size; each level below halves, rounding up).
inline cv::Size deepZoomLevelSize(const DeepZoomInfo& d, int level) {
  int w = d.width, h = d.height;
  for (int l = d.levels - 1; l > level; --l) {
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
  return cv::Size(w, h);
}

// Level `level` of plane `stem` (e.g. "plane_0") assembled from its tiles, in OpenCV's B, G, R
// order. Each tile must have exactly the texels its column and row cover plus the overlap on
// each side that is not the level's edge; the level's folder holds no other file.
inline cv::Mat assembleDeepZoomLevel(const std::filesystem::path& folder, const std::string& stem, int level) {
  const DeepZoomInfo d = readDzi(folder / (stem + ".dzi"));
  const cv::Size size = deepZoomLevelSize(d, level);
  cv::Mat out(size, CV_8UC3);
  const auto dir = folder / (stem + "_files") / std::to_string(level);
  std::size_t tiles = 0;
  for (int row = 0; row * d.tileSize < size.height; ++row)
    for (int col = 0; col * d.tileSize < size.width; ++col, ++tiles) {
      const auto file = dir / (std::to_string(col) + "_" + std::to_string(row) + "." + d.format);
      const cv::Mat tile = cv::imread(file.string(), cv::IMREAD_COLOR);
      const int x = col * d.tileSize, y = row * d.tileSize;
      const int w = std::min(d.tileSize, size.width - x), h = std::min(d.tileSize, size.height - y);
      const int left = col > 0 ? d.overlap : 0, top = row > 0 ? d.overlap : 0;
      const int right = x + w < size.width ? d.overlap : 0, bottom = y + h < size.height ? d.overlap : 0;
      if (tile.empty() || tile.cols != left + w + right || tile.rows != top + h + bottom)
        throw std::runtime_error(file.string() + " is missing or not " + std::to_string(left + w + right) + "x" +
                                 std::to_string(top + h + bottom));
      tile(cv::Rect(left, top, w, h)).copyTo(out(cv::Rect(x, y, w, h)));
    }
  std::size_t present = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++present;
  if (present != tiles) throw std::runtime_error(dir.string() + " holds " + std::to_string(present) + " files for " +
                                                 std::to_string(tiles) + " tiles");
  return out;
}

// Plane j at full size: plane_j.jpg, or its Deep Zoom tiles when only plane_j.dzi is there.
inline cv::Mat readPlaneImage(const std::filesystem::path& folder, int j) {
  const std::string stem = "plane_" + std::to_string(j);
  if (std::filesystem::exists(folder / (stem + ".jpg")) || !std::filesystem::exists(folder / (stem + ".dzi")))
    return cv::imread((folder / (stem + ".jpg")).string(), cv::IMREAD_COLOR);  // OpenCV gives B, G, R
  const DeepZoomInfo d = readDzi(folder / (stem + ".dzi"));
  return assembleDeepZoomLevel(folder, stem, d.levels - 1);
}

struct WebModel {
  std::string type, colorspace;
  int width = 0, height = 0, nplanes = 0;
  std::vector<double> scale, bias;            // nplanes
  std::vector<std::vector<double>> coef;      // nplanes planes of width*height coefficients

  double at(int plane, int x, int y) const {
    return coef[static_cast<std::size_t>(plane)][static_cast<std::size_t>(y) * width + x];
  }
};

inline WebModel readWebModel(const std::filesystem::path& folder) {
  const std::string text = slurp(folder / "info.json");
  const Json info = JsonParser(text).parseDocument();
  WebModel m;
  m.type = info["type"].text;
  m.colorspace = info["colorspace"].text;
  m.width = static_cast<int>(info["width"].number);
  m.height = static_cast<int>(info["height"].number);
  m.nplanes = static_cast<int>(info["nplanes"].number);
  if (info["format"].text != "jpg") throw std::runtime_error("format is not jpg");
  const Json& material = info["materials"].items.at(0);
  for (const Json& v : material["scale"].items) m.scale.push_back(v.number);
  for (const Json& v : material["bias"].items) m.bias.push_back(v.number);
  if (static_cast<int>(m.scale.size()) != m.nplanes || static_cast<int>(m.bias.size()) != m.nplanes)
    throw std::runtime_error("scale or bias does not have nplanes values");
  const std::size_t n = static_cast<std::size_t>(m.width) * m.height;
  m.coef.assign(static_cast<std::size_t>(m.nplanes), std::vector<double>(n));
  for (int j = 0; j * 3 < m.nplanes; ++j) {
    const auto file = folder / ("plane_" + std::to_string(j) + ".jpg");
    const cv::Mat bgr = readPlaneImage(folder, j);
    if (bgr.empty() || bgr.cols != m.width || bgr.rows != m.height)
      throw std::runtime_error("cannot read " + file.string() + " at the size info.json gives");
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        const cv::Vec3b px = bgr.at<cv::Vec3b>(y, x);
        for (int c = 0; c < 3; ++c) {
          const int p = j * 3 + c;
          const double byte = px[2 - c];
          m.coef[static_cast<std::size_t>(p)][static_cast<std::size_t>(y) * m.width + x] =
              (byte / 255.0 - m.bias[static_cast<std::size_t>(p)]) * m.scale[static_cast<std::size_t>(p)];
        }
      }
  }
  return m;
}

// The light's weights for terms 0.. of the model's type, in the viewers' order.
inline std::vector<double> lightWeights(const WebModel& m, double lx, double ly, double lz) {
  std::vector<double> w;
  if (m.type == "ptm") {
    const auto uv = surrogate::reference::ptmArguments(lx, ly, lz);
    const double u = uv[0], v = uv[1];
    w = {1.0, u, v, u * u, u * v, v * v};
  } else {
    const auto a = surrogate::reference::hshAngles(lx, ly, lz);
    for (int k = 0; k < m.nplanes / 3; ++k) w.push_back(surrogate::reference::hshTable(k, a.theta, a.phi));
  }
  return w;
}

// 8-bit RGB (rows top-first, 3 values per pixel): value 0..1 times 255, rounded, clamped.
inline std::vector<int> renderAt(const WebModel& m, double lx, double ly, double lz) {
  const std::vector<double> w = lightWeights(m, lx, ly, lz);
  std::vector<int> out(static_cast<std::size_t>(m.width) * m.height * 3);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double v = 0;
        if (m.colorspace == "lrgb") {
          double l = 0;
          for (int k = 0; k < 6; ++k) l += w[static_cast<std::size_t>(k)] * m.at(3 + k, x, y);
          v = m.at(c, x, y) * l;
        } else {
          for (std::size_t k = 0; k < w.size(); ++k) v += w[k] * m.at(static_cast<int>(k) * 3 + c, x, y);
        }
        const double s = std::round(v * 255.0);
        out[(static_cast<std::size_t>(y) * m.width + x) * 3 + c] = static_cast<int>(std::min(255.0, std::max(0.0, s)));
      }
  return out;
}

// An 8-bit BGR picture (as OpenCV reads it) as RGB values, rows top-first, 3 per pixel.
inline std::vector<int> rgbValues(const cv::Mat& bgr) {
  std::vector<int> out;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x)
      for (int c = 0; c < 3; ++c) out.push_back(bgr.at<cv::Vec3b>(y, x)[2 - c]);
  return out;
}

// PSNR in dB of two 8-bit images of the same size (infinity when identical).
inline double psnr(const std::vector<int>& a, const std::vector<int>& b) {
  double se = 0;
  for (std::size_t i = 0; i < a.size(); ++i) se += double(a[i] - b[i]) * double(a[i] - b[i]);
  if (se == 0) return INFINITY;
  return 10 * std::log10(255.0 * 255.0 / (se / a.size()));
}

inline int maxAbsDifference(const std::vector<int>& a, const std::vector<int>& b) {
  int d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

}  // namespace webtest
