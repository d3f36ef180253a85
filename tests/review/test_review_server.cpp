// surrogate review's server over HTTP, with cpp-httplib's client: what the page is given, who
// is refused, and that an Apply records exactly what `surrogate run` records for the same options
// (the carrier of a copy of the capture run with the options, byte for byte apart from times).
#include <catch2/catch.hpp>

#include <algorithm>

#include <httplib.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <fstream>
#include <regex>

#include "core/digest.h"
#include "core/error.h"
#include "e2e_support.h"
#include "review/review.h"
#include "review_process.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The carrier with what differs between two runs of the same decisions blanked: times and
// durations (an Apply is recorded as the `surrogate run` command line it stands for).
std::string masked(const std::string& xml) {
  std::string s = std::regex_replace(xml, std::regex(R"((time|started|ended|seconds)="[^"]*")"), "$1=\"T\"");
  s = std::regex_replace(s, std::regex(R"(<(modified|created)>[^<]*<)"), "<$1>T<");
  s = std::regex_replace(s, std::regex(R"(completed in [0-9.]+ s)"), "completed in T s");
  return s;
}

std::string carrierOf(const fs::path& capture) { return e2e::bytesOf(capture / "assembly-files/carrier.xml"); }

json stateOf(httplib::Client& client) {
  const auto res = client.Get("/api/state");
  REQUIRE(res);
  REQUIRE(res->status == 200);
  return json::parse(res->body);
}

httplib::Result apply(httplib::Client& client, const json& decisions, int port) {
  return client.Post("/api/apply", {{"Origin", "http://127.0.0.1:" + std::to_string(port)}}, decisions.dump(),
                     "application/json");
}

// "345.3": a number of whole pixels and tenths, as the options carry it.
std::string tenths(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  std::string s = text;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

}  // namespace

TEST_CASE("review: the page's state, frames and refusals over HTTP", "[review]") {
  const fs::path dir = e2e::freshDir("review-state");
  const fs::path capture = e2e::processedCapture(dir);
  review_test::ReviewProcess review(capture, {"--operator", "Ana Silva"}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);

  const json state = stateOf(client);
  // The revision is the carrier file's SHA-256, as sha256sum gives it.
  const e2e::CommandResult sum = e2e::runShell("sha256sum " + e2e::quote(capture / "assembly-files/carrier.xml"));
  CHECK(state["revision"] == "sha256:" + sum.output.substr(0, 64));
  CHECK(state["who"] == "Ana Silva");
  CHECK(state["frameWidth"] == 400);
  CHECK(state["frameHeight"] == 300);
  REQUIRE(state["frames"].size() == 8);
  CHECK(state["frames"][2]["name"] == "IMG_0003");
  REQUIRE(state["spheres"].size() == 1);
  CHECK(state["frames"][2]["highlights"].size() == 1);
  CHECK(state["frames"][2]["light"].contains("rmse"));
  CHECK(state["checks"].size() >= 5);
  CHECK(state["hemisphere"].get<std::string>().find("<svg") == 0);

  // The page itself: its script and stylesheet from this server only.
  const auto page = client.Get("/");
  REQUIRE(page);
  CHECK(page->status == 200);
  CHECK(page->get_header_value("Content-Security-Policy").find("default-src 'none'") != std::string::npos);
  CHECK(page->body.find("<script src=\"/review.js\">") != std::string::npos);
  CHECK(client.Get("/review.js")->status == 200);
  CHECK(client.Get("/review.css")->status == 200);

  // A frame's preview: a JPEG of the frame's size (400 x 300 fits the preview), made in memory.
  const auto before = e2e::snapshot(capture);
  const auto frame = client.Get("/frame/2.jpg");
  REQUIRE(frame);
  CHECK(frame->status == 200);
  CHECK(frame->get_header_value("Content-Type") == "image/jpeg");
  const cv::Mat decoded = cv::imdecode(std::vector<unsigned char>(frame->body.begin(), frame->body.end()), cv::IMREAD_COLOR);
  CHECK(decoded.cols == 400);
  CHECK(decoded.rows == 300);
  CHECK(client.Get("/frame/8.jpg")->status == 404);
  CHECK(client.Get("/nothing")->status == 404);
  CHECK(e2e::snapshot(capture) == before);  // reading never writes

  SECTION("another Host (DNS rebinding), another Origin, another site, or not JSON: refused") {
    CHECK(client.Get("/api/state", {{"Host", "evil.example:" + std::to_string(review.port())}})->status == 403);
    CHECK(client.Get("/", {{"Host", "127.0.0.1:1"}})->status == 403);
    CHECK(client.Get("/api/state", {{"Origin", "http://evil.example"}})->status == 403);
    CHECK(client.Get("/api/state", {{"Sec-Fetch-Site", "cross-site"}})->status == 403);
    const json decisions = {{"revision", state["revision"]}, {"title", "Hijacked"}};
    const auto foreign = client.Post("/api/apply", {{"Origin", "http://evil.example"}}, decisions.dump(), "application/json");
    REQUIRE(foreign);
    CHECK(foreign->status == 403);
    const auto plain = client.Post("/api/apply", decisions.dump(), "text/plain");
    REQUIRE(plain);
    CHECK(plain->status == 415);
    // localhost by name is the server too.
    CHECK(client.Get("/api/state", {{"Host", "localhost:" + std::to_string(review.port())}})->status == 200);
    CHECK(e2e::snapshot(capture) == before);
  }

  SECTION("the server listens on the loopback interface only") {
    const e2e::CommandResult addresses = e2e::runShell("hostname -I 2>/dev/null");
    std::string other;
    std::istringstream words(addresses.output);
    for (std::string a; words >> a;)
      if (a.find('.') != std::string::npos && a.rfind("127.", 0) != 0) {
        other = a;
        break;
      }
    if (other.empty()) {
      WARN("this machine has no address but the loopback one: the check is left out");
    } else {
      httplib::Client outside(other, review.port());
      outside.set_connection_timeout(2);
      const auto res = outside.Get("/api/state");
      CHECK_FALSE(res);  // no server there: the connection is refused
    }
  }
}

TEST_CASE("review: Apply records what surrogate run records for the same options", "[review]") {
  const fs::path dir = e2e::freshDir("review-apply");
  const fs::path capture = e2e::processedCapture(dir);
  const fs::path copyDir = dir / "copy";
  fs::create_directories(copyDir);
  fs::copy(capture, copyDir / "cap", fs::copy_options::recursive);
  const fs::path copy = copyDir / "cap";

  review_test::ReviewProcess review(capture, {"--operator", "Ana Silva"}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);
  const json state = stateOf(client);
  const json& sphere = state["spheres"][0];
  const json& highlight = state["frames"][2]["highlights"][0];
  // A circle a little off the detected one, and the highlight of IMG_0003 where it was found, as
  // a person places them by eye (tenths of a pixel at most).
  const double cx = std::round(sphere["cx"].get<double>()) + 0.26, cy = std::round(sphere["cy"].get<double>()) - 0.44,
               r = std::round(sphere["r"].get<double>()) + 1;
  const double hx = std::round(highlight["x"].get<double>()) + 0.04, hy = std::round(highlight["y"].get<double>());
  const json decisions = {
      {"revision", state["revision"]},
      {"title", "Stela 12"},
      {"creators", {"Ana Silva:photographer"}},
      {"rights", "Museum use only"},
      {"license", "https://creativecommons.org/licenses/by/4.0/"},
      {"meta", {{{"key", "site"}, {"value", "Abydos"}}}},
      {"spheres", {{{"cx", cx}, {"cy", cy}, {"r", r}, {"reason", "the rim is half a pixel further out"}}}},
      {"highlights", {{{"image", "IMG_0003"}, {"sphere", 0}, {"x", hx}, {"y", hy}}}},
      {"exclude", {{{"image", "IMG_0007"}, {"reason", "the flash did not fire"}}}},
      {"accept", {{{"check", "lights-clustered"}, {"reason", "the lights were checked on the stand"}}}},
  };
  const std::vector<std::string> expected = {
      "--operator", "Ana Silva",
      "--title", "Stela 12",
      "--creator", "Ana Silva:photographer",
      "--rights", "Museum use only",
      "--license", "https://creativecommons.org/licenses/by/4.0/",
      "--meta", "site=Abydos",
      "--sphere", tenths(cx) + "," + tenths(cy) + "," + tenths(r), "--reason", "the rim is half a pixel further out",
      "--highlight", "IMG_0003:sphere1=" + tenths(hx) + "," + tenths(hy),
      "--exclude", "IMG_0007", "--reason", "the flash did not fire",
      "--accept", "lights-clustered", "--reason", "the lights were checked on the stand",
  };

  SECTION("the same carrier as the options give, and the page's state says so") {
    const auto res = apply(client, decisions, review.port());
    REQUIRE(res);
    INFO(res->body);
    REQUIRE(res->status == 200);
    const json answer = json::parse(res->body);
    CHECK(answer["options"].get<std::vector<std::string>>() == expected);

    std::string line;
    for (const std::string& e : expected) line += " " + e2e::quote(e);
    const e2e::CommandResult run = e2e::surrogate("run " + e2e::quote(copy) + line);
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    const std::string fromPage = carrierOf(capture), fromOptions = carrierOf(copy);
    CHECK(fromPage.find("command=\"run\"") != std::string::npos);
    CHECK(masked(fromPage) == masked(fromOptions));
    // The decisions are there, with who and why, as the options record them.
    CHECK(fromPage.find("kind=\"exclude-image\" target=\"IMG_0007\"") != std::string::npos);
    CHECK(fromPage.find("who=\"Ana Silva\"") != std::string::npos);

    const json after = stateOf(client);
    CHECK(after["revision"] == answer["revision"]);
    CHECK(after["revision"] != state["revision"]);
    CHECK(after["header"]["title"] == "Stela 12");
    CHECK(after["frames"][6]["excluded"]["reason"] == "the flash did not fire");
    CHECK(after["spheres"][0]["source"] == "manual");
    CHECK(review.output().find("applied, as: surrogate run") != std::string::npos);
    // The report follows the new record, as after `surrogate run`.
    CHECK(e2e::bytesOf(capture / "finished-files/report.html").find("Stela 12") != std::string::npos);
  }

  SECTION("a stale page is refused and nothing is written") {
    const json old = {{"revision", "sha256:" + std::string(64, '0')}, {"title", "Stale"}};
    const std::string bytes = carrierOf(capture);
    const auto res = apply(client, old, review.port());
    REQUIRE(res);
    CHECK(res->status == 409);
    CHECK(json::parse(res->body)["error"] == "stale");
    CHECK(json::parse(res->body)["revision"] == state["revision"]);
    CHECK(carrierOf(capture) == bytes);
  }

  SECTION("a decision the options refuse is refused in their words, nothing written") {
    const json off = {{"revision", state["revision"]},
                      {"highlights", {{{"image", "IMG_0003"}, {"sphere", 0}, {"x", 5000}, {"y", 5}}}}};
    const auto before = e2e::snapshot(capture);
    const auto res = apply(client, off, review.port());
    REQUIRE(res);
    CHECK(res->status == 400);
    CHECK(json::parse(res->body)["message"].get<std::string>().find("--highlight") != std::string::npos);
    const json noReason = {{"revision", state["revision"]}, {"exclude", {{{"image", "IMG_0002"}, {"reason", ""}}}}};
    const auto refused = apply(client, noReason, review.port());
    REQUIRE(refused);
    CHECK(refused->status == 400);
    CHECK(json::parse(refused->body)["message"].get<std::string>().find("needs a reason") != std::string::npos);
    // A number too large for a pixel (1e308 overflows once rounded to tenths): named, refused.
    const json huge = {{"revision", state["revision"]}, {"spheres", {{{"cx", 1e308}, {"cy", 5}, {"r", 5}}}}};
    const auto tooLarge = apply(client, huge, review.port());
    REQUIRE(tooLarge);
    CHECK(tooLarge->status == 400);
    CHECK_THAT(json::parse(tooLarge->body)["message"].get<std::string>(), Catch::StartsWith("spheres[0].cx: must be"));
    CHECK(e2e::snapshot(capture) == before);
  }

  SECTION("a run that fails is said, and recorded in the history as surrogate run records it") {
    // A highlight in the frame but off the sphere: the highlight step refuses it.
    const json off = {{"revision", state["revision"]},
                      {"highlights", {{{"image", "IMG_0003"}, {"sphere", 0}, {"x", 5}, {"y", 5}}}}};
    const auto res = apply(client, off, review.port());
    REQUIRE(res);
    CHECK(res->status == 422);
    const json answer = json::parse(res->body);
    CHECK(answer["error"] == "failed");
    CHECK(answer["revision"] != state["revision"]);
    const json after = stateOf(client);
    CHECK(after["runs"].back()["outcome"] == "failed");
    CHECK(after["runs"].back()["command"] == "run");
    // The results are the previous run's, untouched.
    CHECK(after["spheres"] == state["spheres"]);
  }

  SECTION("while another command holds the capture, Apply says a run is going") {
    fs::create_directories(capture / ".surrogate");
    const std::string lockFile = e2e::quote(capture / ".surrogate/lock");
    // flock(1) holds the capture's lock (an flock on .surrogate/lock, capture/lock.h) for 5 s.
    const e2e::CommandResult held = e2e::runShell("flock -n " + lockFile + " sleep 5 > /dev/null 2>&1 & sleep 0.3");
    REQUIRE(held.exitCode == 0);
    const std::string bytes = carrierOf(capture);
    const auto res = apply(client, {{"revision", state["revision"]}, {"title", "Meanwhile"}}, review.port());
    REQUIRE(res);
    CHECK(res->status == 423);
    CHECK(json::parse(res->body)["message"].get<std::string>().find("another Surrogate command") != std::string::npos);
    CHECK(carrierOf(capture) == bytes);
  }
  CHECK(review.stop() == 0);
}

TEST_CASE("review: a capture a check stopped goes to a verified package without a typed option", "[review]") {
  // Frame 3 exposed at 5 %: the exposure check stops the first run (hrti/light_checks.h).
  const fs::path dir = e2e::freshDir("review-stopped");
  const fs::path capture = dir / "capture";
  REQUIRE(e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture) +
                        " --images 8 --width 400 --height 300 --sphere-radius 45 --seed 7 --dark-frame 3")
              .exitCode == 0);
  fs::remove_all(capture / "truth");

  review_test::ReviewProcess review(capture, {}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);
  json state = stateOf(client);
  CHECK(state["revision"] == "none");
  CHECK(state["frames"].size() == 8);
  CHECK(state["spheres"].empty());
  // The first run, as the page's "Run the capture" sends it: no decision.
  auto res = apply(client, {{"revision", "none"}}, review.port());
  REQUIRE(res);
  CHECK(res->status == 422);
  CHECK(json::parse(res->body)["message"].get<std::string>().find("exposure-outlier") != std::string::npos);
  state = stateOf(client);
  CHECK(state["stoppedBy"] == json::array({"exposure-outlier"}));
  bool failedShown = false;
  for (const json& c : state["checks"]) failedShown = failedShown || (c["name"] == "exposure-outlier" && c["status"] == "failed");
  CHECK(failedShown);

  // The frame left out in the page, with its reason.
  res = apply(client,
              {{"revision", state["revision"]}, {"exclude", {{{"image", "IMG_0003"}, {"reason", "the flash fired weakly"}}}}},
              review.port());
  REQUIRE(res);
  INFO(res->body);
  REQUIRE(res->status == 200);
  state = stateOf(client);
  CHECK(state["runs"].back()["outcome"] == "completed");
  CHECK(state["stoppedBy"].empty());
  CHECK(review.stop() == 0);

  const fs::path package = dir / "stela.zip";
  const e2e::CommandResult pack = e2e::surrogate("pack " + e2e::quote(capture) + " -o " + e2e::quote(package) + " --quiet");
  INFO(pack.output);
  REQUIRE(pack.exitCode == 0);
  const e2e::CommandResult verify = e2e::surrogate("verify " + e2e::quote(package) + " --quiet");
  INFO(verify.output);
  CHECK(verify.exitCode == 0);
}

TEST_CASE("review: --quiet prints the address alone and --verbose each step an Apply runs", "[review]") {
  const fs::path dir = e2e::freshDir("review-verbosity");
  const fs::path capture = e2e::smallCapture(dir, 8);
  {
    review_test::ReviewProcess quiet(capture, {"--quiet"}, dir / "quiet.log");
    httplib::Client client = review_test::pageClient(quiet);
    auto res = apply(client, {{"revision", "none"}}, quiet.port());
    REQUIRE(res);
    CHECK(res->status == 200);
    CHECK(quiet.stop() == 0);
    // One line: the address; no "applied, as:" line, no hint.
    const std::string out = quiet.output();
    INFO(out);
    CHECK(std::count(out.begin(), out.end(), '\n') == 1);
    CHECK(out.rfind("Review of ", 0) == 0);
  }
  review_test::ReviewProcess verbose(capture, {"--verbose"}, dir / "verbose.log");
  httplib::Client client = review_test::pageClient(verbose);
  const json state = stateOf(client);
  auto res = apply(client,
                   {{"revision", state["revision"]}, {"exclude", {{{"image", "IMG_0003"}, {"reason", "a test"}}}}},
                   verbose.port());
  REQUIRE(res);
  CHECK(res->status == 200);
  CHECK(verbose.stop() == 0);
  const std::string out = verbose.output();
  INFO(out);
  CHECK_THAT(out, Catch::Contains("\n  running: "));
  CHECK_THAT(out, Catch::Contains("applied, as: surrogate run "));
  CHECK(e2e::surrogate("review " + e2e::quote(capture) + " --no-browser --quiet --verbose").exitCode == 2);
}

TEST_CASE("review: the revision is checked again under the lock, against the carrier's SHA-256", "[review]") {
  // The runner calls requireRevision once it holds the capture's lock: a commit by another
  // command between the page's check and the lock is refused there (409), not run over.
  const fs::path capture = e2e::processedCapture(e2e::freshDir("review-revision"));
  const fs::path carrierFile = capture / "assembly-files/carrier.xml";
  // The revision as sha256sum(1) gives it, not as the code under test computes it.
  const e2e::CommandResult sum = e2e::runShell("sha256sum " + e2e::quote(carrierFile));
  REQUIRE(sum.exitCode == 0);
  const std::string revision = "sha256:" + sum.output.substr(0, 64);
  CHECK_NOTHROW(surrogate::review::requireRevision(capture, revision));
  std::ofstream(carrierFile, std::ios::app) << " ";
  try {
    surrogate::review::requireRevision(capture, revision);
    FAIL("a changed carrier passed as the page's revision");
  } catch (const surrogate::Error& e) {
    CHECK(std::string(e.step()) == surrogate::review::kStaleStep);
    CHECK(e.kind() == surrogate::ErrorKind::Usage);
    CHECK_THAT(e.message(), Catch::Contains("nothing was applied"));
  }
  const fs::path fresh = e2e::smallCapture(e2e::freshDir("review-revision-none"));
  CHECK_NOTHROW(surrogate::review::requireRevision(fresh, "none"));
  CHECK_THROWS_AS(surrogate::review::requireRevision(fresh, revision), surrogate::Error);
}
