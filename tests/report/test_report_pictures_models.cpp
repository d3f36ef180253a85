// buildReport's pictures and models: given in memory as display and interactive copies they
// make the page their files make, the page is the same on 1 or 2 threads, and a 3000x2000
// capture's page keeps within the size budget with its models averaged down.
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
#include "report_build_support.h"

using namespace surrogate;
using namespace surrogate::report;
using namespace report_build;
using report_test::pictureBytes;

namespace {

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

}  // namespace

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
