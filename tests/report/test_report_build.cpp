// buildReport on carriers made in memory: what the page contains, what it escapes, and how it
// copes with missing files.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <tuple>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "carrier/carrier.h"
#include "core/image.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "page_bytes.h"
#include "report/report.h"

using namespace surrogate;
using namespace surrogate::report;
using report_test::pictureBytes;

namespace {

constexpr const char* kHostile = "\"><img src=x onerror=alert(1)></script><script>alert(2)</script>";

class MemorySource : public ReportSource {
 public:
  explicit MemorySource(carrier::Carrier c) : carrier_(std::move(c)) {}
  const carrier::Carrier& carrier() const override { return carrier_; }
  std::optional<std::string> read(const std::string& path) const override {
    const auto it = files.find(path);
    if (it == files.end()) return std::nullopt;
    return it->second;
  }
  std::string describe() const override { return "test source"; }
  bool isPackage() const override { return false; }
  std::map<std::string, std::string> files;

 private:
  carrier::Carrier carrier_;
};

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

// An HSH of order 2 whose bytes differ from texel to texel, as an .rti file.
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

// A carrier like a run's: 5 images, spheres, lights, a PTM fit with residuals, derived maps,
// an intervention and a warning; every free text field hostile.
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

// A picture as a pipeline step holds it (Image: 16-bit values, or 8-bit values * 257), and the
// same pixels as a PNG file written by OpenCV, a writer independent of Surrogate's.
struct HeldPicture {
  Image pixels;
  std::string png;
};

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

}  // namespace

TEST_CASE("the same check after two fits names the fit each ran on") {
  // residual-outlier runs after every fit: without the fit named, the table showed one check twice.
  carrier::Carrier c = sampleCarrier();
  carrier::Step& hsh = c.addStep("RtiFit", "1");
  hsh.setParam("basis", "hsh2");
  for (carrier::Result& r : c.data)
    if (r.step == c.process[2].id) r.add("check").set("name", "residual-outlier").set("status", "passed").set("detail", "a");
  carrier::Result hr;
  hr.step = hsh.id;
  hr.add("check").set("name", "residual-outlier").set("status", "passed").set("detail", "b");
  c.data.push_back(hr);
  MemorySource source(c);
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  const Report r = buildReport(source.carrier(), source, options);
  CHECK_THAT(r.html, Catch::Contains("<td><code>residual-outlier</code></td><td>Fit: PTM (LRGB)</td><td>passed</td><td>a</td>"));
  CHECK_THAT(r.html, Catch::Contains("<td><code>residual-outlier</code></td><td>Fit: HSH order 2</td><td>passed</td><td>b</td>"));
}

TEST_CASE("pictures given as display copies of their pixels make the page their PNG files make") {
  const std::map<std::string, HeldPicture> held = {
      {"assembly-files/spheres.png", heldPicture(1600, 1200, 3, false, 1)},
      {"finished-files/normals.png", heldPicture(900, 600, 3, true, 2)},
      {"finished-files/albedo.png", heldPicture(300, 200, 1, false, 3)}};
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  // One carrier for both pages: each sampleCarrier() stamps its log with the time it is made,
  // and two made a second apart gave two pages (this test failed about once in 60 runs).
  const carrier::Carrier c = sampleCarrier();
  MemorySource files(c);
  for (const auto& [path, picture] : held) files.files[path] = picture.png;
  files.files["finished-files/ptm-lrgb.ptm"] = smallPtm();
  const Report fromFiles = buildReport(files.carrier(), files, options);
  REQUIRE(fromFiles.picturesEmbedded == 3);

  // From the copies alone (the source has no picture files): the same page.
  MemorySource modelOnly(c);
  modelOnly.files["finished-files/ptm-lrgb.ptm"] = smallPtm();
  auto copies = std::make_shared<std::map<std::string, DisplayPicture>>();
  for (const auto& [path, picture] : held) (*copies)[path] = displayPicture(picture.pixels, options.maxImageSide);
  options.displayed = copies;
  const Report fromCopies = buildReport(modelOnly.carrier(), modelOnly, options);
  CHECK(fromCopies.picturesEmbedded == 3);
  CHECK(fromCopies.html == fromFiles.html);

  // Copies made for another size are not used: the pictures are then read, here missing.
  options.maxImageSide = 500;
  const Report otherSize = buildReport(modelOnly.carrier(), modelOnly, options);
  CHECK(otherSize.picturesEmbedded == 0);
  CHECK(count(otherSize.html, "not found in this package or capture") == 3);
}

TEST_CASE("the report shows lights, pictures, relighting, provenance and camera of a carrier") {
  MemorySource source(sampleCarrier());
  source.files["assembly-files/spheres.png"] = png(1600, 1200);
  source.files["finished-files/normals.png"] = png(300, 200);
  source.files["finished-files/albedo.png"] = png(300, 200);
  source.files["finished-files/ptm-lrgb.ptm"] = smallPtm();
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  const Report r = buildReport(source.carrier(), source, options);

  CHECK(r.lightsPlotted == 5);
  CHECK(count(r.html, "<circle class=\"light\"") == 5);
  CHECK_THAT(r.html, Catch::Contains("data-lights-expected=\"5\""));
  CHECK(r.picturesEmbedded == 3);
  CHECK(count(r.html, "src=\"data:image/jpeg;base64,") == 3);
  // Beside the normal map (300x200): 600 pixels took the Lambertian normal, 1 %, said plainly.
  CHECK_THAT(r.html, Catch::Contains("<p><span class=\"ok explain\">600 pixels (1 %) of the normal map have an "
                                     "estimated normal"));
  // The 1600x1200 overlay is embedded at 720x540.
  CHECK_THAT(r.html, Catch::Contains("(1600\u00d71200, shown at 720\u00d7540)"));
  CHECK(r.relightable);
  CHECK_THAT(r.html, Catch::Contains("id=\"relight-data\""));
  // The view opens at the lights' mean direction: elevations 30..70, azimuths -150..130 in
  // steps of 70 (sampleCarrier). Summed (cos e cos a, cos e sin a, sin e) = (0.046198,
  // -0.604023, 3.714550), normalised (0.0122749, -0.16049, 0.986961) (computed with Python).
  CHECK_THAT(r.html, Catch::Contains("data-start-light=\"0.0122749,-0.16049,0.986961\""));
  // Coverage: lights from 30 to 70 degrees elevation: raking light missing, said on the page.
  REQUIRE_FALSE(r.coverageGaps.empty());
  CHECK_THAT(r.html, Catch::Contains("No light below 20"));
  // Provenance: every step, the intervention with who, and the warning.
  for (const char* component : {"CaptureIngest", "LightDirections", "RtiFit", "DerivedMaps"})
    CHECK_THAT(r.html, Catch::Contains(component));
  CHECK_THAT(r.html, Catch::Contains("A. Conservator"));
  CHECK_THAT(r.html, Catch::Contains("exclude-image"));
  CHECK_THAT(r.html, Catch::Contains("flash misfired"));
  // Camera: the ISO that varies between shots is pointed out.
  CHECK_THAT(r.html, Catch::Contains("EOS 5D"));
  CHECK_THAT(r.html, Catch::Contains("varies between shots"));
  CHECK_THAT(r.html, Catch::Contains("2026-02-03T04:05:06Z"));
  // No network: a CSP forbids every fetch, and no http(s) URL appears in an attribute.
  CHECK_THAT(r.html, Catch::Contains("default-src 'none'"));
  CHECK(r.html.find("src=\"http") == std::string::npos);
  CHECK(r.html.find("href=\"http") == std::string::npos);
}

TEST_CASE("the page is byte-identical whether its pictures and models are made on 1 or 2 threads") {
  // Pictures that differ from each other (a gradient per file), so that a picture shown in
  // another's place would change the page.
  const auto gradient = [](int width, int height, int seed) {
    cv::Mat m(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) m.at<cv::Vec3b>(y, x) = cv::Vec3b(x * seed % 256, y * 3 % 256, (x + y + seed) % 256);
    std::vector<unsigned char> out;
    cv::imencode(".png", m, out);
    return std::string(out.begin(), out.end());
  };
  // Three models, made at once on two threads: an HSH fit and a damaged PTM besides the LRGB
  // one; the page keeps them in carrier order.
  carrier::Carrier c = sampleCarrier();
  for (const auto& [basis, path, format] :
       {std::tuple<std::string, std::string, std::string>{"hsh2", "finished-files/hsh2.rti", "RTI_HSH"},
        {"ptm-rgb", "finished-files/ptm-rgb.ptm", "PTM_FORMAT_RGB"}}) {
    carrier::Step& fit = c.addStep("RtiFit", "1");
    fit.setParam("basis", basis);
    carrier::Result r;
    r.step = fit.id;
    r.add("output").set("file", c.putFile(output(path, "result", format))).set("kind", basis);
    c.data.push_back(r);
  }
  MemorySource source(c);
  source.files["assembly-files/spheres.png"] = gradient(1600, 1200, 1);
  source.files["finished-files/normals.png"] = gradient(900, 600, 2);
  source.files["finished-files/albedo.png"] = gradient(300, 200, 3);
  source.files["finished-files/ptm-lrgb.ptm"] = smallPtm();
  source.files["finished-files/hsh2.rti"] = smallHsh(10, 4);
  source.files["finished-files/ptm-rgb.ptm"] = smallPtm().substr(0, 40);  // cut short
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  options.threads = 1;
  const Report one = buildReport(source.carrier(), source, options);
  options.threads = 2;
  const Report two = buildReport(source.carrier(), source, options);
  CHECK(one.picturesEmbedded == 3);
  CHECK(two.picturesEmbedded == 3);
  CHECK(one.html == two.html);
  const std::size_t lrgb = one.html.find("\"basis\":\"ptm-lrgb\""), hsh2 = one.html.find("\"basis\":\"hsh2\"");
  REQUIRE(lrgb != std::string::npos);
  REQUIRE(hsh2 != std::string::npos);
  CHECK(lrgb < hsh2);
  CHECK_THAT(one.html, Catch::Contains("The model cannot be shown"));
  // In carrier order: the overlay (detection), then normals and albedo (results).
  const std::size_t overlay = one.html.find("(1600\u00d71200"), normals = one.html.find("(900\u00d7600"),
                    albedo = one.html.find("(300\u00d7200");
  REQUIRE(overlay != std::string::npos);
  CHECK(overlay < normals);
  CHECK(normals < albedo);
}

TEST_CASE("models given as interactive copies of the models in memory make the page their files make") {
  // Scales with no short decimal form, as the fits choose them: the copies must carry the
  // numbers the files read back, not others of their own.
  formats::PtmFile ptm;
  ptm.width = 2500;  // longer side above relightMaxSide: copies are block averages
  ptm.height = 7;
  for (int k = 0; k < 6; ++k) {
    ptm.scale[k] = (k + 1) / 3.0 + 1e-9 * k;
    ptm.bias[k] = 17 * k + 3;
  }
  ptm.coefficients.resize(ptm.texels() * 6);
  ptm.rgb.resize(ptm.texels() * 3);
  for (std::size_t i = 0; i < ptm.coefficients.size(); ++i) ptm.coefficients[i] = static_cast<std::uint8_t>(i * 31 % 251);
  for (std::size_t i = 0; i < ptm.rgb.size(); ++i) ptm.rgb[i] = static_cast<std::uint8_t>(i * 13 % 256);
  formats::HshFile hsh;
  hsh.width = 9;
  hsh.height = 5;
  hsh.terms = 4;
  hsh.scale = {0.1f, 1.0f / 3, 2.5e-7f, 7.0f};
  hsh.bias = {-0.3f, 0.7f / 3, 0.0f, -1e-5f};
  hsh.coefficients.resize(hsh.texels() * 3 * 4);
  for (std::size_t i = 0; i < hsh.coefficients.size(); ++i) hsh.coefficients[i] = static_cast<std::uint8_t>(i * 7 % 256);

  carrier::Carrier c = sampleCarrier();
  carrier::Step& fit = c.addStep("RtiFit", "1");
  fit.setParam("basis", "hsh2");
  carrier::Result r;
  r.step = fit.id;
  r.add("output").set("file", c.putFile(output("finished-files/hsh2.rti", "result", "RTI_HSH"))).set("kind", "hsh2");
  c.data.push_back(r);
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";

  MemorySource files(c);
  files.files["finished-files/ptm-lrgb.ptm"] = formats::serializePtm(ptm);
  files.files["finished-files/hsh2.rti"] = formats::serializeRti(hsh);
  const Report fromFiles = buildReport(files.carrier(), files, options);
  REQUIRE(fromFiles.relightable);
  REQUIRE(count(fromFiles.html, "\"model\":\"") == 2);

  // From the copies alone (the source has no model files): the same page.
  MemorySource none(c);
  auto copies = std::make_shared<std::map<std::string, RelightCopy>>();
  (*copies)["finished-files/ptm-lrgb.ptm"] = {relightJson(ptm, options.relightMaxSide), options.relightMaxSide};
  (*copies)["finished-files/hsh2.rti"] = {relightJson(hsh, options.relightMaxSide), options.relightMaxSide};
  options.relightCopies = copies;
  const Report fromCopies = buildReport(none.carrier(), none, options);
  CHECK(fromCopies.html == fromFiles.html);

  // Copies made for another size are not used: the models are then read, here missing.
  options.relightMaxSide = 600;
  const Report otherSize = buildReport(none.carrier(), none, options);
  CHECK_FALSE(otherSize.relightable);
  CHECK(count(otherSize.html, "is not in this package or capture") == 2);
}

// A PTM (LRGB) of width x height whose bytes vary from texel to texel: no two blocks alike,
// so that averaging it down cannot make a smaller copy than its size says.
std::string variedPtm(int width, int height) {
  formats::PtmFile ptm;
  ptm.width = width;
  ptm.height = height;
  ptm.scale = {0.5, 0.5, 0.5, 1, 1, 1};
  ptm.bias = {128, 128, 128, 128, 128, 0};
  ptm.coefficients.resize(ptm.texels() * 6);
  ptm.rgb.resize(ptm.texels() * 3);
  for (std::size_t i = 0; i < ptm.coefficients.size(); ++i) ptm.coefficients[i] = static_cast<std::uint8_t>(i * 31 % 251);
  for (std::size_t i = 0; i < ptm.rgb.size(); ++i) ptm.rgb[i] = static_cast<std::uint8_t>(i * 13 % 256);
  return formats::serializePtm(ptm);
}

TEST_CASE("the page of a 3000x2000 capture keeps within the size budget with its models averaged down") {
  // The default two models at 3000x2000, their bytes varying from texel to texel (no two blocks
  // alike), and full-size pictures.
  const std::string ptm = variedPtm(3000, 2000);
  carrier::Carrier c = sampleCarrier();
  carrier::Step& fit = c.addStep("RtiFit", "1");
  fit.setParam("basis", "hsh2");
  carrier::Result r;
  r.step = fit.id;
  r.add("output").set("file", c.putFile(output("finished-files/hsh2.rti", "result", "RTI_HSH"))).set("kind", "hsh2");
  c.data.push_back(r);
  MemorySource source(c);
  source.files["finished-files/ptm-lrgb.ptm"] = ptm;
  source.files["finished-files/hsh2.rti"] = smallHsh(3000, 2000);
  source.files["assembly-files/spheres.png"] = png(3000, 2000);
  source.files["finished-files/normals.png"] = png(3000, 2000);
  source.files["finished-files/albedo.png"] = png(3000, 2000);
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  const Report page = buildReport(source.carrier(), source, options);
  REQUIRE(page.relightable);
  REQUIRE(page.picturesEmbedded == 3);
  INFO("page " << page.html.size() << " bytes, pictures " << pictureBytes(page.html));
  CHECK(page.html.size() - pictureBytes(page.html) <= kReportBudgetBytes);
  CHECK(page.html.size() <= kReportBudgetBytes);
  // Each model averaged by the smallest whole factor within kRelightModelBytes, 7 for both:
  // the PTM's 9 bytes a texel at 429x286 take 1.10 MB (at 6, 500x334 would take 1.503 MB),
  // the HSH's 12 bytes 1.47 MB.
  CHECK_THAT(page.html, Catch::Contains("\"basis\":\"ptm-lrgb\",\"format\":\"lrgb\",\"width\":429,\"height\":286"));
  CHECK_THAT(page.html, Catch::Contains("\"basis\":\"hsh2\",\"terms\":4,\"width\":429,\"height\":286"));

  // Without the limit on bytes (relightMaxSide alone, as before the budget: 1000x667), the
  // models alone would be over the budget: the test means it.
  options.relightModelsBytes = 0;
  const Report whole = buildReport(source.carrier(), source, options);
  CHECK(whole.html.size() > 3 * kReportBudgetBytes);
}

TEST_CASE("four models at 3000x2000 share the page's bytes and keep it within the size budget") {
  // Two PTMs and two HSHs, as a run with four --basis options lists them: each
  // gets a quarter of kRelightModelsBytes (0.75 MB); with 1.5 MB each the page was 8.5 MB.
  const std::string ptm = variedPtm(3000, 2000);
  carrier::Carrier c = sampleCarrier();
  std::map<std::string, std::string> models = {{"finished-files/ptm-lrgb.ptm", ptm}};
  for (const char* name : {"ptm-lrgb-copy", "hsh2", "hsh2-copy"}) {
    const std::string n = name;
    const bool isHsh = n.rfind("hsh", 0) == 0;
    carrier::Step& fit = c.addStep("RtiFit", "1");
    fit.setParam("basis", isHsh ? "hsh2" : "ptm-lrgb");
    const std::string path = "finished-files/" + n + (isHsh ? ".rti" : ".ptm");
    carrier::Result r;
    r.step = fit.id;
    r.add("output")
        .set("file", c.putFile(output(path, "result", isHsh ? "RTI_HSH" : "PTM_FORMAT_LRGB")))
        .set("kind", isHsh ? "hsh2" : "ptm-lrgb");
    c.data.push_back(r);
    models[path] = isHsh ? smallHsh(3000, 2000) : ptm;
  }
  MemorySource source(c);
  for (const auto& [path, bytes] : models) source.files[path] = bytes;
  REQUIRE(relightModelCount(source.carrier()) == 4);
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  const Report page = buildReport(source.carrier(), source, options);
  REQUIRE(page.relightable);
  INFO("page " << page.html.size() << " bytes, pictures " << pictureBytes(page.html));
  CHECK(page.html.size() <= kReportBudgetBytes);
  // Each within 0.75 MB by the smallest whole factor: the PTM's 9 bytes a texel by 9 (334x223,
  // 0.67 MB; by 8, 375x250 would take 0.84 MB), the HSH's 12 by 10 (300x200, 0.72 MB; by 9,
  // 334x223 would take 0.89 MB).
  CHECK(count(page.html, "\"basis\":\"ptm-lrgb\",\"format\":\"lrgb\",\"width\":334,\"height\":223") == 2);
  CHECK(count(page.html, "\"basis\":\"hsh2\",\"terms\":4,\"width\":300,\"height\":200") == 2);
}

TEST_CASE("every text from the carrier is escaped: hostile fields cannot inject markup") {
  MemorySource source(sampleCarrier());
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  CHECK(r.html.find("<img src=x") == std::string::npos);
  CHECK(r.html.find("<script>alert") == std::string::npos);
  CHECK(r.html.find("onerror=alert(1)>") == std::string::npos);
  CHECK_THAT(r.html, Catch::Contains("&lt;img src=x onerror=alert(1)&gt;"));
  // Exactly one script element is ours (plus the JSON data block when a PTM is present).
  CHECK(count(r.html, "<script") == 1);
}

TEST_CASE("missing files leave their section saying so, without failing the report") {
  MemorySource source(sampleCarrier());  // no file bytes at all
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  CHECK(r.picturesEmbedded == 0);
  CHECK_FALSE(r.relightable);
  CHECK_THAT(r.html, Catch::Contains("assembly-files/spheres.png: not found"));
  CHECK_THAT(r.html, Catch::Contains("is not in this package or capture"));
  CHECK(r.lightsPlotted == 5);
}

TEST_CASE("lights recorded without angles are plotted from their direction") {
  carrier::Carrier c = carrier::newCarrier("Dome", {});
  carrier::Step& s = c.addStep("LightsFromFile", "1");
  carrier::Result r;
  r.step = s.id;
  r.add("light").set("image", "f1").set("x", 0.0).set("y", 0.0).set("z", 1.0);     // zenith: centre
  r.add("light").set("image", "f2").set("x", 0.0).set("y", 1.0).set("z", 0.0);     // top of the rim
  r.add("light").set("image", "f3").set("x", "not a number").set("y", 0.0).set("z", 1.0);  // skipped
  c.data.push_back(r);
  MemorySource source(c);
  const Report rep = buildReport(source.carrier(), source, ReportOptions());
  CHECK(rep.lightsPlotted == 2);
  CHECK_THAT(rep.html, Catch::Contains("cx=\"180\" cy=\"180\" r=\"6\""));
  CHECK_THAT(rep.html, Catch::Contains("cx=\"180\" cy=\"30\" r=\"6\""));
}

TEST_CASE("a carrier without lights or fits still gives a page") {
  carrier::Carrier c = carrier::newCarrier("Empty", {});
  c.addStep("CaptureIngest", "1");
  MemorySource source(c);
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  CHECK(r.lightsPlotted == 0);
  CHECK_THAT(r.html, Catch::Contains("records no light directions"));
  CHECK_THAT(r.html, Catch::Contains("not run"));
}

TEST_CASE("the verification section lists each check, failures first in the summary") {
  MemorySource source(sampleCarrier());
  ReportOptions options;
  CHECK_THAT(buildReport(source.carrier(), source, options).html,
             Catch::Contains("No verification was run for this report"));
  options.verification = std::vector<VerificationCheck>{
      {"fixity: manifest-sha256.txt", true, "42 files match"},
      {"re-execution: s6 RtiFit", false, std::string("coefficients differ ") + kHostile}};
  const std::string html = buildReport(source.carrier(), source, options).html;
  CHECK(count(html, "<tr class=\"check\">") == 2);
  CHECK_THAT(html, Catch::Contains("1 of 2 checks failed."));
  CHECK_THAT(html, Catch::Contains("FAILED"));
  CHECK_THAT(html, Catch::Contains("42 files match"));
  CHECK(html.find("<script>alert") == std::string::npos);
}

TEST_CASE("each image's highlight confidence is shown: lights table, hemisphere plot and highlight table") {
  carrier::Carrier c = carrier::newCarrier("Highlights", {});
  for (int i = 1; i <= 3; ++i) {
    carrier::FileRecord f;
    f.path = "original-captures/IMG_000" + std::to_string(i) + ".dng";
    f.role = "original";
    f.size = 1;
    f.sha256 = std::string(64, 'a');
    c.putFile(f);
  }
  const std::string highlightStep = c.addStep("HighlightDetection", "2").id;
  const std::string lightStep = c.addStep("LightDirections", "2").id;
  carrier::Result hr;
  hr.step = highlightStep;
  hr.add("highlight").set("image", "f1").set("sphere", 0).set("x", 10.0).set("y", 20.0).set("flag", "ok")
      .set("confidence", 1.0);
  hr.add("highlight").set("image", "f2").set("sphere", 0).set("x", 11.0).set("y", 21.0).set("flag", "multiple")
      .set("confidence", 0.25).set("reason", std::string("another spot ") + kHostile);
  hr.add("highlight").set("image", "f3").set("sphere", 0).set("x", 12.0).set("y", 22.0).set("flag", "manual")
      .set("confidence", 1.0).set("reason", "given by hand: rim reflection");
  c.data.push_back(hr);
  carrier::Result lr;
  lr.step = lightStep;
  for (int i = 1; i <= 3; ++i)
    lr.add("light").set("image", "f" + std::to_string(i)).set("x", 0.0).set("y", 0.0).set("z", 1.0)
        .set("elevationDeg", 20.0 * i).set("azimuthDeg", 100.0 * i).set("source", "sphere 0");
  c.data.push_back(lr);
  MemorySource source(c);
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  // The plot: the light of the doubtful highlight ringed, its confidence in the tooltip.
  CHECK(count(r.html, "<circle class=\"light") == 3);
  CHECK(count(r.html, "<circle class=\"light doubtful\"") == 1);
  CHECK_THAT(r.html, Catch::Contains("highlight confidence 0.25"));
  CHECK_THAT(r.html, Catch::Contains("A red ring marks a light"));
  // The lights table has the column; the highlight table every highlight with flag and reason.
  CHECK_THAT(r.html, Catch::Contains("<th>highlight confidence</th>"));
  CHECK_THAT(r.html, Catch::Contains("Every highlight"));
  CHECK_THAT(r.html, Catch::Contains("given by hand: rim reflection"));
  // To check: the doubtful one and the manual one (flag not ok), with their confidence.
  CHECK_THAT(r.html, Catch::Contains("Highlights to check"));
  CHECK_THAT(r.html, Catch::Contains("multiple, confidence 0.25"));
  CHECK(r.html.find("<img src=x") == std::string::npos);
  // The highlight given by hand says so wherever a confidence would be (the carrier's 1 was not
  // measured): the list to check, the highlight table, the lights table and the tooltip.
  CHECK_THAT(r.html, Catch::Contains("manual, confidence by hand"));
  CHECK_THAT(r.html, Catch::Contains("<td>manual</td><td class=\"num\">by hand</td>"));
  CHECK_THAT(r.html, Catch::Contains("<td class=\"num\">-</td><td class=\"num\">by hand</td></tr>"));
  CHECK_THAT(r.html, Catch::Contains("IMG_0003.dng: elevation 60\u00b0, azimuth 300\u00b0, highlight confidence by hand"));
}

TEST_CASE("a sphere given by hand says by hand instead of its scores") {
  carrier::Carrier c = sampleCarrier();
  carrier::Result& lights = c.data.front();
  lights.add("sphere").set("index", 1).set("cx", 30.0).set("cy", 40.0).set("r", 6.0).set("confidence", 1.0)
      .set("evidence", 1.0).set("source", "manual");
  MemorySource source(c);
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  // The detected sphere keeps its figures; the one given by hand has none.
  CHECK_THAT(r.html, Catch::Contains("<td class=\"num\">5</td><td class=\"num\">0.9</td><td class=\"num\">-</td><td>detected</td>"));
  CHECK_THAT(r.html, Catch::Contains("<td class=\"num\">6</td><td class=\"num\">by hand</td><td class=\"num\">by hand</td><td>given by hand</td>"));
}

TEST_CASE("the page opens with the summary and the relighting view, steps and models in plain words") {
  carrier::Carrier c = sampleCarrier();
  c.header.rights = "CC BY 4.0, the museum";
  MemorySource source(std::move(c));
  source.files["finished-files/ptm-lrgb.ptm"] = smallPtm();
  ReportOptions options;
  options.verification = std::vector<VerificationCheck>{{"fixity", true, "42 files match"}, {"schema", true, ""}};
  const Report r = buildReport(source.carrier(), source, options);
  // Summary, viewer, then the plot, the detection and the rest.
  const std::size_t summary = r.html.find("<section id=\"summary\""), relight = r.html.find("<section id=\"relight\""),
                    lights = r.html.find("<section id=\"lights\""), detection = r.html.find("<section id=\"detection\""),
                    provenance = r.html.find("<section id=\"provenance\"");
  REQUIRE(summary != std::string::npos);
  REQUIRE(relight != std::string::npos);
  CHECK(summary < relight);
  CHECK(relight < lights);
  CHECK(lights < detection);
  CHECK(detection < provenance);
  const std::string head = r.html.substr(summary, relight - summary);
  CHECK_THAT(head, Catch::Contains("CC BY 4.0, the museum"));
  CHECK_THAT(head, Catch::Contains("photographer"));
  CHECK_THAT(head, Catch::Contains("5 originals"));
  CHECK_THAT(head, Catch::Contains("Canon EOS 5D"));
  CHECK_THAT(head, Catch::Contains("PASSED"));
  CHECK_THAT(head, Catch::Contains("Fit: PTM (LRGB): 30 dB"));
  // Each figure with its sentence: the PSNR in the summary, RMSE and PSNR in the fit table,
  // the sphere's rim (0.9; its moving highlight is not recorded here).
  CHECK_THAT(head, Catch::Contains("30 dB, <span class=\"ok explain\" title=\"Good: the model reproduces"));
  CHECK_THAT(head, Catch::Contains("below 25 dB worrying).\">good</span>"));
  CHECK_THAT(r.html, Catch::Contains("<th>what it means</th>"));
  CHECK_THAT(r.html, Catch::Contains("differs from the photograph by 4.5 of 255 levels (1.8 %)"));
  CHECK_THAT(r.html, Catch::Contains("<li>Sphere 1: <span class=\"ok explain\">Rim 0.9: the share of the circle's "
                                     "rim that is a clean edge. Good"));
  CHECK_THAT(head, Catch::Contains("<dt>spheres</dt><dd>1</dd>"));
  // Step names as people say them, the component kept in the timeline for the record.
  CHECK(r.html.find("s3 RtiFit (ptm-lrgb)") == std::string::npos);
  CHECK_THAT(r.html, Catch::Contains("Fit: PTM (LRGB) <span class=\"note\">(step s3, RtiFit v1)</span>"));
  // Spheres counted from 1 in the table, and the page says so.
  CHECK_THAT(r.html, Catch::Contains("<tr><td>1</td><td class=\"num\">10, 20</td>"));
  CHECK_THAT(r.html, Catch::Contains("Spheres are numbered from 1, as the command line names them"));
  // The viewer holds the model at its own resolution.
  CHECK_THAT(r.html, Catch::Contains("\"model\":\"ptm\",\"basis\":\"ptm-lrgb\""));
  CHECK_THAT(r.html, Catch::Contains("\"width\":8,\"height\":6,\"originalWidth\":8,\"originalHeight\":6"));
}

TEST_CASE("an HSH-only carrier is relightable in the page") {
  carrier::Carrier c = carrier::newCarrier("HSH only", {});
  carrier::Step& fit = c.addStep("RtiFit", "1");
  fit.setParam("basis", "hsh2");
  carrier::FileRecord model = output("finished-files/hsh2.rti", "result", "RTI_HSH");
  model.createdBy = fit.id;
  const std::string id = c.putFile(model);
  carrier::Result fr;
  fr.step = fit.id;
  fr.add("output").set("file", id).set("kind", "hsh2");
  c.data.push_back(fr);
  MemorySource source(std::move(c));
  source.files["finished-files/hsh2.rti"] = smallHsh(3, 2);
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  CHECK(r.relightable);
  CHECK_THAT(r.html, Catch::Contains("\"model\":\"hsh\",\"basis\":\"hsh2\""));
  CHECK(r.html.find("No model was fitted") == std::string::npos);
}

TEST_CASE("EXIF dates are shown in ISO 8601 as the page's other times") {
  carrier::Carrier c = sampleCarrier();
  int k = 0;
  for (carrier::FileRecord& f : c.files)
    if (f.role == "original") f.camera.push_back({"dateTimeOriginal", k++ == 0 ? "2026:01:02 08:30:00" : "2026:01:01 12:00:00"});
  MemorySource source(c);
  ReportOptions options;
  options.generatedAt = "2026-02-03T04:05:06Z";
  const Report r = buildReport(source.carrier(), source, options);
  // The summary's "taken" and the camera section's: earliest to latest, as ISO 8601 local
  // times (EXIF records no zone here); nowhere EXIF's colons in the date.
  CHECK(count(r.html, "2026-01-01T12:00:00 to 2026-01-02T08:30:00") == 2);
  CHECK(r.html.find("2026:01:0") == std::string::npos);
}

TEST_CASE("steps made per model have headings of their own: the two web copies say which model") {
  carrier::Carrier c = sampleCarrier();
  for (const char* model : {"ptm-lrgb", "hsh2"}) c.addStep("WebCopy", "4").setParam("model", model);
  MemorySource source(c);
  const Report r = buildReport(source.carrier(), source, ReportOptions());
  CHECK_THAT(r.html, Catch::Contains("Web copy of PTM (LRGB) <span class=\"note\">(step s5, WebCopy v4)</span>"));
  CHECK_THAT(r.html, Catch::Contains("Web copy of HSH order 2 <span class=\"note\">(step s6, WebCopy v4)</span>"));
  // Every step's heading is its own.
  std::vector<std::string> heads;
  const std::string open = "<div class=\"step-head\">";
  for (std::size_t at = r.html.find(open); at != std::string::npos; at = r.html.find(open, at + 1))
    heads.push_back(r.html.substr(at + open.size(), r.html.find(" <span", at) - at - open.size()));
  REQUIRE(heads.size() == c.process.size());
  std::sort(heads.begin(), heads.end());
  CHECK(std::adjacent_find(heads.begin(), heads.end()) == heads.end());
}
