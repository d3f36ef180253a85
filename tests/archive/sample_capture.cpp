#include "sample_capture.h"

#include <fstream>
#include <random>
#include <string>

#include "carrier/carrier.h"
#include "core/digest.h"

namespace samplecapture {

namespace fs = std::filesystem;
using namespace surrogate;

namespace {
std::string bytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(rng() & 0xff);
  return s;
}

carrier::FileRecord record(const fs::path& capture, const std::string& rel, const std::string& role,
                           const std::string& format, const std::string& content) {
  fs::create_directories((capture / rel).parent_path());
  std::ofstream(capture / rel, std::ios::binary) << content;
  carrier::FileRecord f;
  f.path = rel;
  f.role = role;
  f.size = content.size();
  f.sha256 = digestFile(capture / rel).sha256;
  f.format = format;
  return f;
}
}  // namespace

fs::path make(const fs::path& dir) {
  const fs::path capture = dir / "capture";
  fs::create_directories(capture);
  carrier::Carrier c = carrier::newCarrier("Stela 12 & <friends>", {{"Ana Silva", "photographer"}, {"Bo Chen", "conservator"}});
  c.header.meta = {{"Source-Organization", "Museum of Tests"},
                   {"External-Identifier", "INV-42"},
                   {"Contact-Name", "Ana Silva"}};
  std::vector<std::string> originals;
  for (int i = 1; i <= 3; ++i) {
    const std::string stem = "IMG_000" + std::to_string(i);
    carrier::FileRecord raw = record(capture, "original-captures/" + stem + ".dng", "original", "DNG",
                                     bytes(20000 + i, i));
    raw.mediaType = "image/x-adobe-dng";
    raw.imageSize = std::make_pair(40, 30);
    raw.camera = {{"make", "Canon"}, {"model", "EOS 5D Mark IV"}, {"serial", "0123456789"},
                  {"lens", "EF100mm f/2.8L"}, {"iso", "100"},
                  {"dateTimeOriginal", "2026:01:01 12:00:0" + std::to_string(i)}};
    raw.xmp = "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"/>";
    const std::string rawId = c.putFile(raw);
    originals.push_back(rawId);
    carrier::FileRecord jpg = record(capture, "jpeg-exports/" + stem + ".jpg", "export", "JPEG", bytes(5000 + i, 10 + i));
    jpg.mediaType = "image/jpeg";
    jpg.puid = "fmt/43";
    jpg.pairedWith = rawId;
    jpg.unrecordedProcessing = true;
    c.putFile(jpg);
  }
  c.putFile(record(capture, "original-captures/IMG_0001.xmp", "sidecar", "XMP", "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"/>"));

  carrier::Step& ingest = c.addStep("CaptureIngest", "1");
  ingest.description = "hash and read the originals";
  ingest.setParam("source", "auto");
  ingest.interventions.push_back({"exclude-image", "original-captures/IMG_0003.dng", "", "Bo Chen",
                                  "2026-01-02T10:00:00Z", "the flash did not fire"});
  const std::string ingestId = ingest.id;
  carrier::Step& fit = c.addStep("RtiFit", "2");  // (invalidates `ingest`)
  const std::string fitId = fit.id;
  fit.algorithm = "PTM LRGB least squares";
  fit.setParam("basis", "ptm-lrgb");
  fit.setParam("quote", "it's \"quoted\"");

  carrier::FileRecord lp = record(capture, "assembly-files/lights.lp", "assembly", "LP", "2\nIMG_0001.jpg 0 0 1\nIMG_0002.jpg 0.5 0 0.86\n");
  lp.createdBy = ingestId;
  const std::string lpId = c.putFile(lp);
  carrier::FileRecord ptm = record(capture, "finished-files/ptm-lrgb.ptm", "result", "PTM_FORMAT_LRGB", bytes(7000, 99));
  ptm.createdBy = fitId;
  const std::string ptmId = c.putFile(ptm);

  carrier::Result r1;
  r1.step = ingestId;
  r1.started = "2026-01-02T10:00:00Z";
  r1.ended = "2026-01-02T10:00:01Z";
  r1.seconds = 1.0;
  for (const std::string& id : originals) r1.add("input").set("file", id).set("kind", "image");
  r1.add("value").set("name", "images").set("value", 2);
  c.data.push_back(r1);
  carrier::Result r2;
  r2.step = fitId;
  r2.started = "2026-01-02T10:00:01Z";
  r2.ended = "2026-01-02T10:00:05Z";
  r2.seconds = 4.0;
  r2.add("input").set("file", lpId).set("kind", "lp");
  r2.add("output").set("file", ptmId).set("kind", "ptm");
  r2.add("value").set("name", "psnr").set("value", 38.25).set("unit", "dB");
  c.data.push_back(r2);
  c.addLog("intervention", ingestId, "excluded IMG_0003: the flash did not fire", "Bo Chen");
  c.addLog("warning", fitId, "2 images only");

  carrier::FileRecord overlay = record(capture, "assembly-files/spheres.png", "assembly", "PNG", bytes(300, 7));
  overlay.createdBy = fitId;
  c.putFile(overlay);
  // Not in the carrier, but payload: the report (a view of the carrier).
  std::ofstream(capture / "finished-files/report.html") << "<html></html>";
  carrier::saveCarrier(c, capture / "assembly-files/carrier.xml");
  return capture;
}

}  // namespace samplecapture
