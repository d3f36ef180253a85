// A run's values against the frame they apply to (run/request_checks.h, with the rules of
// stages/frame_checks.h): circles and highlights given by hand, sphere search regions, crop and
// grey-region rectangles. Every bad value is Error(Usage) naming the option and the value.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "run/plan.h"
#include "run/request_checks.h"
#include "stages/frame_checks.h"
#include "stages/preprocess.h"

using namespace surrogate;
using namespace surrogate::run;
using namespace surrogate::stages;

namespace {

constexpr int kWidth = 400, kHeight = 300;

RunRequest withSphere(const std::string& value) {
  RunRequest r;
  r.stageInterventions.push_back({"SphereDetection", {"manual-sphere", "0", value, "", "", "typo"}});
  return r;
}

RunRequest withHighlight(RunRequest r, const std::string& target, const std::string& value) {
  r.stageInterventions.push_back({"HighlightDetection", {"manual-highlight", target, value, "", "", "rim"}});
  return r;
}

RunRequest withRegions(const std::string& regions) {
  RunRequest r;
  r.stageParams.push_back({"SphereDetection", "regions", regions});
  return r;
}

// The Error(Usage) the check throws: its file names the option and value, its message is
// returned for further checks. Fails the test when nothing (or another error) is thrown.
std::string refusal(const RunRequest& r, const std::string& option) {
  try {
    checkRequestAgainstFrame(r, kWidth, kHeight);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Usage);
    CHECK(e.file() == option);
    CHECK_FALSE(e.message().empty());
    return e.message();
  }
  FAIL("no error for " << option);
  return "";
}

}  // namespace

TEST_CASE("a request with no values given by hand passes the frame checks") {
  CHECK_NOTHROW(checkRequestAgainstFrame(RunRequest{}, kWidth, kHeight));
}

TEST_CASE("a circle given by hand must have its centre in the frame and half its disc, or fit its smaller side") {
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("339,57,45"), kWidth, kHeight));
  // Cut by the frame's edge, centre inside: a real capture can have that.
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("390,10,45"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("0,0,150"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("399,299,3"), kWidth, kHeight));

  CHECK_THAT(refusal(withSphere("900,57,45"), "--sphere 900,57,45"), Catch::Contains("400x300"));
  CHECK_THAT(refusal(withSphere("339,300,45"), "--sphere 339,300,45"), Catch::Contains("CY from 0 to 299"));
  CHECK_THAT(refusal(withSphere("339,57,400"), "--sphere 339,57,400"), Catch::Contains("150"));
  // Larger than half the smaller side: taken when at least half of its disc is in the frame
  // (54 % here), refused below (46 %).
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("339,57,150.5"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withSphere("200,150,160"), kWidth, kHeight));
  CHECK_THAT(refusal(withSphere("339,57,200"), "--sphere 339,57,200"), Catch::Contains("only 46 % of its disc"));
  CHECK_THAT(refusal(withSphere("339,57,-5"), "--sphere 339,57,-5"), Catch::Contains("above 0"));
  CHECK_THAT(refusal(withSphere("339,57,0"), "--sphere 339,57,0"), Catch::Contains("above 0"));
  CHECK_THAT(refusal(withSphere("339,57,2"), "--sphere 339,57,2"), Catch::Contains("at least 3"));
  CHECK_THAT(refusal(withSphere("-1,57,45"), "--sphere -1,57,45"), Catch::Contains("negative"));
  CHECK_THAT(refusal(withSphere("339,57,nan"), "--sphere 339,57,nan"), Catch::Contains("finite"));
  CHECK_THAT(refusal(withSphere("339,57"), "--sphere 339,57"), Catch::Contains("3 comma-separated numbers"));
  CHECK_THAT(refusal(withSphere("339,57,45,"), "--sphere 339,57,45,"), Catch::Contains("CX,CY,R"));
}

TEST_CASE("the share of a disc in the frame is the circular segment's closed form") {
  // A disc cut by one edge at distance d from its centre loses the segment
  // r^2 acos(d / r) - d sqrt(r^2 - d^2).
  const double r = 100;
  for (const double d : {0.0, 30.0, 70.0}) {
    const double segment = r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d);
    // The left edge of the frame is at x = -0.5.
    CHECK(stages::discShareInFrame(d - 0.5, 150, r, 1000, 300) == Approx(1 - segment / (M_PI * r * r)).epsilon(1e-3));  // 4096 strips
  }
  CHECK(stages::discShareInFrame(500, 150, r, 1000, 300) == Approx(1).epsilon(1e-4));
}

TEST_CASE("the second of two circles given by hand is checked too") {
  RunRequest r = withSphere("100,100,40");
  r.stageInterventions.push_back({"SphereDetection", {"manual-sphere", "1", "450,100,40", "", "", "typo"}});
  refusal(r, "--sphere 450,100,40");
}

TEST_CASE("a sphere search region must lie wholly inside the frame") {
  CHECK_NOTHROW(checkRequestAgainstFrame(withRegions("280,0,120,120"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withRegions("0,0,400,300"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withRegions("0,0,100,100;280,0,120,120"), kWidth, kHeight));

  CHECK_THAT(refusal(withRegions("500,0,100,100"), "--sphere-roi 500,0,100,100"), Catch::Contains("400x300"));
  CHECK_THAT(refusal(withRegions("350,0,100,100"), "--sphere-roi 350,0,100,100"),
             Catch::Contains("X+W must be at most 400"));
  CHECK_THAT(refusal(withRegions("0,250,100,100"), "--sphere-roi 0,250,100,100"),
             Catch::Contains("Y+H at most 300"));
  refusal(withRegions("0,0,100,100;280,0,121,120"), "--sphere-roi 280,0,121,120");
  CHECK_THAT(refusal(withRegions("-5,0,100,100"), "--sphere-roi -5,0,100,100"), Catch::Contains("negative"));
  CHECK_THAT(refusal(withRegions("0,0,0,100"), "--sphere-roi 0,0,0,100"), Catch::Contains("above 0"));
  CHECK_THAT(refusal(withRegions("0,0,10.5,100"), "--sphere-roi 0,0,10.5,100"), Catch::Contains("whole numbers"));
  refusal(withRegions("0,0,100"), "--sphere-roi 0,0,100");
}

TEST_CASE("a highlight given by hand must be in the frame") {
  // The refusals name the sphere as a person types it (IMG_0004:sphere1), whatever the form given.
  CHECK_NOTHROW(checkRequestAgainstFrame(withHighlight({}, "IMG_0004:0", "326,70"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withHighlight({}, "IMG_0004:2", "399,299"), kWidth, kHeight));

  CHECK_THAT(refusal(withHighlight({}, "IMG_0004:0", "400,70"), "--highlight IMG_0004:sphere1=400,70"),
             Catch::Contains("X must be from 0 to 399"));
  refusal(withHighlight({}, "IMG_0004:0", "10,900"), "--highlight IMG_0004:sphere1=10,900");
  refusal(withHighlight({}, "IMG_0004:0", "-1,70"), "--highlight IMG_0004:sphere1=-1,70");
  refusal(withHighlight({}, "IMG_0004:0", "inf,70"), "--highlight IMG_0004:sphere1=inf,70");
  refusal(withHighlight({}, "IMG_0004:0", "326"), "--highlight IMG_0004:sphere1=326");
  refusal(withHighlight({}, "IMG_0004:x", "326,70"), "--highlight IMG_0004:x=326,70");
}

TEST_CASE("a highlight on a sphere given by hand must lie on that circle and name one of them") {
  const RunRequest sphere = withSphere("339,57,45");
  CHECK_NOTHROW(checkRequestAgainstFrame(withHighlight(sphere, "IMG_0004:0", "326,70"), kWidth, kHeight));
  // On the outline, and within half a pixel past it (the light direction clamps onto it).
  CHECK_NOTHROW(checkRequestAgainstFrame(withHighlight(sphere, "IMG_0004:0", "384,57"), kWidth, kHeight));
  CHECK_NOTHROW(checkRequestAgainstFrame(withHighlight(sphere, "IMG_0004:0", "384.4,57"), kWidth, kHeight));

  CHECK_THAT(refusal(withHighlight(sphere, "IMG_0004:0", "100,200"), "--highlight IMG_0004:sphere1=100,200"),
             Catch::Contains("339,57,45"));
  refusal(withHighlight(sphere, "IMG_0004:0", "385,57"), "--highlight IMG_0004:sphere1=385,57");
  CHECK_THAT(refusal(withHighlight(sphere, "IMG_0004:1", "326,70"), "--highlight IMG_0004:sphere2=326,70"),
             Catch::Contains("names sphere 2, but only 1 circle(s) are given by hand"));
}

TEST_CASE("crop and grey-region rectangles in full-frame pixels must lie inside the frame") {
  RunRequest ok;
  WhiteBalanceOptions wb = WhiteBalanceOptions::fromText("region:20,200,60,60");
  ok.preprocessing.push_back({"WhiteBalance", wb.toParameters()});
  ok.preprocessing.push_back({"Crop", CropOptions::fromText("0,100,250,200").toParameters()});
  ok.preprocessing.push_back({"Resize", ResizeOptions::fromText("0.5").toParameters()});
  CHECK_NOTHROW(checkRequestAgainstFrame(ok, kWidth, kHeight));

  RunRequest badWb;
  badWb.preprocessing.push_back({"WhiteBalance", WhiteBalanceOptions::fromText("region:380,200,60,60").toParameters()});
  refusal(badWb, "--wb-region 380,200,60,60");

  RunRequest badCrop;
  badCrop.preprocessing.push_back({"Crop", CropOptions::fromText("0,100,250,250").toParameters()});
  CHECK_THAT(refusal(badCrop, "--crop 0,100,250,250"), Catch::Contains("Y+H at most 300"));

  RunRequest autoCrop;
  autoCrop.preprocessing.push_back({"Crop", CropOptions::fromText("auto").toParameters()});
  CHECK_NOTHROW(checkRequestAgainstFrame(autoCrop, kWidth, kHeight));
}

TEST_CASE("the frame-free rules are the ones the command line applies") {
  CHECK(sphereCircleProblem(900, 57, 45).empty());  // no frame: only what needs none
  CHECK_FALSE(sphereCircleProblem(339, 57, -5).empty());
  CHECK_FALSE(sphereCircleProblem(339, 57, 0).empty());
  CHECK_FALSE(sphereCircleProblem(-3, 57, 45).empty());
  CHECK(highlightPointProblem(900, 900).empty());
  CHECK_FALSE(highlightPointProblem(-1, 0).empty());
  CHECK(frameRegionProblem(500, 0, 100, 100).empty());
  CHECK_FALSE(frameRegionProblem(0, 0, -5, 10).empty());
}
