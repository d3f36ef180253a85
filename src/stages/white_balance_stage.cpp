#include "stages/white_balance_stage.h"

#include <algorithm>
#include <array>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"
#include "core/error.h"
#include "pipeline/context.h"
#include "stages/decode_stage.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/preprocess.h"
#include "stages/preprocess_steps.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace {

// The decoded images' transfer per the ImageDecode result ("linear" for camera raw).
bool decodedFromRaw(const carrier::Carrier& c) {
  for (const carrier::Step& s : c.process) {
    if (s.component != DecodeStage::kComponent) continue;
    if (const carrier::Result* r = c.findResult(s.id))
      for (const carrier::DataItem* d : r->itemsOf("decoded"))
        if (d->get("transfer") == std::string("linear")) return true;
  }
  return false;
}

std::string decodeWhiteBalance(const carrier::Carrier& c) {
  for (const carrier::Step& s : c.process)
    if (s.component == DecodeStage::kComponent) return s.param("whiteBalance", "camera");
  return "camera";
}

// Mean linear R, G, B of `region` in each image, read in bands of rows; independent per image,
// so the values do not depend on the thread count.
std::vector<std::array<double, 3>> regionMeans(const ImageStack& stack, const PixelRect& region,
                                               int threads) {
  std::vector<std::array<double, 3>> means(stack.size());
  // One table for every sample value (the stack is 3-channel RGB from ImageDecode).
  std::vector<double> table(65536);
  for (int v = 0; v < 65536; ++v) table[v] = toLinear(static_cast<std::uint16_t>(v), stack.transfer());
  const int ch = stack.channels();
  parallelFor(static_cast<std::size_t>(stack.size()), 1, threads, [&](std::size_t b, std::size_t e) {
    std::vector<std::uint16_t> rows;
    for (std::size_t i = b; i < e; ++i) {
      std::array<double, 3> sum{0, 0, 0};
      for (int y0 = region.y; y0 < region.y + region.height; y0 += 64) {
        const int y1 = std::min(region.y + region.height, y0 + 64);
        rows.resize(static_cast<std::size_t>(y1 - y0) * stack.width() * ch);
        stack.readRows(static_cast<int>(i), y0, y1, rows.data());
        for (int y = 0; y < y1 - y0; ++y)
          for (int x = region.x; x < region.x + region.width; ++x)
            for (int c = 0; c < 3; ++c)
              sum[c] += table[rows[(static_cast<std::size_t>(y) * stack.width() + x) * ch + (ch == 3 ? c : 0)]];
      }
      const double n = static_cast<double>(region.area());
      means[i] = {sum[0] / n, sum[1] / n, sum[2] / n};
    }
  });
  return means;
}

}  // namespace

pipeline::StageInfo WhiteBalanceStage::info() {
  pipeline::StageInfo info = pipeline::withOptions<WhiteBalanceOptions>(
      {kComponent, "1",
       "White balance of the images the fit reads: per-channel gains in linear light (as "
       "shot, from a grey region, or given), and the encoding the fit reads (sRGB or linear)",
       pipeline::PlanSlot::Preprocessing});
  info.reads = pipeline::alwaysReads({kRgbStack, kInputImages});
  return info;
}

void WhiteBalanceStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto input = ctx.get<ImageStack>(kRgbStack);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const WhiteBalanceOptions options = WhiteBalanceOptions::fromParameters(parametersOf(step), "--wb");
  ctx.progress("White balance", 0);

  std::array<double, 3> gains{1, 1, 1};
  if (options.mode == "as-shot") {
    const bool raw = decodedFromRaw(ctx.carrier);
    if (raw && decodeWhiteBalance(ctx.carrier) != "camera")
      throw Error(ErrorKind::Usage, "--wb as-shot", step.component,
                  "the camera raws are decoded with whiteBalance=" + decodeWhiteBalance(ctx.carrier) +
                      ", not the camera's as-shot multipliers; use --raw whiteBalance=camera, or "
                      "--wb region:X,Y,W,H or --wb multipliers:R,G,B");
    recordValue(result, "asShotAppliedBy",
                raw ? "ImageDecode (LibRaw whiteBalance=camera: the camera's as-shot multipliers, "
                      "recorded per image in its decoded/@whiteBalance)"
                    : "the camera or the software that made the images (not recorded)");
  } else if (options.mode == "multipliers") {
    gains = options.multipliers;
  } else {
    if (!inside(options.region, *input)) outsideFrame("--wb-region", options.region, *input, step);
    const auto means = regionMeans(*input, options.region, effectiveThreads(ctx.settings.threads));
    for (std::size_t i = 0; i < means.size() && i < inputs->size(); ++i)
      result.add("imageValue").set("image", (*inputs)[i].fileId).set("name", "greyRegionMean")
          .set("value", formatNumber(means[i][0]) + " " + formatNumber(means[i][1]) +
                            " " + formatNumber(means[i][2]))
          .set("unit", "linear R G B (0..1)");
    gains = greyRegionGains(means, "--wb-region " + options.region.text());
    recordValue(result, "greyRegion", options.region.text(), "pixels x,y,w,h");
  }
  recordValue(result, "mode", options.mode);
  recordValue(result, "gainR", formatNumber(gains[0]), "linear multiplier");
  recordValue(result, "gainG", formatNumber(gains[1]), "linear multiplier");
  recordValue(result, "gainB", formatNumber(gains[2]), "linear multiplier");
  recordValue(result, "outputSpace", options.outputSpace);

  const Transfer out = options.outputSpace == "linear" ? Transfer::Linear : Transfer::Srgb;
  if (gains != std::array<double, 3>{1, 1, 1} || out != input->transfer()) {
    ctx.put<ImageStack>(kRgbStack, std::make_shared<TableStack>(
                                       input, gainTables(gains, input->transfer(), out), out));
  }
  ctx.carrier.addLog("info", step.id,
                     "white balance " + options.mode + ": gains R " + fixedDecimals(gains[0], 4) + ", G " +
                         fixedDecimals(gains[1], 4) + ", B " + fixedDecimals(gains[2], 4) + "; the fit reads " +
                         (out == Transfer::Linear ? "linear" : "sRGB-encoded") + " values");
  ctx.progress("White balance", 1);
}

}  // namespace surrogate::stages
