#include "stages/held_out_quality.h"

#include "core/error.h"
#include "core/stack.h"
#include "fit/basis.h"
#include "fit/render.h"
#include "publish/learned_layout.h"
#include "publish/learned_reader.h"
#include "publish/plane_decode.h"

namespace surrogate::stages {

fit::LearnedModel learnedAsViewed(const fit::LearnedModel& model, const publish::PublishOptions& web) {
  publish::PublishOptions whole = web;
  whole.tiles = publish::TileLayout::None;
  return learnedAsViewed(model, publish::webLayoutOf(model, whole));
}

fit::LearnedModel learnedAsViewed(const fit::LearnedModel& model, const publish::WebLayoutFiles& files) {
  std::vector<std::vector<std::uint8_t>> planes;
  for (int j = 0; j < model.planes / 3; ++j) {
    const std::string name = "plane_" + std::to_string(j) + ".jpg";
    for (const auto& [file, bytes] : files.files)
      if (file == name) planes.push_back(publish::decodePlaneJpeg(bytes, model.width, model.height, name));
  }
  fit::LearnedModel viewed = model;
  publish::setLearnedCoefficients(planes, &viewed);
  return viewed;
}

void checkHoldoutCount(int count, int photographs) {
  if (count < 1 || count > photographs - 4)
    throw Error(ErrorKind::Usage, "--holdout " + std::to_string(count), "command line",
                "leave out at most " + std::to_string(std::max(0, photographs - 4)) + " of the " +
                    std::to_string(photographs) + " photographs, and at least 1: the fit without them keeps at least 4");
}

HeldOutQuality measureHeldOut(const ImageStack& stack, const std::vector<std::array<double, 3>>& lights,
                              const ModelRecipe& recipe, int count) {
  const int N = stack.size();
  checkHoldoutCount(count, N);
  HeldOutQuality q;
  q.indices = fit::chooseHeldOut(lights, count);
  std::vector<int> keep;
  std::vector<std::array<double, 3>> kept;
  for (int i = 0, j = 0; i < N; ++i) {
    if (j < count && q.indices[j] == i) {
      ++j;
      continue;
    }
    keep.push_back(i);
    kept.push_back(lights[i]);
  }
  const SubsetStack training(stack, keep);

  std::unique_ptr<fit::Relightable> classic;
  fit::LearnedModel learned;
  const bool isLearned = fit::isLearnedBasisName(recipe.basis);
  if (isLearned) {
    fit::LearnedOptions options = recipe.learned;
    options.kind = fit::parseLearnedKind(recipe.basis);
    options.threads = recipe.threads;
    options.progress = nullptr;
    learned = learnedAsViewed(fit::fitLearned(training, kept, options), recipe.web);
  } else {
    fit::FitOptions options;
    options.basis = fit::parseBasis(recipe.basis);
    options.threads = recipe.threads;
    if (fit::isPtm(options.basis)) classic = fit::makeRelightable(fit::fitPtm(training, kept, options));
    else classic = fit::makeRelightable(fit::fitHsh(training, kept, options));
  }
  std::vector<fit::HeldOutScore> blends;
  for (int i : q.indices) {
    const Image truth = readImage(stack, i);
    const Image relit = isLearned ? fit::renderLearned(learned, lights[i], recipe.threads)
                                  : classic->render(lights[i], fit::RenderOptions{});
    q.perLight.push_back(fit::compareImages(relit, truth));
    blends.push_back(fit::compareImages(fit::nearestPhotographBlend(training, kept, lights[i]), truth));
  }
  q.model = fit::meanScore(q.perLight);
  q.nearestBlend = fit::meanScore(blends);
  return q;
}

}  // namespace surrogate::stages
