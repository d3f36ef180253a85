// buildReport on carriers made in memory: what the page contains, what it escapes, and how it
// copes with missing files. Pictures and models given in memory, threads and the page's size
// budget: test_report_pictures_models.cpp.
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
