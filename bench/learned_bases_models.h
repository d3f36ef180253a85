// The models learned_bases.cpp compares at held-out lights, each as a viewer gets it: fitted on
// one set of photographs, then a function that relights it, its bytes and its fit time.
//
//   Fold fold = ...;                                   // fit stack + lights, test lights
//   Evaluated e = evaluateSurrogateFile(fold, fit::Basis::Hsh3, threads);
//   Image relit = e.relight(fold.testLights[0]);
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack.h"
#include "fit/basis.h"
#include "fit/learned.h"

namespace surrogate::bench {

using Light = std::array<double, 3>;

// One split of a capture: the photographs fitted and the lights (and photographs) left out.
struct Fold {
  std::shared_ptr<ImageStack> fit;
  std::vector<Light> fitLights;
  std::vector<Image> test;
  std::vector<Light> testLights;
};

// A fitted model ready to relight. `bytes`: what a viewer downloads (web layouts: info.json and
// the planes) or the file's size (.ptm/.rti); `seconds`: the fit's wall time (0 when not fitted
// here).
struct Evaluated {
  std::string name;
  std::uint64_t bytes = 0;
  double seconds = 0;
  std::function<Image(const Light&)> relight;
};

// fitPtm/fitHsh, relit by fit::render: the file (`web` false) or its web copy at `quality`
// written, read back by readWebLayout and relit (`web` true).
Evaluated evaluateSurrogate(const Fold& fold, fit::Basis basis, bool web, int quality, int threads);

// fitLearned, then the artefact a viewer gets (JPEG quality from `quality` on the first plane to
// `lastQuality` on the last): webLayoutOf -> a temporary folder ->
// readWebLayout -> renderLearned.
Evaluated evaluateLearned(const Fold& fold, const fit::LearnedOptions& options, int quality, int lastQuality,
                          const std::filesystem::path& scratch);

// A layout fitted elsewhere (relight-cli's): readWebLayout, then renderLearned or fit::render.
Evaluated evaluateLayout(const std::filesystem::path& folder, int threads);

// The baseline: the `count` nearest photographs in angle, weights 1 / angle.
Evaluated evaluateNearest(const Fold& fold, int count);

// Bytes of a web layout on disk: info.json and plane_* files (what relight's figure counts).
std::uint64_t layoutBytes(const std::filesystem::path& folder);

}  // namespace surrogate::bench
