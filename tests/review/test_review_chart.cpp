// surrogate review and the colour chart, over HTTP against the real program: the state carries
// the chart the last run recorded (found, where, how well), and the chart marked on a frame or
// declined on the page is applied as --colour-chart with its reason, recorded as the option
// records it. The capture is generated with a ColorChecker and its place as truth
// (surrogate-generate --colour-chart), as in tests/e2e/test_colour_e2e.cpp.
#include <catch2/catch.hpp>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

#include "e2e_support.h"
#include "review_process.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json stateOf(httplib::Client& client) {
  const auto res = client.Get("/api/state");
  REQUIRE(res);
  REQUIRE(res->status == 200);
  return json::parse(res->body);
}

json applied(httplib::Client& client, const json& decisions, int port) {
  const auto res = client.Post("/api/apply", {{"Origin", "http://127.0.0.1:" + std::to_string(port)}},
                               decisions.dump(), "application/json");
  REQUIRE(res);
  INFO(res->body);
  REQUIRE(res->status == 200);
  return json::parse(res->body);
}

// The chart's corners the generator drew (truth/colour-chart.txt: "corners x1 y1 ... x4 y4").
std::vector<double> truthCorners(const fs::path& truthDir) {
  std::ifstream in(truthDir / "colour-chart.txt");
  std::vector<double> out;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (key == "corners")
      for (double v; s >> v;) out.push_back(v);
  }
  REQUIRE(out.size() == 8);
  return out;
}

}  // namespace

TEST_CASE("review: the chart the run recorded, and one marked or declined on the page", "[review]") {
  const fs::path dir = e2e::freshDir("review-chart");
  const fs::path capture = dir / "capture";
  auto r = e2e::runShell(std::string(GENERATOR_EXE) + " --out " + e2e::quote(capture) +
                         " --images 16 --width 900 --height 600 --sphere-radius 50 --formats jpeg --colour-chart --colour-cast warm");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  fs::rename(capture / "truth", dir / "truth");
  const std::vector<double> truth = truthCorners(dir / "truth");
  r = e2e::surrogate("run " + e2e::quote(capture) + " --quiet --no-report");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);

  review_test::ReviewProcess review(capture, {"--operator", "Ana Silva"}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);
  const json state = stateOf(client);
  // Found with no option: where (the shot and its file), its four corners near the drawn ones,
  // and the figures after correction.
  const json& found = state["chart"];
  INFO(found.dump());
  CHECK(found["asked"] == "auto");
  CHECK(found["outcome"] == "corrected");
  CHECK(found["method"] == "found");
  CHECK(found["image"].get<std::string>().rfind("IMG_", 0) == 0);
  CHECK(found["imagePath"].get<std::string>().find(found["image"].get<std::string>()) != std::string::npos);
  REQUIRE(found["corners"].size() == 8);
  for (int k = 0; k < 8; ++k) CHECK(std::fabs(found["corners"][k].get<double>() - truth[k]) < 3);
  CHECK(found["deltaE2000Mean"].get<double>() < found["deltaE2000MeanBefore"].get<double>());
  CHECK(found["deltaE2000Max"].get<double>() >= found["deltaE2000Mean"].get<double>());

  // Marked by hand on IMG_0002, as the page sends it: the option the run takes, the reason in
  // the run's note with the ColourCorrection parameters.
  json corners = json::array();
  for (double v : truth) corners.push_back(std::round(v * 10) / 10);
  json answer = applied(client, {{"revision", state["revision"]},
                                 {"chart", {{"image", "IMG_0002"}, {"corners", corners}, {"reason", "checked against the chart on the stand"}}}},
                        review.port());
  const auto options = answer["options"].get<std::vector<std::string>>();
  REQUIRE(options.size() == 6);
  CHECK(options[2] == "--colour-chart");
  CHECK(options[3].rfind("IMG_0002:", 0) == 0);
  CHECK(options[4] == "--reason");
  json after = stateOf(client);
  CHECK(after["chart"]["asked"] == "IMG_0002");
  CHECK(after["chart"]["method"] == "given");
  CHECK(after["chart"]["image"] == "IMG_0002");
  CHECK(after["chart"]["cornersGiven"] == options[3].substr(9));
  const json& notes = after["runs"].back()["notes"];
  CHECK(notes.dump().find("checked against the chart on the stand") != std::string::npos);

  // Declined: no chart, the images keep their colours, the reason recorded the same way.
  applied(client, {{"revision", after["revision"]}, {"chart", {{"none", true}, {"reason", "a test of the page"}}}}, review.port());
  after = stateOf(client);
  CHECK(after["chart"]["asked"] == "none");
  CHECK(after["chart"]["corners"].is_null());
  CHECK(after["chart"]["chart"] == "none");
  CHECK(after["chart"]["outcome"].is_null());  // the step records only the chart asked for
  CHECK(after["chart"]["method"].is_null());
  CHECK(after["runs"].back()["notes"].dump().find("a test of the page") != std::string::npos);
}
