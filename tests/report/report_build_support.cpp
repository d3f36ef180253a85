// The buildReport tests' shared helpers (report_build_support.h).
#include "report_build_support.h"

#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "formats/ptm.h"
#include "formats/rti_hsh.h"

using namespace surrogate;

namespace report_build {

std::string png(int width, int height) {
  cv::Mat m(height, width, CV_8UC3, cv::Scalar(40, 120, 200));
  std::vector<unsigned char> out;
  cv::imencode(".png", m, out);
  return std::string(out.begin(), out.end());
}

std::string smallPtm() {
  formats::PtmFile ptm;
  ptm.width = 8;
  ptm.height = 6;
  ptm.scale = {0.5, 0.5, 0.5, 1, 1, 1};
  ptm.bias = {128, 128, 128, 128, 128, 0};
  ptm.coefficients.assign(ptm.texels() * 6, 128);
  ptm.rgb.assign(ptm.texels() * 3, 200);
  return formats::serializePtm(ptm);
}

std::string smallHsh(int width, int height) {
  formats::HshFile hsh;
  hsh.width = width;
  hsh.height = height;
  hsh.terms = 4;
  hsh.scale.assign(4, 0.01f);
  hsh.bias.assign(4, 0.5f);
  hsh.coefficients.resize(hsh.texels() * 3 * 4);
  for (std::size_t k = 0; k < hsh.coefficients.size(); ++k) hsh.coefficients[k] = static_cast<std::uint8_t>(k * 7);
  return formats::serializeRti(hsh);
}

carrier::FileRecord output(const std::string& path, const std::string& role, const std::string& format) {
  carrier::FileRecord f;
  f.path = path;
  f.role = role;
  f.size = 1;
  f.format = format;
  return f;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

carrier::Carrier sampleCarrier() {
  carrier::Carrier c = carrier::newCarrier(std::string("Stela ") + kHostile, {{kHostile, "photographer"}});
  c.header.meta.push_back({"site", kHostile});
  for (int i = 1; i <= 5; ++i) {
    carrier::FileRecord f;
    f.path = "original-captures/IMG_000" + std::to_string(i) + ".dng";
    f.role = "original";
    f.size = 100;
    f.sha256 = std::string(64, 'a');
    f.camera = {{"make", "Canon"}, {"model", "EOS 5D"}, {"lens", kHostile}, {"iso", i == 5 ? "200" : "100"}};
    c.putFile(f);
  }
  carrier::Step& ingest = c.addStep("CaptureIngest", "1");
  ingest.interventions.push_back({"exclude-image", "original-captures/IMG_0006.dng", "", "A. Conservator",
                                  "2026-01-01T00:00:00Z", std::string("flash misfired ") + kHostile});
  carrier::Step& lights = c.addStep("LightDirections", "1");
  lights.setParam("model", kHostile);
  carrier::Step& fit = c.addStep("RtiFit", "1");
  fit.setParam("basis", "ptm-lrgb");
  carrier::Step& maps = c.addStep("DerivedMaps", "1");

  const std::string overlay = c.putFile(output("assembly-files/spheres.png", "assembly", "PNG"));
  const std::string ptm = c.putFile(output("finished-files/ptm-lrgb.ptm", "result", "PTM_FORMAT_LRGB"));
  const std::string normals = c.putFile(output("finished-files/normals.png", "result", "PNG"));
  const std::string albedo = c.putFile(output("finished-files/albedo.png", "result", "PNG"));

  carrier::Result lr;
  lr.step = lights.id;
  lr.add("sphere").set("index", 0).set("cx", 10.0).set("cy", 20.0).set("r", 5.0).set("confidence", 0.9)
      .set("source", "detected");
  lr.add("output").set("file", overlay).set("kind", "sphere-overlay");
  for (int i = 0; i < 5; ++i)
    lr.add("light").set("image", "f" + std::to_string(i + 1)).set("x", 0.0).set("y", 0.0).set("z", 1.0)
        .set("elevationDeg", 30.0 + 10 * i).set("azimuthDeg", -150.0 + 70 * i).set("source", "sphere 0");
  c.data.push_back(lr);
  carrier::Result fr;
  fr.step = fit.id;
  fr.add("output").set("file", ptm).set("kind", "ptm-lrgb");
  fr.add("value").set("name", "rmse").set("value", 4.5);
  fr.add("value").set("name", "psnr").set("value", 30.0);
  for (int i = 0; i < 5; ++i)
    fr.add("imageValue").set("image", "f" + std::to_string(i + 1)).set("name", "rmse").set("value", 1.0 + i);
  c.data.push_back(fr);
  carrier::Result mr;
  mr.step = maps.id;
  mr.add("output").set("file", normals).set("kind", "normals");
  mr.add("output").set("file", albedo).set("kind", "albedo");
  mr.add("value").set("name", "normalFallbackPixels").set("value", 600);
  c.data.push_back(mr);
  for (carrier::FileRecord& f : c.files)
    if (f.id == normals) f.createdBy = maps.id;
  c.addLog("warning", fit.id, std::string("something odd ") + kHostile);
  return c;
}

HeldPicture heldPicture(int width, int height, int channels, bool sixteenBit, int seed) {
  HeldPicture p;
  p.pixels = Image(width, height, channels);
  p.pixels.bitsPerSample = sixteenBit ? 16 : 8;
  cv::Mat m(height, width, CV_MAKETYPE(sixteenBit ? CV_16U : CV_8U, channels));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) {
        const int value = (x * 977 + y * 131 + c * 4099 + seed * 7919) % 65536;
        const int stored = sixteenBit ? value : value % 256 * 257;
        p.pixels.at(x, y, c) = static_cast<std::uint16_t>(stored);
        const int bgr = x * channels + (channels == 3 ? 2 - c : 0);  // OpenCV keeps BGR
        if (sixteenBit) m.at<std::uint16_t>(y, bgr) = static_cast<std::uint16_t>(stored);
        else m.at<std::uint8_t>(y, bgr) = static_cast<std::uint8_t>(stored / 257);
      }
  std::vector<unsigned char> out;
  cv::imencode(".png", m, out);
  p.png.assign(out.begin(), out.end());
  return p;
}

}  // namespace report_build
