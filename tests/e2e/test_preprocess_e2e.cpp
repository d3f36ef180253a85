// Pre-processing as recorded steps (issue 8): `surrogate run --wb-region ... --crop ...
// --resize ...` fits only the balanced, cropped, reduced area, records each step with its
// parameters and results, leaves the originals untouched, and re-execution of the carrier
// reproduces the fitted files bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "carrier/carrier.h"
#include "e2e_support.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "run/plan.h"

namespace fs = std::filesystem;
using namespace surrogate;

namespace {

// The files a capture brings (never written by the tool).
std::map<std::string, std::string> originals(const fs::path& capture) {
  std::map<std::string, std::string> out;
  for (const char* dir : {"original-captures", "jpeg-exports"})
    for (const auto& [path, hash] : e2e::snapshot(capture / dir)) out[std::string(dir) + "/" + path] = hash;
  return out;
}

const carrier::Step* stepOf(const carrier::Carrier& c, const std::string& component) {
  for (const carrier::Step& s : c.process)
    if (s.component == component) return &s;
  return nullptr;
}

std::string valueOf(const carrier::Carrier& c, const std::string& component, const std::string& name) {
  const carrier::Step* s = stepOf(c, component);
  REQUIRE(s != nullptr);
  const carrier::Result* r = c.findResult(s->id);
  REQUIRE(r != nullptr);
  for (const carrier::DataItem* v : r->itemsOf("value"))
    if (v->get("name") == name) return *v->get("value");
  FAIL("no value " << name << " in the result of " << component);
  return "";
}

// The pre-processing steps' results without times (they differ between runs).
std::string preprocessingResults(const carrier::Carrier& c) {
  std::string out;
  for (const char* component : {"WhiteBalance", "Crop", "Resize"}) {
    const carrier::Step* s = stepOf(c, component);
    if (!s) continue;
    const carrier::Result* r = c.findResult(s->id);
    REQUIRE(r != nullptr);
    for (const carrier::DataItem& i : r->items) {
      out += i.element;
      for (const auto& [k, v] : i.attributes) out += " " + k + "=" + v;
      out += "\n";
    }
  }
  return out;
}

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

}  // namespace

TEST_CASE("crop, resize and grey-region white balance: the fit covers only that area, each step is recorded, originals untouched, re-execution matches") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("preprocess"), 10);
  const auto before = originals(capture);
  const e2e::CommandResult r = e2e::surrogate(
      "run " + e2e::quote(capture) +
      " --quiet --threads 2 --source export --wb-region 20,230,60,40 --crop 40,30,300,200 --resize 0.5");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(originals(capture) == before);

  // The fitted files have the cropped, halved size.
  const formats::PtmFile ptm = formats::readPtm(capture / "finished-files/ptm-lrgb.ptm");
  CHECK(ptm.width == 150);
  CHECK(ptm.height == 100);
  const formats::HshFile hsh = formats::readRti(capture / "finished-files/hsh2.rti");
  CHECK(hsh.width == 150);
  CHECK(hsh.height == 100);

  // The process list: light estimation, then white balance, crop, resize, then the fits.
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  std::vector<std::string> order;
  for (const carrier::Step& s : c.process) order.push_back(s.component);
  const auto at = [&](const char* name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
  CHECK(at("LightDirections") < at("WhiteBalance"));
  CHECK(at("WhiteBalance") < at("Crop"));
  CHECK(at("Crop") < at("Resize"));
  CHECK(at("Resize") < at("RtiFit"));
  CHECK(stepOf(c, "WhiteBalance")->param("mode") == "region");
  CHECK(stepOf(c, "WhiteBalance")->param("region") == "20,230,60,40");
  CHECK(stepOf(c, "WhiteBalance")->param("outputSpace") == "srgb");
  CHECK(stepOf(c, "Crop")->param("rectangle") == "40,30,300,200");
  CHECK(stepOf(c, "Resize")->param("factor") == "0.5");
  CHECK(stepOf(c, "Resize")->param("filter") == "area");
  CHECK(valueOf(c, "Crop", "rectangle") == "40,30,300,200");
  CHECK(valueOf(c, "Resize", "outputSize") == "150x100");

  // The gains, computed here independently: per image the region's mean linear R, G, B; the
  // median over the images; G / R and G / B.
  std::vector<double> means[3];
  const carrier::Step* ingest = stepOf(c, "CaptureIngest");
  for (const carrier::DataItem* in : c.findResult(ingest->id)->itemsOf("input")) {
    if (in->get("kind") != std::string("image")) continue;
    const Image im = image::decodeImage(capture / c.findFile(*in->get("file"))->path, image::RawDecodeSettings{});
    double sum[3] = {0, 0, 0};
    for (int y = 230; y < 270; ++y)
      for (int x = 20; x < 80; ++x)
        for (int ch = 0; ch < 3; ++ch) sum[ch] += srgbToLinear(im.at(x, y, ch) / 65535.0);
    for (int ch = 0; ch < 3; ++ch) means[ch].push_back(sum[ch] / (60 * 40));
  }
  REQUIRE(means[0].size() == 10);
  const double gainR = median(means[1]) / median(means[0]);
  const double gainB = median(means[1]) / median(means[2]);
  CHECK(std::stod(valueOf(c, "WhiteBalance", "gainR")) == Approx(gainR).epsilon(1e-9));
  CHECK(std::stod(valueOf(c, "WhiteBalance", "gainG")) == 1.0);
  CHECK(std::stod(valueOf(c, "WhiteBalance", "gainB")) == Approx(gainB).epsilon(1e-9));

  // The exports were processed outside Surrogate: flagged on every input and in the log.
  const carrier::Result* decode = c.findResult(stepOf(c, "ImageDecode")->id);
  int flagged = 0;
  for (const carrier::DataItem* v : decode->itemsOf("imageValue"))
    flagged += v->get("name") == std::string("unrecordedProcessing");
  CHECK(flagged == 10);
  bool warned = false;
  for (const carrier::LogEntry& e : c.log)
    warned = warned || (e.level == "warning" && e.text.find("processed by other software") != std::string::npos);
  CHECK(warned);

  // Re-execution of the recorded process list elsewhere, with another thread count: the same
  // pre-processing results and the same fitted bytes.
  const fs::path again = e2e::freshDir("preprocess-replay") / "capture";
  fs::create_directories(again);
  for (const char* dir : {"original-captures", "jpeg-exports"})
    fs::copy(capture / dir, again / dir, fs::copy_options::recursive);
  pipeline::RunSettings settings;
  settings.threads = 1;
  settings.memoryBudget = std::size_t(8) << 20;  // forces several bands
  const carrier::Carrier replayed =
      run::replayCarrier(again, c, settings, again / "assembly-files/carrier.xml");
  CHECK(preprocessingResults(replayed) == preprocessingResults(c));
  for (const char* f : {"finished-files/ptm-lrgb.ptm", "finished-files/hsh2.rti", "finished-files/normals.png"}) {
    INFO(f);
    CHECK(e2e::bytesOf(again / f) == e2e::bytesOf(capture / f));
  }
}

TEST_CASE("crop auto fits the largest rectangle clear of the detected spheres") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("crop-auto"), 8);
  const e2e::CommandResult r =
      e2e::surrogate("run " + e2e::quote(capture) + " --quiet --basis ptm-lrgb --crop auto --wb multipliers:1.25,1,0.8");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(stepOf(c, "Crop")->param("method") == "auto");
  CHECK(valueOf(c, "WhiteBalance", "gainR") == "1.25");
  CHECK(valueOf(c, "WhiteBalance", "gainB") == "0.8");  // the shortest text that reads back (core/text.h)
  int x, y, w, h;
  REQUIRE(std::sscanf(valueOf(c, "Crop", "rectangle").c_str(), "%d,%d,%d,%d", &x, &y, &w, &h) == 4);
  const formats::PtmFile ptm = formats::readPtm(capture / "finished-files/ptm-lrgb.ptm");
  CHECK(ptm.width == w);
  CHECK(ptm.height == h);
  CHECK(long(w) * h >= 400L * 300 / 4);  // one sphere of radius 45 leaves most of the frame
  int spheres = 0;
  for (const carrier::Result& res : c.data)
    for (const carrier::DataItem* s : res.itemsOf("sphere")) {
      ++spheres;
      const double cx = s->number("cx"), cy = s->number("cy"), radius = s->number("r");
      const double nx = std::clamp(cx, double(x), double(x + w - 1));
      const double ny = std::clamp(cy, double(y), double(y + h - 1));
      CHECK(std::hypot(nx - cx, ny - cy) > radius);
    }
  CHECK(spheres >= 1);
}

TEST_CASE("bad pre-processing options are usage errors naming the option") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("preprocess-bad"), 8);
  struct Case {
    const char* options;
    const char* named;
  };
  // Checked before anything runs.
  for (const Case& k : {Case{"--crop 0,0,0,10", "--crop"}, Case{"--crop 10,10,-5,20", "--crop"},
                        Case{"--wb multipliers:1,-1,1", "--wb"}, Case{"--wb multipliers:1,0,1", "--wb"},
                        Case{"--resize 0", "--resize"}, Case{"--resize 2", "--resize"},
                        Case{"--wb-region 1,2,3", "--wb-region"}, Case{"--output-space xyz", "--output-space"}}) {
    INFO(k.options);
    const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet " + k.options);
    INFO(r.output);
    CHECK(r.exitCode == 2);
    CHECK(r.output.find(k.named) != std::string::npos);
  }
  // Checked against the images' size when the step runs.
  for (const Case& k : {Case{"--crop 350,250,100,100", "--crop"}, Case{"--wb-region 390,10,20,20", "--wb-region"},
                        Case{"--resize 500x100", "--resize"}}) {
    INFO(k.options);
    const e2e::CommandResult r =
        e2e::surrogate("run " + e2e::quote(capture) + " --quiet --source export --basis ptm-lrgb " + k.options);
    INFO(r.output);
    CHECK(r.exitCode == 2);
    CHECK(r.output.find(k.named) != std::string::npos);
    CHECK(r.output.find("400x300") != std::string::npos);
  }
}

TEST_CASE("crop auto on a dome capture without spheres keeps the full frame and says so") {
  const fs::path first = e2e::smallCapture(e2e::freshDir("dome-lights"), 8);
  REQUIRE(e2e::surrogate("lights " + e2e::quote(first) + " -o " + e2e::quote(first / "dome.lp") + " --quiet").exitCode == 0);
  const fs::path capture = e2e::smallCapture(e2e::freshDir("dome-crop"), 8);
  fs::copy_file(first / "dome.lp", capture / "dome.lp");
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --lp dome.lp --quiet --basis ptm-lrgb --crop auto");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(stepOf(c, "SphereDetection") == nullptr);
  CHECK(valueOf(c, "Crop", "rectangle") == "0,0,400,300");
  bool warned = false;
  for (const carrier::LogEntry& e : c.log) warned = warned || e.text.find("keeps the full frame") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("option --wb as-shot refuses camera raws decoded without the as-shot multipliers") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("wb-as-shot"), 8);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) +
                                              " --quiet --basis ptm-lrgb --wb as-shot --raw whiteBalance=none");
  INFO(r.output);
  CHECK(r.exitCode == 2);
  CHECK(r.output.find("--wb as-shot") != std::string::npos);
  CHECK(r.output.find("whiteBalance=camera") != std::string::npos);
}

TEST_CASE("a JPEG original whose XMP records an editing history is flagged as processed outside, its XMP kept") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("xmp-history"), 8);
  fs::remove_all(capture / "original-captures");  // a JPEG-only capture: the JPEGs are the originals
  // Insert an XMP packet (APP1 segment) with a Photoshop editing history after the SOI marker.
  const fs::path edited = capture / "jpeg-exports/IMG_0003.jpg";
  const std::string jpeg = e2e::bytesOf(edited);
  REQUIRE(jpeg.substr(0, 2) == "\xFF\xD8");
  const std::string packet =
      "<?xpacket begin=\"\xEF\xBB\xBF\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?>"
      "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"><rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\">"
      "<rdf:Description rdf:about=\"\" xmlns:xmpMM=\"http://ns.adobe.com/xap/1.0/mm/\" "
      "xmlns:stEvt=\"http://ns.adobe.com/xap/1.0/sType/ResourceEvent#\"><xmpMM:History><rdf:Seq>"
      "<rdf:li rdf:parseType=\"Resource\"><stEvt:action>saved</stEvt:action>"
      "<stEvt:softwareAgent>Adobe Photoshop</stEvt:softwareAgent></rdf:li></rdf:Seq></xmpMM:History>"
      "</rdf:Description></rdf:RDF></x:xmpmeta><?xpacket end=\"w\"?>";
  const std::string payload = std::string("http://ns.adobe.com/xap/1.0/") + '\0' + packet;
  const std::size_t length = payload.size() + 2;
  std::string segment = "\xFF\xE1";
  segment += static_cast<char>(length >> 8);
  segment += static_cast<char>(length & 0xFF);
  {
    std::ofstream out(edited, std::ios::binary | std::ios::trunc);
    out << jpeg.substr(0, 2) << segment << payload << jpeg.substr(2);
  }
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --basis ptm-lrgb");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  int flaggedFiles = 0;
  for (const carrier::FileRecord& f : c.files) {
    if (f.role != "original") continue;
    INFO(f.path);
    CHECK(f.unrecordedProcessing == (f.path == "jpeg-exports/IMG_0003.jpg"));
    flaggedFiles += f.unrecordedProcessing;
    if (f.unrecordedProcessing) CHECK(f.xmp.find("Adobe Photoshop") != std::string::npos);
  }
  CHECK(flaggedFiles == 1);
  const carrier::Result* decode = c.findResult(stepOf(c, "ImageDecode")->id);
  int flaggedInputs = 0;
  for (const carrier::DataItem* v : decode->itemsOf("imageValue"))
    flaggedInputs += v->get("name") == std::string("unrecordedProcessing");
  CHECK(flaggedInputs == 1);
}

TEST_CASE("a package made with crop, resize and white balance verifies by re-execution") {
  const fs::path dir = e2e::freshDir("preprocess-pack");
  const fs::path capture = e2e::smallCapture(dir, 8);
  const e2e::CommandResult packed =
      e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(dir / "bag") +
                     " --quiet --basis ptm-lrgb --wb-region 20,230,60,40 --crop 40,30,300,200 --resize 0.5");
  INFO(packed.output);
  REQUIRE(packed.exitCode == 0);
  const e2e::CommandResult verified = e2e::surrogate("verify " + e2e::quote(dir / "bag") + " --reexecute");
  INFO(verified.output);
  CHECK(verified.exitCode == 0);
  for (const char* step : {"WhiteBalance", "Crop", "Resize", "RtiFit"})
    CHECK(verified.output.find(std::string(".") + step + " ") != std::string::npos);
}

TEST_CASE("re-execution follows the carrier's order of pre-processing steps, not a fixed one") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("preprocess-order"), 8);
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) +
                                              " --quiet --source export --basis ptm-lrgb --crop 40,30,300,200 --resize 0.5");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  carrier::Carrier c = carrier::loadCarrier(capture / "assembly-files/carrier.xml");
  CHECK(valueOf(c, "Crop", "inputSize") == "400x300");
  // Resize first, then crop in the reduced frame: the same area at half size.
  auto crop = std::find_if(c.process.begin(), c.process.end(), [](const carrier::Step& s) { return s.component == "Crop"; });
  auto resize = std::find_if(c.process.begin(), c.process.end(), [](const carrier::Step& s) { return s.component == "Resize"; });
  REQUIRE(crop + 1 == resize);
  crop->setParam("rectangle", "20,15,150,100");
  std::iter_swap(crop, resize);
  const fs::path again = e2e::freshDir("preprocess-order-replay") / "capture";
  fs::create_directories(again);
  for (const char* dir : {"original-captures", "jpeg-exports"}) fs::copy(capture / dir, again / dir, fs::copy_options::recursive);
  const carrier::Carrier replayed = run::replayCarrier(again, c, pipeline::RunSettings{});
  CHECK(valueOf(replayed, "Resize", "inputSize") == "400x300");
  CHECK(valueOf(replayed, "Crop", "inputSize") == "200x150");
  const formats::PtmFile ptm = formats::readPtm(again / "finished-files/ptm-lrgb.ptm");
  CHECK(ptm.width == 150);
  CHECK(ptm.height == 100);
}
