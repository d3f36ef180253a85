// learned-layout-sample OUT: writes OUT/rbf and OUT/bln, the web layouts (quality 100) of two
// hand-made learned models of 64 x 48 texels (learned_samples.h), for the OpenLIME browser
// test (tests/publish/browser/openlime_learned.test.js), which draws them in OpenLIME and
// compares the canvas with `surrogate render`.
#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "publish/learned_layout.h"
#include "learned_samples.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: learned-layout-sample OUT\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  surrogate::publish::PublishOptions options;
  options.quality = 100;
  options.tiles = surrogate::publish::TileLayout::None;
  try {
    std::filesystem::create_directories(out);
    for (auto kind : {surrogate::fit::LearnedKind::Rbf, surrogate::fit::LearnedKind::Bilinear})
      surrogate::publish::writeWebLayoutFolder(
          surrogate::publish::webLayoutOf(learnedsample::handMade(kind, 64, 48, 0.25), options),
          out / surrogate::fit::learnedKindName(kind));
  } catch (const surrogate::Error& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
