// The page's words for highlight detection's refusals (review/refusal_words.h): what to do on
// the page, spheres numbered from 1, no option named; any other refusal in the run's own words.
#include <catch2/catch.hpp>

#include <string>

#include "core/error.h"
#include "hrti/highlight_refusal.h"
#include "review/refusal_words.h"

using surrogate::Error;
using surrogate::ErrorKind;
using surrogate::hrti::HighlightRefusal;
using surrogate::review::pageWords;

namespace {

// As the stage words it for the command line.
const Error kRunWords(ErrorKind::Input, "--sphere 300,80,45", "highlight detection",
                      "the circle given by hand for sphere 1 ... withdraw it with --forget-sphere sphere1 --reason \"...\"");

}  // namespace

TEST_CASE("review words: a circle by hand off the sphere is dragged or withdrawn on the page", "[review]") {
  const std::string w = pageWords(HighlightRefusal(kRunWords, HighlightRefusal::Subject::CircleByHand, 0,
                                                   {"IMG_0001", "IMG_0002", "IMG_0004"}, 4));
  CHECK(w.find("The circle placed by hand for sphere 1 shows no trustworthy highlight in 3 of 4 frames "
               "(IMG_0001; IMG_0002; IMG_0004)") == 0);
  CHECK(w.find("Drag the circle onto sphere 1") != std::string::npos);
  CHECK(w.find("\u201cWithdraw\u2026\u201d beside it under Standing decisions") != std::string::npos);
  CHECK(w.find("--") == std::string::npos);
  CHECK(w.find("sphere 0") == std::string::npos);
}

TEST_CASE("review words: the second sphere found is sphere 2, and a long list of frames is cut", "[review]") {
  std::vector<std::string> frames;
  for (int n = 1; n <= 12; ++n) frames.push_back("IMG_00" + std::string(n < 10 ? "0" : "") + std::to_string(n));
  const std::string w = pageWords(HighlightRefusal(kRunWords, HighlightRefusal::Subject::CircleFound, 1, frames, 20));
  CHECK(w.find("The circle Surrogate found for sphere 2 shows no trustworthy highlight in 12 of 20 frames") == 0);
  CHECK(w.find("IMG_0008; and 4 more)") != std::string::npos);
  CHECK(w.find("--") == std::string::npos);
}

TEST_CASE("review words: a frame without a highlight is left out or given one on the page", "[review]") {
  const std::string one = pageWords(HighlightRefusal(kRunWords, HighlightRefusal::Subject::Frames, 0, {"IMG_0003"}, 8));
  CHECK(one == "IMG_0003 shows no trustworthy highlight on any sphere, so its light direction cannot be measured: "
               "click it among the frames, then leave it out (tick \u201cLeave this frame out\u201d and say why) or "
               "place its highlight by hand (\u201cPlace this frame\u2019s highlight\u201d, then click the centre of "
               "the highlight).");
  const std::string two = pageWords(HighlightRefusal(kRunWords, HighlightRefusal::Subject::Frames, 0, {"IMG_0003", "IMG_0005"}, 8));
  CHECK(two.find("IMG_0003; IMG_0005 show no trustworthy highlight on any sphere, so their light direction cannot be "
                 "measured: for each, click it") == 0);
}

TEST_CASE("review words: any other refusal is said in the run's words", "[review]") {
  CHECK(pageWords(kRunWords) == kRunWords.text());
}
