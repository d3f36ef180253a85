// `surrogate run --publish`: the web copy of each model as recorded results of a WebCopy step,
// a standing decision, the package's access copy (METS fileGrp USE="access") and re-created
// byte for byte by `verify --reexecute`.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <tuple>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

fs::path publishedCapture(const std::string& name) {
  const fs::path dir = e2e::freshDir(name);
  const fs::path capture = e2e::smallCapture(dir, 12);
  const e2e::CommandResult r =
      e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --publish --quiet --threads 2");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  return capture;
}

std::string carrierOf(const fs::path& capture) { return e2e::bytesOf(capture / "assembly-files" / "carrier.xml"); }

// The <file> element recording `path` (empty when none).
std::string fileRecord(const std::string& carrier, const std::string& path) {
  const auto at = carrier.find("path=\"" + path + "\"");
  if (at == std::string::npos) return "";
  const auto start = carrier.rfind("<file ", at), end = carrier.find('>', at);
  return carrier.substr(start, end - start);
}

std::string webCopyStepId(const std::string& carrier) {
  std::smatch m;
  const std::regex step("<step id=\"(s[0-9]+)\" component=\"WebCopy\"");
  return std::regex_search(carrier, m, step) ? m[1].str() : "";
}

}  // namespace

TEST_CASE("run with publish records the web copy as results of a WebCopy step", "[e2e][publish]") {
  const fs::path capture = publishedCapture("web-copy-run");
  const std::string carrier = carrierOf(capture);
  const std::string step = webCopyStepId(carrier);
  REQUIRE(!step.empty());
  CHECK(carrier.find("<param name=\"quality\" value=\"95\"/>") != std::string::npos);
  CHECK(carrier.find("<param name=\"tileSize\" value=\"256\"/>") != std::string::npos);
  const std::string web = "finished-files/web/ptm-lrgb/";
  for (const auto& [name, format, media] : {std::tuple<const char*, const char*, const char*>{"info.json", "JSON", "application/json"},
                                            {"plane_0.jpg", "JPEG", "image/jpeg"},
                                            {"plane_2.jpg", "JPEG", "image/jpeg"},
                                            {"index.html", "HTML", "text/html"},
                                            {"viewer-data.js", "JavaScript", "text/javascript"}}) {
    const std::string record = fileRecord(carrier, web + name);
    INFO(name);
    REQUIRE(!record.empty());
    CHECK(fs::is_regular_file(capture / (web + name)));
    CHECK(record.find("role=\"result\"") != std::string::npos);
    CHECK(record.find("createdBy=\"" + step + "\"") != std::string::npos);
    CHECK(record.find("format=\"" + std::string(format) + "\"") != std::string::npos);
    CHECK(record.find("mediaType=\"" + std::string(media) + "\"") != std::string::npos);
  }
  // The planes are JPEG files (SOI marker), info.json names the PTM basis.
  CHECK(e2e::bytesOf(capture / (web + "plane_0.jpg")).rfind("\xFF\xD8", 0) == 0);
  CHECK(e2e::bytesOf(capture / (web + "info.json")).find("\"ptm\"") != std::string::npos);
}

TEST_CASE("the packed web copy is the access copy and re-executes byte for byte", "[e2e][publish]") {
  const fs::path capture = publishedCapture("web-copy-pack");
  const fs::path bag = capture.parent_path() / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);

  const std::string mets = e2e::bytesOf(bag / "metadata" / "mets.xml");
  const auto access = mets.find("<mets:fileGrp ID=\"fileGrp-access\" USE=\"access\">");
  REQUIRE(access != std::string::npos);
  const std::string group = mets.substr(access, mets.find("</mets:fileGrp>", access) - access);
  CHECK(group.find("data/finished-files/web/ptm-lrgb/plane_0.jpg") != std::string::npos);
  CHECK(group.find("data/finished-files/web/ptm-lrgb/info.json") != std::string::npos);
  CHECK(group.find("data/finished-files/ptm-lrgb.ptm") == std::string::npos);
  const auto result = mets.find("<mets:fileGrp ID=\"fileGrp-result\" USE=\"result\">");
  REQUIRE(result != std::string::npos);
  CHECK(mets.substr(result, mets.find("</mets:fileGrp>", result) - result).find("finished-files/web/") == std::string::npos);
  CHECK(e2e::bytesOf(bag / "metadata" / "crm.rdf").find("web access copy") != std::string::npos);

  const e2e::CommandResult sound = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(sound.output);
  CHECK(sound.exitCode == 0);
  CHECK(sound.output.find("SOUND") != std::string::npos);
  CHECK(std::regex_search(sound.output, std::regex("ok +reexecute\\.s[0-9]+\\.WebCopy +reproduced exactly")));
  CHECK(std::regex_search(sound.output, std::regex("ok +reexecute\\.files ")));

  // A forged plane (one byte changed, same size) fails the bag's fixity.
  const fs::path plane = bag / "data" / "finished-files" / "web" / "ptm-lrgb" / "plane_1.jpg";
  std::string bytes = e2e::bytesOf(plane);
  REQUIRE(bytes.size() > 200);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5a);
  std::ofstream(plane, std::ios::binary | std::ios::trunc) << bytes;
  const e2e::CommandResult forged = e2e::surrogate("verify " + e2e::quote(bag));
  INFO(forged.output);
  CHECK(forged.exitCode == 3);
  CHECK(forged.output.find("plane_1.jpg") != std::string::npos);
  CHECK(forged.output.find("SOUND: all") == std::string::npos);
}

TEST_CASE("the web copy is a standing decision and its quality re-runs it", "[e2e][publish]") {
  const fs::path capture = publishedCapture("web-copy-decision");
  const std::string plane = "finished-files/web/ptm-lrgb/plane_1.jpg";
  const std::string before = fileRecord(carrierOf(capture), plane);
  REQUIRE(!before.empty());

  // A run that does not mention it keeps it.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --threads 2").exitCode == 0);
  CHECK(!webCopyStepId(carrierOf(capture)).empty());
  CHECK(fileRecord(carrierOf(capture), plane).find("sha256=") != std::string::npos);

  // Another quality: the step runs with it, the planes differ.
  const e2e::CommandResult q = e2e::surrogate("run " + e2e::quote(capture) + " --publish-quality 40 --quiet --threads 2");
  INFO(q.output);
  REQUIRE(q.exitCode == 0);
  const std::string carrier = carrierOf(capture);
  CHECK(carrier.find("<param name=\"quality\" value=\"40\"/>") != std::string::npos);
  CHECK(carrier.find("WebCopy quality = 40") != std::string::npos);
  const std::string after = fileRecord(carrier, plane);
  CHECK(after.substr(after.find("sha256=")).substr(0, 72) != before.substr(before.find("sha256=")).substr(0, 72));
  // It stands for the next run too.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --quiet --threads 2").exitCode == 0);
  CHECK(carrierOf(capture).find("<param name=\"quality\" value=\"40\"/>") != std::string::npos);
  // info lists it among the choices a run repeats, with its options, in text and JSON.
  const e2e::CommandResult info = e2e::surrogate("info " + e2e::quote(capture));
  CHECK_THAT(info.output, Catch::Contains("web copy of ptm-lrgb in finished-files/web/ (quality 40, tiles auto, tileSize 256)"));
  CHECK_THAT(info.output, Catch::Contains("models: ptm-lrgb\n"));
  const e2e::CommandResult json = e2e::surrogate("info " + e2e::quote(capture) + " --json");
  CHECK_THAT(json.output, Catch::Contains("\"webCopy\":{\"models\":[\"ptm-lrgb\"],\"parameters\":[{\"name\":\"quality\",\"value\":\"40\"}"));

  // Whole planes to Deep Zoom tiles: the whole planes are no longer made and are moved aside.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --publish-tiles deepzoom --quiet --threads 2").exitCode == 0);
  CHECK(fileRecord(carrierOf(capture), plane).empty());
  CHECK(!fileRecord(carrierOf(capture), "finished-files/web/ptm-lrgb/plane_1.dzi").empty());
  CHECK(fs::is_regular_file(capture / "superseded-files" / "r5" / plane));

  // Withdrawn: no step, the files superseded; an option without a web copy is refused.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --no-publish --quiet --threads 2").exitCode == 0);
  CHECK(webCopyStepId(carrierOf(capture)).empty());
  CHECK(!fs::exists(capture / "finished-files" / "web" / "ptm-lrgb" / "info.json"));
  CHECK(fs::is_regular_file(capture / "superseded-files" / "r6" / "finished-files" / "web" / "ptm-lrgb" / "info.json"));
  CHECK_THAT(e2e::surrogate("info " + e2e::quote(capture)).output, Catch::Contains("web copy: none"));
  CHECK_THAT(e2e::surrogate("info " + e2e::quote(capture) + " --json").output, Catch::Contains("\"webCopy\":null"));
  const e2e::CommandResult refused = e2e::surrogate("run " + e2e::quote(capture) + " --publish-quality 50 --quiet");
  CHECK(refused.exitCode == 2);
  CHECK(refused.output.find("--publish") != std::string::npos);
}
