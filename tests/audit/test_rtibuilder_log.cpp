// RTIBuilder's log read as data (audit/rtibuilder_log.h). The expected values of the real log
// (tests/data/rtibuilder/Fisch.xml, RTIBuilder 2.0.2; source in that folder's README.md) were
// read from the file itself, each quoted beside its check; the other logs are written here.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "audit/rtibuilder_log.h"
#include "core/error.h"

using namespace surrogate;
using Catch::Contains;
namespace fs = std::filesystem;

namespace {

fs::path fisch() { return fs::path(SURROGATE_SOURCE_DIR) / "tests/data/rtibuilder/Fisch.xml"; }

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string errorOf(const fs::path& p) {
  try {
    audit::readRtiBuilderLog(p);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Input);
    CHECK(e.file() == p.string());
    return e.message();
  }
  FAIL("no error for " << p);
  return "";
}

const audit::LogSphere& sphereWithOrder(const audit::RtiBuilderLog& log, int order) {
  for (const audit::LogSphere& s : log.spheres)
    if (s.order == order) return s;
  FAIL("no sphere of order " << order);
  return log.spheres.front();
}

// The 36 photographs of the fish fossil capture as Surrogate names them.
audit::CaptureFacts fishCapture() {
  audit::CaptureFacts c;
  for (int i = 1; i <= 36; ++i) c.photographs.push_back("jpeg-exports/fish_fossil_" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".jpg");
  c.photographCount = 36;
  c.width = 2000, c.height = 1334, c.spheres = 2, c.basis = "hsh2";
  return c;
}

}  // namespace

TEST_CASE("the real RTIBuilder 2.0.2 log gives its project, author, host, dates and image size") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  CHECK(log.software == "RTIBuilder");
  CHECK(log.version == "2.0.2");  // "HSHfitter Path found : C:\RTIbuilder_v2_0_2\Fitters\..."
  CHECK_THAT(log.versionFrom, Contains("RTIbuilder_v2_0_2"));
  CHECK(log.projectName == "Fisch");                 // <xc:ProjectName>Fisch</xc:ProjectName>
  CHECK(log.author == "kacebe");                     // <xc:Author>kacebe</xc:Author>
  CHECK(log.host == "c-gv-bruhn");                   // <xc:Host>c-gv-bruhn</xc:Host>
  CHECK(log.operatingSystem == "Windows 10 x86");    // <xc:Info ... OperatingSystem="Windows 10 x86"
  CHECK(log.created == "2017/4/5 9:49:21");          // <xc:CreationDate>
  CHECK(log.modified == "2017/4/5 9:49:21");         // <xc:LastModificationDate>
  CHECK(log.imageWidth == 2000);                     // <xc:Info2 NAME="Image width" VALUE="2000.0"/>
  CHECK(log.imageHeight == 1334);                    // <xc:Info2 NAME="Image height" VALUE="1334.0"/>
}

TEST_CASE("the real log's 36 original images are all used and none is excluded") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  REQUIRE(log.images.size() == 36);  // fileGrp USE="Original image files"
  CHECK(log.images.front().path == "jpeg-exports\\fish_fossil_01.jpg");
  CHECK(log.images.back().path == "jpeg-exports\\fish_fossil_36.jpg");
  REQUIRE(log.usedImages.size() == 36);  // each "Images for HighDetection" group has 36 fptr
  CHECK(log.usedImages.front() == "fish_fossil_01.jpg");
  CHECK(log.excludedImages.empty());
  CHECK(log.reportedImagesUsed == 72);  // "Number of images used : 72" (36 on each sphere)
  CHECK(log.highlightMethod == "HLTDETECTION");  // <xc:process ... TYPE="HLTDETECTION">
}

TEST_CASE("the real log's two spheres with their detection and highlight parameters, highlights and lights") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  REQUIRE(log.spheres.size() == 2);
  // <xc:sphere ID="4f32a1f3-..." Order="0" r="85.0" x="149.0" y="1169.0"/>
  const audit::LogSphere& lower = sphereWithOrder(log, 0);
  CHECK(lower.id == "4f32a1f3-7376-4776-b310-d7e11e837ced");
  CHECK(lower.x == 149.0);
  CHECK(lower.y == 1169.0);
  CHECK(lower.radius == 85.0);
  // BallDetectionInput: BEGIN="x:56.0 y:1046.0" END="x:256.0 y:1270.0" algorithm="0"
  // binarize="false" hough="true", on the 10 fptr of group bae4d3cd.
  REQUIRE(lower.detection.size() == 4);
  CHECK(lower.detection[0].name == "search area");
  CHECK(lower.detection[0].value == "x:56.0 y:1046.0 to x:256.0 y:1270.0");
  CHECK(lower.detection[1].name == "algorithm");
  CHECK(lower.detection[1].value == "0");
  CHECK(lower.detection[2].value == "false");  // binarize
  CHECK(lower.detection[3].value == "true");   // hough
  CHECK(lower.detectionImages == 10);
  // The highlight detection's input area: BEGIN="x:64.0 y:1084.0" END="x:234.0 y:1254.0"
  // threshold="250".
  REQUIRE(lower.highlightDetection.size() == 2);
  CHECK(lower.highlightDetection[0].value == "x:64.0 y:1084.0 to x:234.0 y:1254.0");
  CHECK(lower.highlightDetection[1].name == "threshold");
  CHECK(lower.highlightDetection[1].value == "250");
  // computedData lists no highlights for this sphere; dataSec's Data 0cb383b7 (its
  // Ref_HighLights) does: x1 107.9881, y1 1143.619, img1 81fb5616 (fish_fossil_01.jpg).
  REQUIRE(lower.highlights.size() == 36);
  CHECK(lower.highlights[0].image == "fish_fossil_01.jpg");
  CHECK(lower.highlights[0].x == 107.9881);
  CHECK(lower.highlights[0].y == 1143.619);
  REQUIRE(lower.lightDirections.size() == 36);
  // <xc:lightdirection ImageID="81fb5616-..." x="-0.79459935" y="0.49175268" z="0.35607743"/>
  CHECK(lower.lightDirections[0].image == "fish_fossil_01.jpg");
  CHECK(lower.lightDirections[0].x == -0.79459935);
  CHECK(lower.lightDirections[0].z == 0.35607743);

  // <xc:sphere ID="9dcfef6e-..." Order="1" r="85.0" x="168.0" y="208.0"/>
  const audit::LogSphere& upper = sphereWithOrder(log, 1);
  CHECK(upper.x == 168.0);
  CHECK(upper.y == 208.0);
  REQUIRE(upper.highlights.size() == 36);
  // <xc:highlight ImageID="81fb5616-..." x="124.689316" y="183.15533"/>
  CHECK(upper.highlights[0].x == 124.689316);
  CHECK(upper.highlights[0].y == 183.15533);
  // the last: ImageID="7fda8eac-..." (fish_fossil_36.jpg) x="-0.26073223" y="0.6523089" z="0.71169645"
  REQUIRE(upper.lightDirections.size() == 36);
  CHECK(upper.lightDirections[35].image == "fish_fossil_36.jpg");
  CHECK(upper.lightDirections[35].y == 0.6523089);
}

TEST_CASE("the real log's fitter is hshfitter of order 2 on 4 threads, which succeeded") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  REQUIRE(log.fitter);
  // "Command line to execute : C:\RTIbuilder_v2_0_2\Fitters\HSHfitter\hshfitter.exe
  //  C:\tmp\rti\fish_fossil-data-set_2000\assembly-files\Fisch.lp 2 4
  //  C:\tmp\rti\fish_fossil-data-set_2000\finished-files\Fisch_2000.rti"
  CHECK(log.fitter->name == "hshfitter");
  CHECK(log.fitter->kind == "HSH");
  CHECK(log.fitter->order == 2);
  CHECK(log.fitter->threads == 4);
  CHECK(log.fitter->basis == "hsh2");
  CHECK(log.fitter->lightFile == "C:\\tmp\\rti\\fish_fossil-data-set_2000\\assembly-files\\Fisch.lp");
  CHECK(log.fitter->output == "C:\\tmp\\rti\\fish_fossil-data-set_2000\\finished-files\\Fisch_2000.rti");
  CHECK(log.fitter->options.empty());
  CHECK(log.fitter->result == "Fitter return ok!HSH was generated successfully");
  CHECK(log.fitter->succeeded);
  CHECK(log.events.size() == 13);
  CHECK(log.events[1].level == "WARNING");
  CHECK(log.events[1].text == "Unable to automatically locate the Crop folder definition!");
  // Files written: the edge, median and blend images, the light file, the model.
  REQUIRE(log.outputs.size() == 8);
  CHECK(log.outputs[0].path == "assembly-files\\Fisch_edge1.jpg");
  CHECK(log.outputs[0].use == "Stage1 and Stage2 images");
  CHECK(log.outputs[5].path == "assembly-files\\Fisch_blend2.jpg");
  CHECK(log.outputs[7].use == "fitter output");
}

TEST_CASE("what the reader does not classify is kept as name and value") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  auto value = [&](const std::string& name) {
    for (const audit::LogItem& i : log.other)
      if (i.name == name) return i.value;
    return std::string("(absent)");
  };
  CHECK(value("ProjectPath") == "C:\\tmp\\rti\\fish_fossil-data-set_2000");  // Info2 NAME="ProjectPath"
  CHECK(value("Info@MemoryAvailable") == "89407488");
  CHECK(value("Header@UUID") == "01c78769-73d2-401c-80fd-66852e541221");
  CHECK(value("Header/Timestamp") == "4");
}

TEST_CASE("the log's text and JSON for surrogate info") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  const std::string text = log.toText();
  CHECK_THAT(text, Contains(": RTIBuilder log (RTIBuilder 2.0.2)\n"));
  CHECK_THAT(text, Contains("  project:     Fisch, by kacebe on c-gv-bruhn (Windows 10 x86)\n"));
  CHECK_THAT(text, Contains("  images:      36 listed, 36 used, 0 excluded, 2000x1334\n"));
  CHECK_THAT(text, Contains("  sphere 1:    centre 149, 1169, radius 85; found on 10 images (search area x:56.0 y:1046.0 to "
                            "x:256.0 y:1270.0, algorithm 0, binarize false, hough true)\n"));
  CHECK_THAT(text, Contains("  fitter:      hshfitter, HSH order 2 (hsh2), 4 threads\n"));
  const std::string json = log.toJson();
  CHECK_THAT(json, Contains("\"kind\":\"rtibuilder-log\""));
  CHECK_THAT(json, Contains("\"basis\":\"hsh2\""));
  CHECK_THAT(json, Contains("\"reportedImagesUsed\":72"));
}

TEST_CASE("a log matching the capture has no discrepancy and each difference is named") {
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(fisch());
  CHECK(audit::logDiscrepancies(log, fishCapture()).empty());
  // Originals (raw) of the same shots match by name without extension, ignoring case.
  audit::CaptureFacts raw = fishCapture();
  for (std::string& p : raw.photographs) p = "original-captures/FISH_FOSSIL_" + p.substr(25, 2) + ".DNG";
  CHECK(raw.photographs[0] == "original-captures/FISH_FOSSIL_01.DNG");
  CHECK(audit::logDiscrepancies(log, raw).empty());

  audit::CaptureFacts other = fishCapture();
  other.photographs.erase(other.photographs.begin());  // fish_fossil_01 gone
  other.photographs.push_back("jpeg-exports/fish_fossil_37.jpg");
  other.photographCount = 37;
  other.width = 4000, other.height = 2668, other.spheres = 1, other.basis = "ptm-lrgb";
  const std::vector<std::string> d = audit::logDiscrepancies(log, other);
  REQUIRE(d.size() == 6);
  CHECK(d[0] == "the log used 1 image(s) that are not among the capture's photographs: fish_fossil_01.jpg");
  CHECK(d[1] == "1 photograph(s) of the capture are not in the log: jpeg-exports/fish_fossil_37.jpg");
  CHECK(d[2] == "the log used 36 images; the capture has 37 photographs");
  CHECK(d[3] == "the log's images are 2000x1334; the photographs are 4000x2668");
  CHECK(d[4] == "the log found 2 sphere(s); Surrogate found 1");
  CHECK(d[5] == "the log's fit is hsh2; the prior model audited is ptm-lrgb");
}

TEST_CASE("a log whose images were left out lists them as excluded") {
  std::string text = readAll(fisch());
  // Drop fish_fossil_05 (9c38356e-...) from both highlight detection groups.
  const std::string fptr = "            <xc:fptr>9c38356e-055a-4aee-bf25-69edbc45db6f</xc:fptr>\n";
  const auto hd = text.find("USE=\"Images for HighDetection\"");
  REQUIRE(hd != std::string::npos);
  for (auto at = text.find(fptr, hd); at != std::string::npos; at = text.find(fptr, at)) text.erase(at, fptr.size());
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(writeFile("excluded.xml", text));
  CHECK(log.usedImages.size() == 35);
  CHECK(log.excludedImages == std::vector<std::string>{"fish_fossil_05.jpg"});
  const std::vector<std::string> d = audit::logDiscrepancies(log, fishCapture());
  CHECK(std::find(d.begin(), d.end(), "the log lists 1 image(s) it did not use: fish_fossil_05.jpg") != d.end());
}

TEST_CASE("a malformed log is refused naming the file") {
  const std::string text = readAll(fisch()).substr(0, 3000);
  CHECK_THAT(errorOf(writeFile("truncated.xml", text)), Contains("is not well-formed XML"));
}

TEST_CASE("an XML file that is not an RTIBuilder log is refused saying what one is") {
  const fs::path carrier = writeFile("carrier.xml", "<?xml version=\"1.0\"?>\n<carrier version=\"1\"/>\n");
  CHECK_FALSE(audit::looksLikeRtiBuilderLog(carrier));
  const std::string m = errorOf(carrier);
  CHECK_THAT(m, Contains("is not an RTIBuilder log: the XML document RTIBuilder keeps in a project's assembly-files/"));
  CHECK_THAT(m, Contains("its root element is <carrier> in no namespace"));
  // The right name in another namespace is not one either.
  const fs::path other = writeFile("other.xml", "<XMLCarrier xmlns=\"urn:example\"/>");
  CHECK(audit::looksLikeRtiBuilderLog(other));
  CHECK_THAT(errorOf(other), Contains("its root element is <XMLCarrier> in urn:example"));
}

TEST_CASE("a log larger than any RTIBuilder writes is refused unread, as is one of too many elements") {
  const fs::path huge = fs::temp_directory_path() / "huge.xml";
  { std::ofstream(huge) << "<XMLCarrier xmlns=\"http://alba.di.uminho.pt/XMLCarrier\">"; }
  fs::resize_file(huge, audit::kMaxLogBytes + 1);  // sparse: nothing is written
  CHECK_THAT(errorOf(huge), Contains("larger than any RTIBuilder log"));

  std::string many = "<XMLCarrier xmlns=\"http://alba.di.uminho.pt/XMLCarrier\"><Log>";
  for (std::size_t i = 0; i < audit::kMaxLogElements; ++i) many += "<e/>";
  many += "</Log></XMLCarrier>";
  CHECK_THAT(errorOf(writeFile("many.xml", many)), Contains("elements, more than Surrogate reads"));
}

TEST_CASE("control characters and bad bytes in a log are escaped when read") {
  const std::string text = std::string("<XMLCarrier xmlns=\"http://alba.di.uminho.pt/XMLCarrier\" xmlns:xc=\"") +
                           audit::kRtiBuilderLogNamespace + "\"><xc:Header><xc:ProjectName>A\x7f[31mB\xc2\x85" "C</xc:ProjectName>"
                           "</xc:Header><xc:Log><xc:event LEVEL=\"INFO\">line\nbreak</xc:event></xc:Log></XMLCarrier>";
  const audit::RtiBuilderLog log = audit::readRtiBuilderLog(writeFile("escape.xml", text));
  CHECK(log.projectName == "A\\x7F[31mB\\xC2\\x85C");  // DEL and C1 NEL, which XML 1.0 allows
  REQUIRE(log.events.size() == 1);
  CHECK(log.events[0].text == "line\\x0Abreak");
  CHECK(log.spheres.empty());
  CHECK_FALSE(log.fitter);
}
