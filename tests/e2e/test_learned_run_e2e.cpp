// `surrogate run --basis bln`: a learned basis fitted within the recorded pipeline (a LearnedFit
// step), its web layout finished-files/bln/ recorded file by file, shown by the report's
// relighting view, copied by `publish CAPTURE`, bagged by `pack` and made again byte for byte by
// `verify --reexecute`; a plane changed in the package is found.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>

#include "e2e_support.h"

namespace fs = std::filesystem;

namespace {

// 18 photographs of 200x150: they hold the default 45 planes (3 N - 3 = 51), the fit that leaves
// 2 out fits 45 on 16 too, and the fit takes a fraction of a second.
fs::path learnedCapture(const std::string& name, const std::string& options) {
  const fs::path capture =
      e2e::generatedWithTruth(name, "--images 18 --width 200 --height 150 --sphere-radius 30 --formats jpeg --seed 3");
  const e2e::CommandResult r = e2e::surrogate("run " + e2e::quote(capture) + " " + options + " --quiet --threads 2");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  return capture;
}

std::string carrierOf(const fs::path& root) { return e2e::bytesOf(root / "assembly-files" / "carrier.xml"); }

// The <file> element recording `path` (empty when none).
std::string fileRecord(const std::string& carrier, const std::string& path) {
  const auto at = carrier.find("path=\"" + path + "\"");
  if (at == std::string::npos) return "";
  const auto start = carrier.rfind("<file ", at), end = carrier.find('>', at);
  return carrier.substr(start, end - start);
}

}  // namespace

TEST_CASE("run --basis bln records the learned layout and verify reexecute reproduces it", "[e2e][learned]") {
  const fs::path capture = learnedCapture("learned-run", "--basis ptm-lrgb --basis bln --holdout 2");
  const fs::path folder = capture / "finished-files" / "bln";
  REQUIRE(fs::is_regular_file(folder / "info.json"));
  const std::string info = e2e::bytesOf(folder / "info.json");
  CHECK(info.find("\"type\": \"bilinear\"") != std::string::npos);
  CHECK(info.find("\"nplanes\": 45") != std::string::npos);

  // Every file of the layout recorded as a result of the LearnedFit step, with its digests.
  const std::string carrier = carrierOf(capture);
  std::smatch step;
  REQUIRE(std::regex_search(carrier, step, std::regex("<step id=\"(s[0-9]+)\" component=\"LearnedFit\"")));
  CHECK(carrier.find("<param name=\"basis\" value=\"bln\"/>") != std::string::npos);
  CHECK(carrier.find("<param name=\"holdout\" value=\"2\"/>") != std::string::npos);
  std::vector<std::string> names = {"info.json"};
  for (int j = 0; j < 15; ++j) names.push_back("plane_" + std::to_string(j) + ".jpg");
  for (const std::string& name : names) {
    INFO(name);
    CHECK(fs::is_regular_file(folder / name));
    const std::string record = fileRecord(carrier, "finished-files/bln/" + name);
    CHECK(record.find("role=\"result\"") != std::string::npos);
    CHECK(record.find("createdBy=\"" + step[1].str() + "\"") != std::string::npos);
    CHECK(record.find("sha256=\"") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(folder / "plane_15.jpg"));
  for (const char* value : {"kernelWidth", "ridge", "psnr", "leaveOneOutPsnr", "explainedVariance", "heldOutPsnr",
                            "heldOutSsim", "nearestBlendPsnr", "nearestBlendSsim"})
    CHECK(carrier.find("<value name=\"" + std::string(value) + "\"") != std::string::npos);

  // --holdout measures the PTM too (RtiFit's parameter), the same photographs left out.
  std::smatch ptmStep;
  REQUIRE(std::regex_search(carrier, ptmStep, std::regex("<step id=\"(s[0-9]+)\" component=\"RtiFit\"[\\s\\S]*?</step>")));
  CHECK(ptmStep.str().find("<param name=\"holdout\" value=\"2\"/>") != std::string::npos);
  CHECK(std::regex_search(carrier, std::regex("<result step=\"" + ptmStep[1].str() + "\"((?!</result>)[\\s\\S])*<value name=\"heldOutPsnr\"")));

  // The report shows the learned fit's figures and relights it, and compares the two fits at
  // the photographs left out.
  const std::string report = e2e::bytesOf(capture / "finished-files" / "report.html");
  CHECK(report.find("<table class=\"learned-fits\">") != std::string::npos);
  CHECK(report.find("<table class=\"held-out\">") != std::string::npos);
  CHECK(report.find("\"model\":\"learned\",\"basis\":\"bln\"") != std::string::npos);
  CHECK(report.find(">Bilinear (learned)</button>") != std::string::npos);

  // publish CAPTURE copies the layout as it is, beside the PTM's web copy.
  const fs::path web = capture.parent_path() / "web";
  const e2e::CommandResult published = e2e::surrogate("publish " + e2e::quote(capture) + " -o " + e2e::quote(web));
  INFO(published.output);
  REQUIRE(published.exitCode == 0);
  for (const std::string& name : names) CHECK(e2e::bytesOf(web / "bln" / name) == e2e::bytesOf(folder / name));
  CHECK(e2e::bytesOf(web / "index.html").find("href=\"bln/info.json\"") != std::string::npos);

  // Packed, re-executed at another thread count: the same bytes.
  const fs::path bag = capture.parent_path() / "bag";
  const e2e::CommandResult packed = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet");
  INFO(packed.output);
  REQUIRE(packed.exitCode == 0);
  CHECK(e2e::bytesOf(bag / "data" / "finished-files" / "bln" / "plane_0.jpg") == e2e::bytesOf(folder / "plane_0.jpg"));
  const e2e::CommandResult sound = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(sound.output);
  CHECK(sound.exitCode == 0);
  CHECK(sound.output.find("SOUND:") != std::string::npos);
  CHECK(std::regex_search(sound.output, std::regex("ok +reexecute\\." + step[1].str() + "\\.LearnedFit +reproduced exactly")));

  // One plane changed in the package: not sound.
  const fs::path plane = bag / "data" / "finished-files" / "bln" / "plane_0.jpg";
  std::string bytes = e2e::bytesOf(plane);
  REQUIRE(bytes.size() > 1000);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x55);
  fs::permissions(plane, fs::perms::owner_write, fs::perm_options::add);
  std::ofstream(plane, std::ios::binary | std::ios::trunc) << bytes;
  const e2e::CommandResult tampered = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(tampered.output);
  CHECK(tampered.exitCode != 0);
  CHECK(tampered.output.find("NOT SOUND") != std::string::npos);
  CHECK(tampered.output.find("finished-files/bln/plane_0.jpg") != std::string::npos);
}

TEST_CASE("the learned options stand for later runs and are refused without a learned basis", "[e2e][learned]") {
  const fs::path capture = learnedCapture("learned-standing", "--basis rbf --planes 27 --quality 90");
  CHECK(fs::is_regular_file(capture / "finished-files" / "rbf" / "plane_8.jpg"));
  CHECK_FALSE(fs::exists(capture / "finished-files" / "rbf" / "plane_9.jpg"));
  // DerivedMaps from the learned model when it is the only one.
  CHECK(carrierOf(capture).find("<param name=\"model\" value=\"rbf\"/>") != std::string::npos);
  CHECK(fs::is_regular_file(capture / "finished-files" / "normals.png"));

  // A run without options keeps the basis and its options.
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --title again --quiet --threads 2").exitCode == 0);
  REQUIRE(e2e::surrogate("run " + e2e::quote(capture) + " --holdout 2 --quiet --threads 2").exitCode == 0);
  const std::string carrier = carrierOf(capture);
  CHECK(carrier.find("<param name=\"planes\" value=\"27\"/>") != std::string::npos);
  CHECK(carrier.find("<param name=\"quality\" value=\"90\"/>") != std::string::npos);
  CHECK(carrier.find("<param name=\"holdout\" value=\"2\"/>") != std::string::npos);

  // --planes applies to the learned bases only; more planes than the photographs hold are fitted
  // as many as they hold (3 N - 3), and said so; a holdout that leaves fewer than 4 is refused.
  const e2e::CommandResult ptm =
      e2e::surrogate("run " + e2e::quote(capture) + " --basis ptm-lrgb --planes 30 --quiet");
  CHECK(ptm.exitCode == 2);
  CHECK(ptm.output.find("--planes: applies to the learned bases only") != std::string::npos);
  const e2e::CommandResult many = e2e::surrogate("run " + e2e::quote(capture) + " --planes 54 --holdout 0 --quiet");
  INFO(many.output);
  CHECK(many.exitCode == 0);
  const std::string capped = carrierOf(capture);
  CHECK(capped.find("<param name=\"planes\" value=\"54\"/>") != std::string::npos);
  CHECK(capped.find("name=\"planesFitted\" value=\"51\"") != std::string::npos);
  CHECK(capped.find("51 planes (the 18 photographs hold no more; 54 asked)") != std::string::npos);
  const e2e::CommandResult terms =
      e2e::surrogate("run " + e2e::quote(capture) + " --basis hsh3 --basis rbf --holdout 10 --quiet");
  CHECK(terms.exitCode == 2);
  CHECK(terms.output.find("--holdout 10: hsh3 fits 9 coefficients per pixel") != std::string::npos);
  CHECK(terms.output.find("leave out at most 9") != std::string::npos);
  const e2e::CommandResult left = e2e::surrogate("run " + e2e::quote(capture) + " --holdout 15 --quiet");
  CHECK(left.exitCode == 2);
  CHECK(left.output.find("leave out at most 14") != std::string::npos);
}
