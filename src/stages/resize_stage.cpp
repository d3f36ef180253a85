#include "stages/resize_stage.h"

#include "core/error.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/preprocess.h"
#include "stages/preprocess_steps.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

pipeline::StageInfo ResizeStage::info() {
  // No defaults: the plan gives every parameter (a factor or a size).
  pipeline::StageInfo info = pipeline::checkedBy<ResizeOptions>(
      {kComponent, "1",
       "Reduce the images the fit reads: area-weighted mean in linear light, exact integer "
       "weights",
       pipeline::PlanSlot::Preprocessing});
  info.reads = pipeline::alwaysReads({kRgbStack, kStackFrame});
  return info;
}

void ResizeStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto input = ctx.get<ImageStack>(kRgbStack);
  const ResizeOptions options = ResizeOptions::fromParameters(parametersOf(step), "--resize");
  const auto [w, h] = options.outputSize(input->width(), input->height(), "--resize");
  recordValue(result, "inputSize", sizeText(input->width(), input->height()), "pixels");
  recordValue(result, "outputSize", sizeText(w, h), "pixels");
  recordValue(result, "filter", "area: area-weighted mean in linear light, exact integer weights");
  if (w != input->width() || h != input->height()) {
    ctx.put<ImageStack>(kRgbStack, std::make_shared<AreaResizeStack>(input, w, h));
    // A reduced pixel's centre is the centre of the block it averages (near lights need it).
    if (ctx.has(kStackFrame)) {
      StackFrame frame = *ctx.get<StackFrame>(kStackFrame);
      const double fx = double(input->width()) / w, fy = double(input->height()) / h;
      frame.x0 += frame.sx * (fx - 1) / 2;
      frame.y0 += frame.sy * (fy - 1) / 2;
      frame.sx *= fx;
      frame.sy *= fy;
      ctx.put(kStackFrame, std::make_shared<StackFrame>(frame));
    }
  }
  ctx.carrier.addLog("info", step.id,
                     "the fit reads the images reduced from " + sizeText(input->width(), input->height()) +
                         " to " + sizeText(w, h) + " pixels (area averaging)");
}

}  // namespace surrogate::stages
