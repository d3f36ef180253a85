// describeCarrier, interventionText and shownValue on a carrier built here, field by field, so
// that every expected value is one this test put in.
#include <catch2/catch.hpp>

#include "carrier/summary.h"

using namespace surrogate;
using namespace surrogate::carrier;

namespace {

Carrier sampleCarrier() {
  Carrier c;
  c.header.title = "Stela 12";
  c.header.created = "2026-01-02T10:00:00Z";
  c.header.modified = "2026-01-03T11:00:00Z";
  c.header.machine.hostname = "studio-pc";
  c.header.rights = "Museum use only";
  c.header.creators = {{"Ana Silva", "photographer"}};
  c.header.meta = {{"site", "Museum store 3"}};
  FileRecord image;
  image.path = "original-captures/IMG_0001.dng";
  image.imageSize = std::make_pair(40, 30);
  c.putFile(image);
  FileRecord lp;
  lp.path = "dome.lp";
  c.putFile(lp);
  FileRecord note;
  note.path = "notes.txt";
  c.putFile(note);

  Step& ingest = c.addStep("CaptureIngest", "3");
  ingest.setParam("lp", "dome.lp");
  ingest.interventions.push_back({"exclude-image", "IMG_0003", "", "Ana Silva", "2026-01-02T10:00:00Z", "no flash"});
  Step& spheres = c.addStep("SphereDetection", "4");
  spheres.interventions.push_back({"manual-sphere", "0", "339.00000000000006,56.999999999999993,45", "Ben Okafor",
                                   "2026-01-03T11:00:00Z", "cut by the frame edge"});
  spheres.interventions.push_back({"manual-highlight", "IMG_0002:1", "12.34,30", "Ben Okafor", "2026-01-03T11:00:00Z",
                                   "glare"});
  c.addStep("RtiFit", "2");
  Result done;
  done.step = "s1";
  done.seconds = 2.5;
  c.data.push_back(done);
  Result failed;
  failed.step = "s2";
  failed.status = "failed";
  failed.seconds = 0.25;
  c.data.push_back(failed);
  c.header.runs.push_back({"r1", "run", "Ana Silva", "2026-01-02T10:00:00Z", "2026-01-02T10:01:00Z", "completed",
                           {"--exclude", "IMG_0003"}, {"first run"}});
  return c;
}

}  // namespace

TEST_CASE("describeCarrier gives the header, steps, decisions and runs as recorded", "[carrier][summary]") {
  const CarrierSummary s = describeCarrier(sampleCarrier());
  CHECK(s.title == "Stela 12");
  CHECK(s.created == "2026-01-02T10:00:00Z");
  CHECK(s.modified == "2026-01-03T11:00:00Z");
  CHECK(s.hostname == "studio-pc");
  CHECK(s.rights == "Museum use only");
  CHECK(s.license.empty());
  REQUIRE(s.creators.size() == 1);
  CHECK(s.creators[0].name == "Ana Silva");
  CHECK(s.creators[0].role == "photographer");
  CHECK(s.metadata == std::vector<std::pair<std::string, std::string>>{{"site", "Museum store 3"}});
  CHECK(s.files == 3);
  CHECK(s.images == 1);  // the one file with an image size

  REQUIRE(s.steps.size() == 3);
  CHECK(s.steps[0].id == "s1");
  CHECK(s.steps[0].component == "CaptureIngest");
  CHECK(s.steps[0].version == "3");
  CHECK(s.steps[0].status == "completed");
  CHECK(s.steps[0].seconds == 2.5);
  CHECK(s.steps[0].interventions == 1);
  CHECK(s.steps[1].status == "failed");
  CHECK(s.steps[1].seconds == 0.25);
  CHECK(s.steps[1].interventions == 2);
  CHECK(s.steps[2].status == "not run");  // no result
  CHECK(s.steps[2].seconds == 0);

  REQUIRE(s.decisions.size() == 3);
  CHECK(s.decisions[0].step == "s1");
  CHECK(s.decisions[0].component == "CaptureIngest");
  CHECK(s.decisions[0].what == "IMG_0003 is left out of every step");
  CHECK(s.decisions[1].step == "s2");
  CHECK(s.decisions[1].intervention.who == "Ben Okafor");
  CHECK(s.decisions[1].what == "circle of sphere 1 given by hand (x,y,r 339,57,45)");
  CHECK(s.decisions[2].what == "highlight of IMG_0002 on sphere 2 given by hand (x,y 12.3,30)");
  REQUIRE(s.exclusions.size() == 1);
  CHECK(s.exclusions[0].intervention.target == "IMG_0003");
  CHECK(s.exclusions[0].intervention.reason == "no flash");
  CHECK(s.domeLights == std::vector<std::string>{"dome.lp"});
  REQUIRE(s.runs.size() == 1);
  CHECK(s.runs[0].arguments == std::vector<std::string>{"--exclude", "IMG_0003"});
}

TEST_CASE("describeCarrier of an empty carrier has nothing but empty lists", "[carrier][summary]") {
  const CarrierSummary s = describeCarrier(Carrier{});
  CHECK(s.files == 0);
  CHECK(s.images == 0);
  CHECK(s.steps.empty());
  CHECK(s.decisions.empty());
  CHECK(s.exclusions.empty());
  CHECK(s.domeLights.empty());
  CHECK(s.runs.empty());
}

TEST_CASE("interventionText says what each kind of intervention does", "[carrier][summary]") {
  CHECK(interventionText({"manual-highlight", "IMG_0002", "1,2", "", "", ""}) ==
        "highlight of IMG_0002 given by hand (x,y 1,2)");
  CHECK(interventionText({"accept-changed-original", "original-captures/a.dng", "", "", "", ""}) ==
        "the changed original-captures/a.dng accepted as it is now");
  CHECK(interventionText({"future-kind", "t", "0.5", "", "", ""}) == "t = 0.5");
  CHECK(interventionText({"future-kind", "t", "", "", "", ""}) == "t");
}

TEST_CASE("shownValue rounds the numbers of a list to 0.1 and leaves text alone", "[carrier][summary]") {
  CHECK(shownValue("326.00000000000006,70") == "326,70");
  CHECK(shownValue("12.34") == "12.3");
  CHECK(shownValue("auto") == "auto");
  CHECK(shownValue("1,x") == "1,x");
  CHECK(shownValue("") == "");
  CHECK(shownValue("nan") == "nan");
}
