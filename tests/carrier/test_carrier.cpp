#include <catch2/catch.hpp>

#include <filesystem>

#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/error.h"

using namespace surrogate;
using namespace surrogate::carrier;
namespace fs = std::filesystem;

namespace {
Carrier sampleCarrier() {
  Carrier c = newCarrier("Stela <12> & \"friends\"", {{"A. Photographer", "photographer"}});
  c.header.meta.emplace_back("Source-Organization", "Museu D. Diogo de Sousa");
  c.header.software.push_back({"LibRaw", "0.20.2", "decoder"});
  FileRecord f;
  f.path = "original-captures/IMG_0001.dng";
  f.role = "original";
  f.size = 1234;
  f.sha256 = std::string(64, 'a');
  f.format = "DNG";
  f.imageSize = std::make_pair(1200, 800);
  f.camera = {{"make", "Surrogate"}, {"model", "Synthetic HRTI"}, {"iso", "100"}};
  f.xmp = "<?xpacket begin='' id='W5M0MpCehiHzreSzNTczkc9d'?><x:xmpmeta xmlns:x='adobe:ns:meta/'/>";
  const std::string id = c.putFile(f);
  Step& s = c.addStep("SphereDetection", "1");
  s.setParam("minRadius", "20");
  s.interventions.push_back({"manual-sphere", "0", "512.5,300,80", "tester", timestampNow(),
                             "the automatic detection picked the lens cap"});
  Result r;
  r.step = s.id;
  r.started = r.ended = timestampNow();
  r.add("sphere").set("index", 0).set("cx", 512.5).set("cy", 1.0 / 3.0).set("r", 80.0)
      .set("source", "manual");
  r.add("input").set("file", id);
  c.data.push_back(r);
  c.addLog("intervention", s.id, "sphere set by hand", "tester");
  return c;
}
}  // namespace

TEST_CASE("a carrier round-trips through XML with numbers exact and text escaped") {
  const Carrier c = sampleCarrier();
  const std::string text = toXml(c);
  const Carrier back = parseCarrier(text, "memory");
  CHECK(back.header.title == c.header.title);
  CHECK(back.header.meta == c.header.meta);
  REQUIRE(back.files.size() == 1);
  CHECK(back.files[0].id == "f1");
  CHECK(back.files[0].camera == c.files[0].camera);
  CHECK(back.files[0].xmp == c.files[0].xmp);
  CHECK(back.files[0].imageSize == c.files[0].imageSize);
  REQUIRE(back.process.size() == 1);
  CHECK(back.process[0].param("minRadius") == "20");
  REQUIRE(back.process[0].interventions.size() == 1);
  CHECK(back.process[0].interventions[0].reason == "the automatic detection picked the lens cap");
  const Result* r = back.findResult("s1");
  REQUIRE(r != nullptr);
  CHECK(r->itemsOf("sphere")[0]->number("cy") == 1.0 / 3.0);  // exact, not approximately
  CHECK(toXml(back) == text);
}

TEST_CASE("saveCarrier writes a file that loadCarrier validates and reads") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-carrier";
  fs::remove_all(dir);
  fs::create_directories(dir);
  saveCarrier(sampleCarrier(), dir / "carrier.xml");
  const Carrier back = loadCarrier(dir / "carrier.xml");
  CHECK(back.files.size() == 1);
  fs::remove_all(dir);
}

TEST_CASE("saving an invalid carrier is refused and leaves no file") {
  const fs::path dir = fs::temp_directory_path() / "surrogate-test-carrier-invalid";
  fs::remove_all(dir);
  fs::create_directories(dir);
  Carrier c = sampleCarrier();
  c.files[0].sha256 = "not-a-hash";
  CHECK_THROWS_AS(saveCarrier(c, dir / "carrier.xml"), Error);
  CHECK_FALSE(fs::exists(dir / "carrier.xml"));
  fs::remove_all(dir);
}

TEST_CASE("a carrier that breaks the schema is rejected with the line number") {
  std::string text = toXml(sampleCarrier());
  const auto at = text.find("role=\"original\"");
  text.replace(at, 15, "role=\"mystery\"");
  try {
    parseCarrier(text, "edited.xml");
    FAIL("accepted an invalid carrier");
  } catch (const Error& e) {
    CHECK(e.file() == "edited.xml");
    CHECK_THAT(e.message(), Catch::Contains("line"));
    CHECK_THAT(e.message(), Catch::Contains("carrier.xsd"));
  }
}

TEST_CASE("putFile gives new ids and replaces a record with the same path") {
  Carrier c;
  FileRecord a;
  a.path = "a.jpg";
  FileRecord b;
  b.path = "b.jpg";
  CHECK(c.putFile(a) == "f1");
  CHECK(c.putFile(b) == "f2");
  a.size = 9;
  CHECK(c.putFile(a) == "f1");
  CHECK(c.files.size() == 2);
  CHECK(c.findFileByPath("a.jpg")->size == 9);
}

TEST_CASE("putFiles records as putFile does for each, ids and replacements alike") {
  // Against putFile one by one: the same list, the same ids, in the same order.
  auto record = [](const std::string& path, std::uint64_t size) {
    FileRecord f;
    f.path = path;
    f.size = size;
    return f;
  };
  Carrier one, batch;
  for (Carrier* c : {&one, &batch}) {
    c->putFile(record("a.jpg", 1));
    FileRecord odd = record("odd.jpg", 2);
    odd.id = "f7";  // a carrier whose ids have gaps (a file removed): ids are never reused
    c->files.push_back(odd);
  }
  const std::vector<FileRecord> more = {record("b.jpg", 3), record("a.jpg", 4), record("c.jpg", 5),
                                        record("b.jpg", 6)};
  for (const FileRecord& f : more) one.putFile(f);
  batch.putFiles(more);
  REQUIRE(batch.files.size() == one.files.size());
  for (std::size_t i = 0; i < one.files.size(); ++i) {
    CHECK(batch.files[i].id == one.files[i].id);
    CHECK(batch.files[i].path == one.files[i].path);
    CHECK(batch.files[i].size == one.files[i].size);
  }
  CHECK(batch.findFileByPath("b.jpg")->id == "f8");
  CHECK(batch.findFileByPath("b.jpg")->size == 6);
  CHECK(batch.findFileByPath("c.jpg")->id == "f9");
  const auto byPath = batch.filesByPath();
  CHECK(byPath.size() == 4);
  CHECK(byPath.at("a.jpg") == batch.findFileByPath("a.jpg"));
}

TEST_CASE("rights and licence in the header round-trip, and a carrier without them (older versions) still validates") {
  Carrier c = sampleCarrier();
  const std::string without = toXml(c);
  CHECK(without.find("<rights>") == std::string::npos);  // nothing written when not given
  CHECK_NOTHROW(parseCarrier(without, "old.xml"));
  c.header.rights = "Images: Museum <of> Stelae & co; research use only";
  c.header.license = "https://creativecommons.org/licenses/by-nc/4.0/";
  const std::string text = toXml(c);
  const Carrier back = parseCarrier(text, "memory");
  CHECK(back.header.rights == c.header.rights);
  CHECK(back.header.license == c.header.license);
  CHECK(toXml(back) == text);
  // They sit after the user metadata and before the machine, in the schema's order.
  CHECK(text.find("<meta ") < text.find("<rights>"));
  CHECK(text.find("<license>") < text.find("<machine "));
  // An empty rights element is not a statement: the schema refuses it.
  std::string empty = text;
  empty.replace(empty.find("<rights>"), empty.find("</rights>") - empty.find("<rights>"), "<rights>");
  CHECK_THROWS_AS(parseCarrier(empty, "empty.xml"), Error);
}

TEST_CASE("numbers are written with the fewest digits that read back and old 17-digit text reads the same") {
  Carrier c = sampleCarrier();
  Result r;
  r.step = "s1";
  r.started = r.ended = timestampNow();
  r.add("light").set("image", "f1").set("x", 0.8).set("y", 0.1 + 0.2).set("z", 1e-7)
      .set("elevationDeg", 250.0).set("azimuthDeg", -135.5).set("source", "lp");
  r.seconds = 0.25;
  c.data.push_back(r);
  const std::string text = toXml(c);
  CHECK(text.find("x=\"0.8\" y=\"0.30000000000000004\" z=\"1e-07\" elevationDeg=\"250\" azimuthDeg=\"-135.5\"") !=
        std::string::npos);
  CHECK(text.find("seconds=\"0.25\"") != std::string::npos);
  CHECK(text.find("cy=\"0.3333333333333333\"") != std::string::npos);

  // A carrier written before (carrier.cpp printed "%.17g") holds the long forms of the same
  // doubles: read back, they are the values the short forms give.
  std::string old = text;
  for (const auto& [now, before] : std::vector<std::pair<std::string, std::string>>{
           {"x=\"0.8\"", "x=\"0.80000000000000004\""},
           {"z=\"1e-07\"", "z=\"9.9999999999999995e-08\""},
           {"seconds=\"0.25\"", "seconds=\"0.25\""},
           {"cy=\"0.3333333333333333\"", "cy=\"0.33333333333333331\""}}) {
    const auto at = old.find(now);
    REQUIRE(at != std::string::npos);
    old.replace(at, now.size(), before);
  }
  const Carrier back = parseCarrier(old, "memory");
  const Result* items = nullptr;
  for (const Result& x : back.data)
    if (!x.itemsOf("light").empty()) items = &x;
  REQUIRE(items != nullptr);
  const DataItem& light = *items->itemsOf("light")[0];
  CHECK(light.number("x") == 0.8);
  CHECK(light.number("z") == 1e-7);
  CHECK(back.data[0].itemsOf("sphere")[0]->number("cy") == 1.0 / 3.0);
  // Written again, the old carrier's numbers take their short forms: the same record.
  Carrier again = back;
  for (Result& x : again.data)
    for (DataItem& i : x.items)
      for (auto& [name, value] : i.attributes)
        if (name == "x" || name == "z" || name == "cy") i.set(name, i.number(name));
  CHECK(toXml(again) == text);
}

TEST_CASE("prior work round-trips with its kind and maker and is evidence") {
  Carrier c = sampleCarrier();
  FileRecord f;
  f.path = "finished-files/stela.ptm";
  f.role = "prior";
  f.size = 99;
  f.sha256 = std::string(64, 'b');
  f.format = "PTM_FORMAT_LRGB";
  f.priorKind = "rti";
  f.madeBy = "PTM_1.2 PTM_FORMAT_LRGB & \"more\"";
  c.putFile(f);
  const Carrier back = parseCarrier(toXml(c), "memory");
  const FileRecord* r = back.findFileByPath("finished-files/stela.ptm");
  REQUIRE(r != nullptr);
  CHECK(r->role == "prior");
  CHECK(r->priorKind == "rti");
  CHECK(r->madeBy == f.madeBy);
  CHECK(back.findFileByPath("original-captures/IMG_0001.dng")->priorKind.empty());
  CHECK(isEvidenceRole("prior"));
  // A kind the schema does not know is refused.
  std::string text = toXml(c);
  text.replace(text.find("priorKind=\"rti\""), 15, "priorKind=\"ptm\"");
  CHECK_THROWS_AS(parseCarrier(text, "edited.xml"), Error);
}
