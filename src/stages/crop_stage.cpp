#include "stages/crop_stage.h"

#include "carrier/advice.h"

#include <algorithm>

#include "core/text.h"
#include "core/error.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/preprocess.h"
#include "stages/preprocess_steps.h"
#include "stages/sphere_detection_stage.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

pipeline::StageInfo CropStage::info() {
  // No defaults: the plan gives every parameter (a crop has no rectangle by default).
  pipeline::StageInfo info = pipeline::checkedBy<CropOptions>(
      {kComponent, "1",
       "Crop the images the fit reads to a rectangle (given, or the largest clear of the "
       "spheres); light estimation keeps the full frame",
       pipeline::PlanSlot::Preprocessing});
  info.reads = pipeline::alwaysReads({kRgbStack, kLuminanceStack, kStackFrame});
  return info;
}

void CropStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto input = ctx.get<ImageStack>(kRgbStack);
  const CropOptions options = CropOptions::fromParameters(parametersOf(step), "--crop");
  PixelRect rect = options.rect;
  if (options.method == "user") {
    if (!inside(rect, *input)) outsideFrame("--crop", rect, *input, step);
  } else {
    // The spheres as the carrier records them (full-frame coordinates).
    const auto full = ctx.get<ImageStack>(kLuminanceStack);
    if (input->width() != full->width() || input->height() != full->height())
      throw Error(ErrorKind::Input, "--crop auto", step.component,
                  "the automatic crop needs the full frame, but an earlier step of the process "
                  "list changed the image size; put Crop before Resize");
    std::vector<Circle> circles;
    bool detection = false;
    for (const carrier::Step& s : ctx.carrier.process) {
      if (s.component != SphereDetectionStage::kComponent) continue;
      detection = true;
      const carrier::Result* r = ctx.carrier.findResult(s.id);
      if (!r || r->status != "completed")
        throw Error(ErrorKind::Input, "--crop auto", step.component,
                    "the automatic crop needs the spheres, but step " + s.id +
                        " (" + s.component + ") has not run before it; put Crop after the light "
                        "estimation steps");
      for (const carrier::DataItem* d : r->itemsOf("sphere"))
        circles.push_back({d->number("cx"), d->number("cy"), d->number("r")});
    }
    rect = largestClearRectangle(input->width(), input->height(), circles, options.margin);
    if (rect.area() == 0)
      throw Error(ErrorKind::Input, "--crop auto", step.component,
                  "the spheres leave no rectangle clear of them; give the rectangle with --crop X,Y,W,H");
    recordValue(result, "spheresAvoided", std::to_string(circles.size()));
    recordValue(result, "margin", formatNumber(options.margin), "fraction of the sphere radius");
    if (!detection)
      carrier::addWarning(ctx.carrier, step.id,
                          {"--crop auto keeps the full frame: the lights come from a file, so no spheres were found "
                           "to crop away",
                           carrier::Usable::Yes, "the results cover the whole frame, spheres included",
                           "if the spheres should be cropped away, give the rectangle with --crop X,Y,W,H",
                           ""});
  }
  recordValue(result, "method", options.method == "user" ? "given by the user" : "automatic: largest rectangle clear of the spheres");
  recordValue(result, "rectangle", rect.text(), "pixels x,y,w,h");
  recordValue(result, "inputSize", sizeText(input->width(), input->height()), "pixels");
  recordValue(result, "outputSize", sizeText(rect.width, rect.height), "pixels");
  if (rect.x != 0 || rect.y != 0 || rect.width != input->width() || rect.height != input->height()) {
    ctx.put<ImageStack>(kRgbStack, std::make_shared<CropStack>(input, rect));
    // Near lights need to know where the fitted pixels lie in the frame.
    if (ctx.has(kStackFrame)) {
      StackFrame frame = *ctx.get<StackFrame>(kStackFrame);
      frame.x0 += frame.sx * rect.x;
      frame.y0 += frame.sy * rect.y;
      ctx.put(kStackFrame, std::make_shared<StackFrame>(frame));
    }
  }
  ctx.carrier.addLog("info", step.id,
                     "the fit reads the rectangle " + rect.text() + " (" +
                         (options.method == "user" ? "given by the user" : "clear of the spheres") +
                         ") of the " + sizeText(input->width(), input->height()) + " images");
}

}  // namespace surrogate::stages
