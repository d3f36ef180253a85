// `surrogate info` on a carrier with a colour step (tests/report/colour_carrier.h): the "colour"
// object of the JSON and the text lines; nothing for a carrier without the step.
#include <catch2/catch.hpp>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "cli/info_print.h"
#include "colour_carrier.h"

using namespace surrogate;
using Catch::Contains;

namespace {

std::string json(const carrier::Carrier& c) {
  JsonWriter j;
  j.beginObject();
  cli::colourJson(j, c);
  j.endObject();
  return j.str();
}

std::string text(const carrier::Carrier& c) {
  std::ostringstream out;
  std::streambuf* was = std::cout.rdbuf(out.rdbuf());
  cli::printColour(c);
  std::cout.rdbuf(was);
  return out.str();
}

}  // namespace

TEST_CASE("info JSON gives the chart and its figures and levels and every patch of a corrected carrier") {
  const std::string j = json(colour_test::correctedCarrier());
  CHECK_THAT(j, Contains("{\"colour\":{\"step\":\"s2\",\"chart\":\"auto\",\"corrected\":true,\"outcome\":\"corrected\","
                         "\"image\":\"jpeg-exports/IMG_0003.jpg\",\"method\":\"found\","
                         "\"reference\":\"colorchecker-classic-2014\","
                         "\"referenceTitle\":\"ColorChecker Classic (charts made after November 2014)\","
                         "\"model\":\"matrix\",\"framesMeasured\":24,"));
  CHECK_THAT(j, Contains("\"deltaE2000\":{\"meanBefore\":6.1,\"maxBefore\":14.6,\"mean\":1.65,\"max\":2.8,"
                         "\"meanHeldOut\":2.1,\"maxHeldOut\":4.3}"));
  CHECK_THAT(j, Contains("\"qualityLevels\":[\"FADGI 2023: 3 star\",\"Metamorfoze 2019: below every level\"]"));
  // In chart order from 0, with the recorded Lab values; the patch not measured has nulls.
  CHECK_THAT(j, Contains("\"patches\":[{\"index\":0,\"name\":\"dark skin\",\"frames\":24,"
                         "\"reference\":[37.54,14.37,14.92],\"before\":[37.54,17.37,14.92],"
                         "\"corrected\":[38.04,14.37,14.92],\"deltaE2000Before\":3,\"deltaE2000\":0.5,"
                         "\"deltaE2000HeldOut\":0.7}"));
  CHECK_THAT(j, Contains("{\"index\":10,\"name\":\"yellow green\",\"frames\":0,\"reference\":[71.77,-24.13,58.19],"
                         "\"before\":null,\"corrected\":null,\"deltaE2000Before\":null,\"deltaE2000\":null,"
                         "\"deltaE2000HeldOut\":null}"));
  CHECK_THAT(j, Contains("{\"index\":23,\"name\":\"black 2 (1.5 D)\""));
  std::size_t patches = 0;
  for (std::size_t at = j.find("{\"index\":"); at != std::string::npos; at = j.find("{\"index\":", at + 1)) ++patches;
  CHECK(patches == 24);
}

TEST_CASE("info JSON of colours kept gives the outcome and the image searched alone") {
  CHECK(json(colour_test::notFoundCarrier()) ==
        "{\"colour\":{\"step\":\"s2\",\"chart\":\"auto\",\"corrected\":false,\"outcome\":\"no ColorChecker found in "
        "jpeg-exports/IMG_0003.jpg: the images keep their colours\",\"image\":\"jpeg-exports/IMG_0003.jpg\"}}");
  CHECK(json(colour_test::noChartCarrier()) ==
        "{\"colour\":{\"step\":\"s2\",\"chart\":\"none\",\"corrected\":false,\"outcome\":\"no colour chart "
        "(chart=none): the images keep their colours\",\"image\":null}}");
}

TEST_CASE("info text gives the colour in one or two lines") {
  CHECK(text(colour_test::correctedCarrier()) ==
        "  colour:  corrected with ColorChecker Classic (charts made after November 2014), found in "
        "jpeg-exports/IMG_0003.jpg, 24 frames; matrix: CIEDE2000 mean 6.10 -> 1.65, max 14.60 -> 2.80 "
        "(held out: mean 2.10, max 4.30)\n"
        "           FADGI 2023: 3 star; Metamorfoze 2019: below every level\n");
  CHECK(text(colour_test::notFoundCarrier()) ==
        "  colour:  no ColorChecker found in jpeg-exports/IMG_0003.jpg: the images keep their colours\n");
}

TEST_CASE("info on a carrier without a colour step has no colour object or line") {
  carrier::Carrier c = carrier::newCarrier("Older carrier", {});
  c.addStep("CaptureIngest", "1");
  CHECK(json(c) == "{}");
  CHECK(text(c).empty());
}

TEST_CASE("the carrier JSON holds the colour object after the lights only when the step is there") {
  JsonWriter with;
  cli::carrierJson(with, colour_test::correctedCarrier());
  CHECK_THAT(with.str(), Contains("\"lights\":[],\"colour\":{\"step\":\"s2\""));
  CHECK_THAT(with.str(), Contains("]},\"warnings\":["));
  carrier::Carrier old = carrier::newCarrier("Older carrier", {});
  old.addStep("CaptureIngest", "1");
  JsonWriter without;
  cli::carrierJson(without, old);
  CHECK_THAT(without.str(), Contains("\"lights\":[],\"warnings\":["));
  CHECK_THAT(without.str(), !Contains("\"colour\""));
}

TEST_CASE("the colour step as recorded is valid carrier XML and info reads it back the same") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "surrogate-test-info-colour";
  std::filesystem::create_directories(dir);
  const carrier::Carrier made = colour_test::correctedCarrier();
  carrier::saveCarrier(made, dir / "carrier.xml");  // validates against xsd/carrier.xsd
  CHECK(json(carrier::loadCarrier(dir / "carrier.xml")) == json(made));
  std::filesystem::remove_all(dir);
}
