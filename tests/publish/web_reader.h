// Test support: an independent reader of the web layout, written from docs/formats.md ("The
// web layout") and sharing no code with src/publish: a small JSON parser for info.json, the
// planes decoded with OpenCV, coefficient = (byte / 255 - bias) * scale, and the basis of
// each type in the viewers' order (PTM: 1, u, v, u^2, uv, v^2; HSH: the RTIViewer table of
// tests/fit/reference_basis.h). renderAt gives 8-bit display values as `surrogate render` does.
#pragma once

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

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
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
    cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);  // OpenCV gives B, G, R
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
