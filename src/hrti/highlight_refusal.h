// HighlightRefusal: a refusal of highlight detection (stages/highlight_detection_stage.cpp) as
// an Error in the command line's words, which also holds what it is about: the review page says
// what to do on the page instead of naming options (review/refusal_words.h).
//
//   throw HighlightRefusal(Error(ErrorKind::Input, file, step, "... --forget-sphere 0 ..."),
//                          HighlightRefusal::Subject::CircleByHand, 0, {"IMG_0001", "IMG_0002"}, 8);
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace surrogate::hrti {

class HighlightRefusal : public Error {
 public:
  enum class Subject {
    CircleByHand,  // a circle given by hand shows no trustworthy highlight in most frames
    CircleFound,   // a circle found shows none in most frames: not a sphere
    Frames,        // frames with no trustworthy highlight on any sphere
  };
  HighlightRefusal(const Error& words, Subject subject, std::size_t sphere, std::vector<std::string> frames,
                   std::size_t images)
      : Error(words), subject(subject), sphere(sphere), frames(std::move(frames)), images(images) {}

  Subject subject;
  std::size_t sphere;               // counted from 0, as the carrier and the options do
  std::vector<std::string> frames;  // the frames concerned, by name (IMG_0003)
  std::size_t images;               // the frames the detection looked at
};

}  // namespace surrogate::hrti
