// Issues 17 and 40 (the audit): a generated capture laid out as RTIBuilder leaves it, with prior
// work written here without Surrogate's code: an .lp (Windows paths, CRLF, a blank line) of the
// generator's true lights with three of them tilted by exactly 6 degrees, a PTM fitted with
// those lights by the independent writer of tests/audit/prior_rti.h (with a clamped bias, or
// without), and a log XML. `audit PRIOR` on the folder made read-only copies it into a work
// folder, leaves it untouched to the timestamp, names exactly the tilted images, gives the
// verdict in parts with exit 4; the work folder packs and re-executes SOUND, and a changed
// audit figure in a packed carrier does not.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <sys/stat.h>

#include "../audit/prior_rti.h"
#include "bag_check.h"
#include "e2e_support.h"
#include "rtibuilder_capture.h"

namespace fs = std::filesystem;
using namespace surrogate;
using namespace audit_e2e;

namespace {

// The JSON array after `"key":[` up to its closing bracket (the arrays read here hold objects
// without arrays inside).
std::string jsonArray(const std::string& json, const std::string& key) {
  const std::string open = "\"" + key + "\":[";
  const auto start = json.find(open);
  REQUIRE(start != std::string::npos);
  return json.substr(start + open.size(), json.find(']', start) - start - open.size());
}

double jsonNumber(const std::string& json, const std::string& key) {
  std::smatch m;
  REQUIRE(std::regex_search(json, m, std::regex("\"" + key + "\":(-?[0-9.]+)")));
  return std::stod(m[1]);
}

// A file of the bag rewritten with as many bytes (Payload-Oxum stays right), its digests in the
// manifests and theirs in the tag manifests updated, so that only the content tells.
void rewriteInBag(const fs::path& bag, const std::string& path, const std::string& bytes) {
  const std::string before = e2e::bytesOf(bag / path);
  REQUIRE(before.size() == bytes.size());
  const auto digest = [](const std::string& algorithm, const std::string& b) {
    return algorithm == "sha256" ? bagcheck::sha256(b) : bagcheck::sha512(b);
  };
  const auto replace = [&](const std::string& manifest, const std::string& from, const std::string& to) {
    std::string text = e2e::bytesOf(bag / manifest);
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    test::writeText((bag / manifest).string(), text.replace(at, from.size(), to));
  };
  test::writeText((bag / path).string(), bytes);
  std::map<std::string, std::string> manifestsBefore;
  for (const std::string algorithm : {"sha256", "sha512"}) {
    const std::string manifest = "manifest-" + algorithm + ".txt";
    manifestsBefore[manifest] = e2e::bytesOf(bag / manifest);
    replace(manifest, digest(algorithm, before), digest(algorithm, bytes));
  }
  for (const std::string algorithm : {"sha256", "sha512"})
    for (const auto& [manifest, old] : manifestsBefore)
      replace("tagmanifest-" + algorithm + ".txt", digest(algorithm, old), digest(algorithm, e2e::bytesOf(bag / manifest)));
}

// Every entry under `root` with what an audit must leave as it was: type and mode, size,
// modification and status-change times to the nanosecond, a file's access time (folders are
// listed by the audit, which may update theirs) and SHA-256. Files are hashed before they are
// stat'ed, so that this reading does not show in the times it records.
std::map<std::string, std::string> untouchedState(const fs::path& root) {
  std::map<std::string, std::string> out;
  const std::map<std::string, std::string> hashes = e2e::snapshot(root);
  const auto stamp = [](const timespec& t) { return std::to_string(t.tv_sec) + "." + std::to_string(t.tv_nsec); };
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    struct stat st {};
    REQUIRE(::lstat(it->path().c_str(), &st) == 0);
    const std::string rel = fs::relative(it->path(), root).generic_string();
    const bool file = S_ISREG(st.st_mode);
    out[rel] = std::to_string(st.st_mode) + " " + std::to_string(st.st_size) + " m" + stamp(st.st_mtim) + " c" +
               stamp(st.st_ctim) + (file ? " a" + stamp(st.st_atim) + " " + hashes.at(rel) : std::string());
  }
  return out;
}

std::string partOf(const std::string& json, const std::string& part) {
  const std::string key = "{\"part\":\"" + part + "\",\"state\":\"";
  const auto at = json.find(key);
  REQUIRE(at != std::string::npos);
  return json.substr(at + key.size(), json.find('"', at + key.size()) - at - key.size());
}

}  // namespace

TEST_CASE("audit of a read-only RTIBuilder folder names the tilted lights, exits 4 and leaves it as it was",
          "[e2e][audit]") {
  const fs::path capture = rtibuilderCapture("audit");
  const fs::path work = capture.parent_path() / "capture-audit";
  REQUIRE(e2e::runShell("chmod -R a-w " + e2e::quote(capture)).exitCode == 0);
  const std::map<std::string, std::string> before = untouchedState(capture);

  const e2e::CommandResult r = e2e::surrogate("audit " + e2e::quote(capture) + " --json");
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK(untouchedState(capture) == before);
  REQUIRE(fs::exists(work / "assembly-files" / "carrier.xml"));
  const std::string& json = r.output;
  // The verdict first, in parts: the lights differ, and so does the model's integrity.
  CHECK(json.rfind("{\"reproduced\":false,\"exitCode\":4,\"verdict\":[{\"subject\":\"finished-files/stela.ptm with "
                   "the lights of assembly-files/stela.lp\"", 0) == 0);
  CHECK(partOf(json, "lights") == "differs");
  CHECK(partOf(json, "integrity") == "differs");
  CHECK(partOf(json, "model") == "differs");  // the clamped bias costs the prior more than a dB
  CHECK(json.find("\"ran\":true") != std::string::npos);
  // Every file: 12 photographs, the .lp, .ptm and log, and the generator's truth/ folder.
  CHECK(json.find("\"copiedFiles\":" + std::to_string(e2e::snapshot(capture).size()) + ",") != std::string::npos);
  CHECK(json.find("\"file\":\"assembly-files/stela.lp\"") != std::string::npos);

  // Exactly the tilted images, each about 6 degrees off.
  const std::string above = jsonArray(json, "aboveThreshold");
  const std::regex entry("\"image\":\"([^\"]+)\",\"degrees\":([0-9.]+)");
  std::set<std::string> named;
  for (std::sregex_iterator it(above.begin(), above.end(), entry), end; it != end; ++it) {
    named.insert((*it)[1]);
    CHECK(std::stod((*it)[2]) == Approx(kTiltDegrees).margin(kAngleTolerance));
  }
  CHECK(named == std::set<std::string>{"IMG_0003.jpg", "IMG_0006.jpg", "IMG_0009.jpg"});
  CHECK(jsonNumber(json, "medianDegrees") < kAngleTolerance);

  // Both PSNRs, the clamped bias, the verdict.
  const std::string models = json.substr(json.find("\"models\":"));
  CHECK(models.find("\"file\":\"finished-files/stela.ptm\"") != std::string::npos);
  const double prior = jsonNumber(models.substr(models.find("\"prior\":")), "psnr");
  const double refit = jsonNumber(models.substr(models.find("\"refitPriorLights\":")), "psnr");
  const double own = jsonNumber(models.substr(models.find("\"refitSurrogateLights\":")), "psnr");
  CHECK(prior > 10);
  CHECK(refit - prior > 1.0);
  CHECK(own > 20);
  CHECK(models.find("\"quantisation\":{\"clamped\":true") != std::string::npos);
  const std::string verdicts = json.substr(json.find("\"verdicts\":"));
  CHECK(verdicts.find("\"cause\":\"broken-bias\"") != std::string::npos);
  CHECK(verdicts.find("\"cause\":\"different-lights\"") != std::string::npos);

  // The work folder's carrier records where each copy came from, with the bytes read.
  const std::string carrier = e2e::bytesOf(work / "assembly-files" / "carrier.xml");
  CHECK(carrier.find("<audited source=\"" + fs::absolute(capture).lexically_normal().string() + "\" kind=\"folder\"") !=
        std::string::npos);
  CHECK(carrier.find("<evidence path=\"finished-files/stela.ptm\" from=\"finished-files/stela.ptm\" size=\"" +
                     std::to_string(fs::file_size(capture / "finished-files" / "stela.ptm")) + "\" sha256=\"" +
                     bagcheck::sha256(e2e::bytesOf(capture / "finished-files" / "stela.ptm")) + "\"/>") !=
        std::string::npos);
  CHECK(carrier.find("priorKind=\"rti\"") != std::string::npos);

  // The difference image is made at the worst image (the lowest PSNR of the prior), as luminance
  // in false colour with its legend below, at a full scale of at least 4 levels.
  const std::string worst = models.substr(models.find("\"prior\":"));
  std::smatch worstImage;
  REQUIRE(std::regex_search(worst, worstImage, std::regex("\"worstImage\":\"([^\"]+)\"")));
  const std::string differences = models.substr(models.find("\"differences\":["));
  CHECK(differences.find("{\"file\":\"assembly-files/audit/stela-difference.png\",\"image\":\"" +
                         worstImage[1].str() + "\",\"worst\":true") == 15);
  const double fullScale = jsonNumber(differences, "fullScale");
  CHECK(fullScale >= 4);
  WARN("difference image at " << worstImage[1].str() << ", full scale " << fullScale << " levels");
  const cv::Mat difference = cv::imread((work / "assembly-files" / "audit" / "stela-difference.png").string());
  CHECK(difference.cols == 560);   // the map of 400 pixels, widened for the legend
  CHECK(difference.rows > 300);    // the legend below the map

  // The text form: the verdict on top, printed from the record when nothing changed.
  const e2e::CommandResult text = e2e::surrogate("audit " + e2e::quote(capture));
  INFO(text.output);
  CHECK(text.exitCode == 4);
  CHECK(text.output.rfind("NOT REPRODUCED  finished-files/stela.ptm with the lights of assembly-files/stela.lp "
                          "(threshold 2.0 deg)\n  lights     differs     3 of 12 images differ by more than both their "
                          "combined uncertainty and the threshold 2.0 degrees: ", 0) == 0);
  CHECK(text.output.find("as recorded") != std::string::npos);
  CHECK(text.output.find("3 differ (beyond both the combined uncertainty and the threshold 2.0 deg): IMG_0003.jpg") !=
        std::string::npos);
  CHECK(untouchedState(capture) == before);

  // The report opens on the audit's card, and plots the prior lights.
  const std::string report = e2e::bytesOf(work / "finished-files" / "report.html");
  CHECK(report.find("<main><section id=\"audit-summary\"><h2>Audit: <span class=\"bad\">not reproduced</span>") !=
        std::string::npos);
  CHECK(report.find("<section id=\"audit\"><h2>Audit of prior work</h2>") != std::string::npos);
  std::size_t off = 0, crosses = 0;
  for (std::size_t at = report.find("class=\"prior-light"); at != std::string::npos;
       at = report.find("class=\"prior-light", at + 1)) {
    ++crosses;
    off += report.compare(at, 22, "class=\"prior-light off") == 0;
  }
  CHECK(crosses == kImages);
  CHECK(off == kTilted.size());
  // The prior's error per photograph on the hemisphere, and the difference image shown large.
  std::size_t errorPoints = 0;
  for (std::size_t at = report.find("<circle class=\"error-light\""); at != std::string::npos;
       at = report.find("<circle class=\"error-light\"", at + 1))
    ++errorPoints;
  CHECK(errorPoints == kImages);
  CHECK(report.find("<figure class=\"difference\"><img src=\"data:image/jpeg;base64,") != std::string::npos);
  CHECK(report.find("assembly-files/audit/stela-difference.png") != std::string::npos);

  // The work folder packs with the evidence it examined, and re-executes SOUND.
  const fs::path bag = capture.parent_path() / "audit-bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(work) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  CHECK(bagcheck::sha256(e2e::bytesOf(bag / "data" / "finished-files" / "stela.ptm")) ==
        bagcheck::sha256(e2e::bytesOf(capture / "finished-files" / "stela.ptm")));
  const e2e::CommandResult sound = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(sound.output);
  CHECK(sound.exitCode == 0);
  CHECK(std::regex_search(sound.output, std::regex("ok +carrier\\.evidence")));
  CHECK(std::regex_search(sound.output, std::regex("ok +reexecute\\.s[0-9]+\\.Audit +reproduced exactly")));
  CHECK(untouchedState(capture) == before);
  e2e::runShell("chmod -R u+w " + e2e::quote(capture));
}

// The case: the prior model is as good as Surrogate's refit at the prior's own lights,
// but three of those lights are wrong. The parts say so apart.
TEST_CASE("audit separates lights that differ from a model that is reproduced", "[e2e][audit]") {
  const fs::path capture = rtibuilderCapture("audit-lights", /*clampBias=*/false);
  // A real RTIBuilder 2.0.2 log (tests/data/rtibuilder/README.md: another capture's, the fish
  // fossil's), in place of the invented one: read, listed, and compared with this capture.
  fs::copy_file(fs::path(SURROGATE_SOURCE_DIR) / "tests/data/rtibuilder/Fisch.xml",
                capture / "assembly-files" / "stela_log.xml", fs::copy_options::overwrite_existing);
  const e2e::CommandResult r = e2e::surrogate("audit " + e2e::quote(capture) + " --json -o " +
                                              e2e::quote(capture.parent_path() / "work"));
  INFO(r.output);
  CHECK(r.exitCode == 4);
  CHECK(partOf(r.output, "lights") == "differs");
  CHECK(partOf(r.output, "model") == "reproduced");
  CHECK(partOf(r.output, "integrity") == "reproduced");
  CHECK(fs::exists(capture.parent_path() / "work" / "assembly-files" / "carrier.xml"));
  CHECK(!fs::exists(capture.parent_path() / "capture-audit"));
  const std::string logs = r.output.substr(r.output.find("\"priorLogs\":[{\"file\":\"assembly-files/stela_log.xml\""));
  CHECK(logs.find("\"records\":[\"RTIBuilder 2.0.2\"") != std::string::npos);
  CHECK(logs.find("fitter: hshfitter, HSH order 2 (hsh2), 4 threads") != std::string::npos);
  CHECK(logs.find("the log used 36 images; the capture has 12 photographs") != std::string::npos);
  CHECK(logs.find("the log's fit is hsh2; the prior model audited is ptm-lrgb") != std::string::npos);
  // At a threshold above the tilt, the lights are reproduced too: exit 0, the step run again.
  const e2e::CommandResult wide = e2e::surrogate("audit " + e2e::quote(capture) + " --json --threshold 10 -o " +
                                                 e2e::quote(capture.parent_path() / "work"));
  INFO(wide.output);
  CHECK(wide.exitCode == 0);
  CHECK(wide.output.rfind("{\"reproduced\":true,\"exitCode\":0,", 0) == 0);
  CHECK(wide.output.find("\"ran\":true") != std::string::npos);
  CHECK(jsonArray(wide.output, "aboveThreshold").empty());
  const std::string carrier = e2e::bytesOf(capture.parent_path() / "work" / "assembly-files" / "carrier.xml");
  CHECK(carrier.find("<param name=\"angleThresholdDegrees\" value=\"10\"/>") != std::string::npos);
  CHECK(carrier.find("command=\"audit\"") != std::string::npos);
  // The threshold was that audit's only (issue 52): asked again without it, the audit is run
  // again at the default; asked again with it, the record is printed.
  const e2e::CommandResult same = e2e::surrogate("audit " + e2e::quote(capture) + " --json --threshold 10 -o " +
                                                 e2e::quote(capture.parent_path() / "work"));
  CHECK(same.exitCode == 0);
  CHECK(same.output.find("\"ran\":false") != std::string::npos);
  const e2e::CommandResult again = e2e::surrogate("audit " + e2e::quote(capture) + " --json -o " +
                                                  e2e::quote(capture.parent_path() / "work"));
  CHECK(again.exitCode == 4);
  CHECK(again.output.find("\"ran\":true") != std::string::npos);
  CHECK(again.output.find("\"thresholdDegrees\":2,") != std::string::npos);
}

// The photographs named with --at get difference images of their own beside the worst one's;
// the names stand like any recorded parameter. A name that is none of the photographs stops
// the run with exit 2, naming some that are, and leaves the previous results whole.
TEST_CASE("audit makes difference images at the photographs --at names and refuses an unknown name", "[e2e][audit]") {
  const fs::path capture = rtibuilderCapture("audit-named");
  const fs::path work = capture.parent_path() / "capture-audit";
  const e2e::CommandResult r =
      e2e::surrogate("audit " + e2e::quote(capture) + " --json --at IMG_0002.jpg --at IMG_0007");  // file, shot
  INFO(r.output);
  REQUIRE(r.exitCode == 4);
  CHECK(r.output.find("\"ran\":true") != std::string::npos);
  for (const char* file : {"stela-difference.png", "stela-difference-IMG_0002.png", "stela-difference-IMG_0007.png"})
    CHECK(fs::exists(work / "assembly-files" / "audit" / file));
  CHECK(r.output.find("\"file\":\"assembly-files/audit/stela-difference-IMG_0007.png\",\"image\":\"IMG_0007.jpg\","
                      "\"worst\":false") != std::string::npos);
  const fs::path carrierPath = work / "assembly-files" / "carrier.xml";
  const std::string carrier = e2e::bytesOf(carrierPath);
  CHECK(carrier.find("<param name=\"differenceImages\" value=\"IMG_0002.jpg,IMG_0007\"/>") != std::string::npos);
  CHECK(carrier.find("name=\"differenceOf\" value=\"IMG_0002.jpg\"") != std::string::npos);
  // Asked again with the same names, the record is printed; the names stand without --at.
  CHECK(e2e::surrogate("audit " + e2e::quote(capture) + " --json --at IMG_0002.jpg --at IMG_0007").output.find(
            "\"ran\":false") != std::string::npos);
  CHECK(e2e::surrogate("audit " + e2e::quote(capture) + " --json").output.find("\"ran\":false") != std::string::npos);

  const e2e::CommandResult unknown = e2e::surrogate("audit " + e2e::quote(capture) + " --at NOPE.jpg");
  INFO(unknown.output);
  CHECK(unknown.exitCode == 2);
  CHECK(unknown.output.find("NOPE.jpg") != std::string::npos);
  CHECK(unknown.output.find("IMG_0001.jpg, IMG_0002.jpg") != std::string::npos);
  CHECK(e2e::bytesOf(carrierPath).find("<param name=\"differenceImages\" value=\"IMG_0002.jpg,IMG_0007\"/>") !=
        std::string::npos);
}

// A dome capture: its lights are the dome's .lp, so there is no independent estimate to compare
// a light file with; the prior model is compared at the dome's lights, beside Surrogate's fit
// from the same lights.
TEST_CASE("audit of a dome capture compares the prior fit at the dome lights", "[e2e][audit]") {
  const fs::path capture = e2e::freshDir("audit-dome") / "capture";
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture) + " --images " +
                        std::to_string(kImages) + " --width 400 --height 300 --sphere-radius 45 --seed 7 --formats jpeg")
              .exitCode == 0);
  const std::vector<TrueLight> truth = trueLights(capture);
  std::vector<test::Light> lights;
  for (const TrueLight& t : truth) lights.push_back(t.light);
  fs::rename(capture / "truth" / "lights.lp", capture / "dome.lp");
  fs::remove_all(capture / "truth");
  fs::create_directories(capture / "finished-files");
  test::writeText((capture / "finished-files" / "dome-fit.ptm").string(),
                  test::ptmText(test::fitPrior(photographs(capture, truth), lights), test::BiasRule::WithZero));

  const e2e::CommandResult r = e2e::surrogate("audit " + e2e::quote(capture) + " --lp dome.lp --json");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  const std::string models = r.output.substr(r.output.find("\"models\":"));
  CHECK(models.find("\"lightFile\":\"dome.lp\"") != std::string::npos);
  const double prior = jsonNumber(models.substr(models.find("\"prior\":")), "psnr");
  const double refit = jsonNumber(models.substr(models.find("\"refitPriorLights\":")), "psnr");
  CHECK(prior > 20);
  CHECK(std::abs(refit - prior) < 1.0);  // the same lights, the same basis: the same fit
  CHECK(r.output.find("\"reproduced\":true") != std::string::npos);
  CHECK(r.output.find("\"lightFiles\":[]") != std::string::npos);  // no estimate to compare it with
  CHECK(partOf(r.output, "lights") == "cannot tell");
}

TEST_CASE("audit refuses what it cannot audit and never writes into it", "[e2e][audit]") {
  const fs::path root = e2e::freshDir("audit-none");
  const fs::path capture = e2e::smallCapture(root, 8);
  const std::map<std::string, std::string> before = e2e::snapshot(capture);
  const e2e::CommandResult none = e2e::surrogate("audit " + e2e::quote(capture));
  CHECK(none.exitCode == 1);
  CHECK(none.output.find("holds no prior work to audit") != std::string::npos);
  CHECK(!fs::exists(capture.parent_path() / (capture.filename().string() + "-audit")));
  CHECK(e2e::snapshot(capture) == before);
  CHECK(!fs::exists(capture / ".surrogate"));

  const e2e::CommandResult notCapture = e2e::surrogate("audit " + e2e::quote(root / "nowhere"));
  CHECK(notCapture.exitCode == 1);
  CHECK(notCapture.output.find("does not exist") != std::string::npos);
  // A folder that is no capture is refused as one, from its source folders alone: nothing else
  // in it is walked (a home folder, or /, with its links).
  fs::create_directories(root / "not-a-capture" / "stuff");
  fs::create_directory_symlink("/", root / "not-a-capture" / "stuff" / "everything");
  const e2e::CommandResult noCapture = e2e::surrogate("audit " + e2e::quote(root / "not-a-capture"));
  CHECK(noCapture.exitCode == 1);
  CHECK(noCapture.output.find("is not a capture folder") != std::string::npos);

  // A work folder inside the folder audited, or a folder that is some other thing.
  const fs::path prior = rtibuilderCapture("audit-refusals");
  const e2e::CommandResult inside = e2e::surrogate("audit " + e2e::quote(prior) + " -o " + e2e::quote(prior / "work"));
  CHECK(inside.exitCode == 2);
  CHECK(inside.output.find("never writes into what it audits") != std::string::npos);
  CHECK(!fs::exists(prior / "work"));
  const e2e::CommandResult other = e2e::surrogate("audit " + e2e::quote(prior) + " -o " + e2e::quote(capture));
  CHECK(other.exitCode == 2);
  CHECK(other.output.find("is not the work folder of an audit of") != std::string::npos);

  // A prior file changed after its audit: the work folder keeps the audit of the files as read.
  const fs::path work = prior.parent_path() / "work";
  REQUIRE(e2e::surrogate("audit " + e2e::quote(prior) + " --quiet -o " + e2e::quote(work)).exitCode == 4);
  std::string lp = e2e::bytesOf(prior / "assembly-files" / "stela.lp");
  test::writeText((prior / "assembly-files" / "stela.lp").string(), lp + "\r\n");
  const e2e::CommandResult changed = e2e::surrogate("audit " + e2e::quote(prior) + " -o " + e2e::quote(work));
  CHECK(changed.exitCode == 1);
  CHECK(changed.output.find("has changed since the audit in") != std::string::npos);
  CHECK(changed.output.find("assembly-files/stela.lp changed") != std::string::npos);
}

TEST_CASE("a packed audit re-executes SOUND and a changed audit figure does not", "[e2e][audit]") {
  const fs::path capture = rtibuilderCapture("audit-pack");
  const fs::path bag = capture.parent_path() / "bag";
  REQUIRE(e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(bag) + " --quiet").exitCode == 0);
  const e2e::CommandResult sound = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(sound.output);
  CHECK(sound.exitCode == 0);
  CHECK(sound.output.find("SOUND") != std::string::npos);
  std::smatch step;
  REQUIRE(std::regex_search(sound.output, step, std::regex("ok +reexecute\\.(s[0-9]+)\\.Audit +reproduced exactly")));

  // The package audited as a folder is: its payload is the evidence, Surrogate's results left.
  const e2e::CommandResult packaged = e2e::surrogate("audit " + e2e::quote(bag) + " --json");
  INFO(packaged.output);
  CHECK(packaged.exitCode == 4);
  CHECK(partOf(packaged.output, "lights") == "differs");
  const std::string workCarrier = e2e::bytesOf(capture.parent_path() / "bag-audit" / "assembly-files" / "carrier.xml");
  CHECK(workCarrier.find("kind=\"package\"") != std::string::npos);
  CHECK(workCarrier.find("from=\"data/finished-files/stela.ptm\"") != std::string::npos);
  CHECK(workCarrier.find("from=\"data/assembly-files/lights.lp\"") == std::string::npos);  // Surrogate's own

  // The package's METS tells a repository where the evidence came from: one PREMIS transfer
  // event linking every copy, and each copy's originalName its name in the folder audited.
  // The audit of the package, packed in turn.
  const fs::path auditBag = capture.parent_path() / "bag-audit-bag";
  const e2e::CommandResult packedAudit = e2e::surrogate("pack " + e2e::quote(capture.parent_path() / "bag-audit") +
                                                       " -o " + e2e::quote(auditBag) + " --quiet");
  INFO(packedAudit.output);
  REQUIRE(packedAudit.exitCode == 0);
  const std::string mets = e2e::bytesOf(auditBag / "metadata" / "mets.xml");
  const std::string bagCarrier = e2e::bytesOf(auditBag / "data" / "assembly-files" / "carrier.xml");
  CHECK(mets.find("<premis:eventIdentifierValue>event-evidence-transfer</premis:eventIdentifierValue>") != std::string::npos);
  CHECK(mets.find("eventType/tra\">transfer</premis:eventType>") != std::string::npos);
  const std::regex evidenceRe("<evidence path=\"([^\"]+)\" from=\"([^\"]+)\"");
  std::size_t evidence = 0;
  for (std::sregex_iterator it(bagCarrier.begin(), bagCarrier.end(), evidenceRe), end; it != end; ++it, ++evidence) {
    const std::string path = (*it)[1], from = (*it)[2];
    INFO(path << " from " << from);
    CHECK(mets.find("<premis:linkingObjectIdentifierValue>data/" + path + "</premis:linkingObjectIdentifierValue>") !=
          std::string::npos);
    // The copy's own object, found by its payload path, names where it came from.
    const std::size_t object = mets.find("<premis:objectIdentifierValue>data/" + path + "</premis:objectIdentifierValue>");
    REQUIRE(object != std::string::npos);
    const std::size_t objectEnd = mets.find("</premis:object>", object);
    const std::string text = mets.substr(object, objectEnd - object);
    CHECK(text.find("<premis:originalName>" + from + "</premis:originalName>") != std::string::npos);
    CHECK(text.find("<premis:linkingEventIdentifierValue>event-evidence-transfer</premis:linkingEventIdentifierValue>") !=
          std::string::npos);
  }
  CHECK(evidence > 0);
  // And the package of the audit verifies: its METS valid against the METS and PREMIS schemas
  // and the one the stylesheet derives from its carrier.
  const e2e::CommandResult auditVerified = e2e::surrogate("verify " + e2e::quote(auditBag));
  INFO(auditVerified.output);
  CHECK(auditVerified.exitCode == 0);

  // The recorded median angle of the prior light file, changed in the bag's carrier.
  const std::string carrierPath = "data/assembly-files/carrier.xml";
  std::string carrier = e2e::bytesOf(bag / carrierPath);
  std::smatch median;
  REQUIRE(std::regex_search(carrier, median, std::regex("name=\"medianDegrees\" value=\"([0-9.]+)([0-9])\"")));
  const char last = median[2].str()[0] == '1' ? '2' : '1';  // one digit changed: same size
  carrier[median.position(2)] = last;
  rewriteInBag(bag, carrierPath, carrier);
  const e2e::CommandResult tampered = e2e::surrogate("verify " + e2e::quote(bag) + " --reexecute --threads 1");
  INFO(tampered.output);
  CHECK(tampered.exitCode != 0);
  CHECK(tampered.output.find("SOUND:") == std::string::npos);
  CHECK(std::regex_search(tampered.output, std::regex("FAIL +reexecute\\." + step[1].str() + "\\.Audit")));
  CHECK(tampered.output.find("medianDegrees") != std::string::npos);
}

TEST_CASE("a prior file that cannot be read is left out of the audit, which exits 1", "[e2e][audit]") {
  const fs::path capture = e2e::smallCapture(e2e::freshDir("audit-broken"), 8);
  fs::create_directories(capture / "finished-files");
  // A PTM_1.2 header cut off after the width (docs/formats.md, "Header": six lines).
  test::writeText((capture / "finished-files" / "old.ptm").string(), "PTM_1.2\nPTM_FORMAT_LRGB\n400\n");
  const e2e::CommandResult r = e2e::surrogate("audit " + e2e::quote(capture) + " --json");
  INFO(r.output);
  CHECK(r.exitCode == 1);
  CHECK(r.output.find("\"notAudited\":[{\"file\":\"finished-files/old.ptm\",\"reason\":\"") != std::string::npos);
  CHECK(r.output.find("\"models\":[]") != std::string::npos);
  CHECK(e2e::bytesOf(capture / "finished-files" / "old.ptm") == "PTM_1.2\nPTM_FORMAT_LRGB\n400\n");
}
