// The page's decisions as options of `surrogate run` (review/decisions.h), without a server: the
// colour chart's two forms, and what is refused before any run is asked for.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/error.h"
#include "review/decisions.h"

using surrogate::review::argumentsFor;
using Args = std::vector<std::string>;

TEST_CASE("review decisions: a chart marked on a frame is --colour-chart IMAGE:corners with its reason", "[review]") {
  // The corners as placed by eye (any number of decimals), written to 0.1 pixel as typed.
  const std::string body = R"({"chart": {"image": "IMG_0003", "corners": [100.04, 80, 700.26, 80.5, 699.95, 480, 99.5, 479.96],
                                          "reason": "the chart lies in shadow: not found"}})";
  CHECK(argumentsFor(body) == Args{"--colour-chart", "IMG_0003:100,80,700.3,80.5,700,480,99.5,480", "--reason",
                                   "the chart lies in shadow: not found"});
  // Without a reason: none is sent, as for a sphere.
  CHECK(argumentsFor(R"({"chart": {"image": "IMG_0001", "corners": [1, 2, 3, 4, 5, 6, 7, 8]}})") ==
        Args{"--colour-chart", "IMG_0001:1,2,3,4,5,6,7,8"});
}

TEST_CASE("review decisions: no colour chart is --colour-chart none", "[review]") {
  CHECK(argumentsFor(R"({"chart": {"none": true, "reason": "the chart was taken off before the shots"}})") ==
        Args{"--colour-chart", "none", "--reason", "the chart was taken off before the shots"});
}

TEST_CASE("review decisions: the chart comes after the highlights and before the exclusions", "[review]") {
  const std::string body = R"({"exclude": [{"image": "IMG_0007", "reason": "dark"}],
                               "chart": {"none": true, "reason": "no chart"},
                               "highlights": [{"image": "IMG_0002", "sphere": 0, "x": 10, "y": 20}]})";
  CHECK(argumentsFor(body) == Args{"--highlight", "IMG_0002:sphere1=10,20", "--colour-chart", "none", "--reason", "no chart",
                                   "--exclude", "IMG_0007", "--reason", "dark"});
}

TEST_CASE("review decisions: a chart that is not one is refused naming the member", "[review]") {
  auto refused = [](const std::string& body, const std::string& member) {
    try {
      argumentsFor(body);
      FAIL("accepted: " << body);
    } catch (const surrogate::Error& e) {
      CHECK(std::string(e.what()).find(member) != std::string::npos);
    }
  };
  refused(R"({"chart": "IMG_0003"})", "chart");
  refused(R"({"chart": {"image": "IMG_0003", "corners": [1, 2, 3, 4, 5, 6]}})", "chart.corners");
  refused(R"({"chart": {"image": "IMG_0003", "corners": [1, 2, 3, 4, 5, 6, 7, "8"]}})", "chart.corners[7]");
  refused(R"({"chart": {"image": "IMG_0003", "corners": [1, 2, 3, 4, 5, 6, 7, 1e308]}})", "chart.corners[7]");
  refused(R"({"chart": {"corners": [1, 2, 3, 4, 5, 6, 7, 8]}})", "image");
  refused(R"({"chart": {"none": false}})", "chart.none");
  refused(R"({"chart": {"none": true, "image": "IMG_0003"}})", "chart");
}
