#include "stages/preprocess_stages.h"

#include <algorithm>
#include <array>
#include <vector>

#include "core/error.h"
#include "core/text.h"
#include "core/parallel.h"
#include "pipeline/context.h"
#include "stages/decode_stage.h"
#include "stages/inputs.h"
#include "stages/light_stages.h"
#include "stages/outputs.h"
#include "stages/preprocess.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

bool inside(const PixelRect& r, const ImageStack& s) {
  return r.x >= 0 && r.y >= 0 && r.width > 0 && r.height > 0 &&
         static_cast<long long>(r.x) + r.width <= s.width() &&
         static_cast<long long>(r.y) + r.height <= s.height();
}

[[noreturn]] void outsideFrame(const std::string& option, const PixelRect& r, const ImageStack& s,
                               const carrier::Step& step) {
  throw Error(ErrorKind::Usage, option + " " + r.text(), step.component,
              "the rectangle reaches outside the " + sizeText(s.width(), s.height()) +
                  " images this step receives (carrier step " + step.id +
                  "); give X,Y,W,H with X+W <= " + std::to_string(s.width()) + " and Y+H <= " +
                  std::to_string(s.height()));
}

void recordValue(carrier::Result& result, const std::string& name, const std::string& value,
                 const std::string& unit = "") {
  carrier::DataItem& item = result.add("value").set("name", name).set("value", value);
  if (!unit.empty()) item.set("unit", unit);
}

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

// ---- WhiteBalance ---------------------------------------------------------------------------

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

// ---- Crop -----------------------------------------------------------------------------------

pipeline::StageInfo CropStage::info() {
  // No defaults: the plan gives every parameter (a crop has no rectangle by default).
  pipeline::StageInfo info = pipeline::checkedBy<CropOptions>(
      {kComponent, "1",
       "Crop the images the fit reads to a rectangle (given, or the largest clear of the "
       "spheres); light estimation keeps the full frame",
       pipeline::PlanSlot::Preprocessing});
  info.reads = pipeline::alwaysReads({kRgbStack, kLuminanceStack});
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
      ctx.carrier.addLog("warning", step.id,
                         "no sphere detection in this process list (light directions from a file): "
                         "the automatic crop keeps the full frame");
  }
  recordValue(result, "method", options.method == "user" ? "given by the user" : "automatic: largest rectangle clear of the spheres");
  recordValue(result, "rectangle", rect.text(), "pixels x,y,w,h");
  recordValue(result, "inputSize", sizeText(input->width(), input->height()), "pixels");
  recordValue(result, "outputSize", sizeText(rect.width, rect.height), "pixels");
  if (rect.x != 0 || rect.y != 0 || rect.width != input->width() || rect.height != input->height())
    ctx.put<ImageStack>(kRgbStack, std::make_shared<CropStack>(input, rect));
  ctx.carrier.addLog("info", step.id,
                     "the fit reads the rectangle " + rect.text() + " (" +
                         (options.method == "user" ? "given by the user" : "clear of the spheres") +
                         ") of the " + sizeText(input->width(), input->height()) + " images");
}

// ---- Resize ---------------------------------------------------------------------------------

pipeline::StageInfo ResizeStage::info() {
  // No defaults: the plan gives every parameter (a factor or a size).
  pipeline::StageInfo info = pipeline::checkedBy<ResizeOptions>(
      {kComponent, "1",
       "Reduce the images the fit reads: area-weighted mean in linear light, exact integer "
       "weights",
       pipeline::PlanSlot::Preprocessing});
  info.reads = pipeline::alwaysReads({kRgbStack});
  return info;
}

void ResizeStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto input = ctx.get<ImageStack>(kRgbStack);
  const ResizeOptions options = ResizeOptions::fromParameters(parametersOf(step), "--resize");
  const auto [w, h] = options.outputSize(input->width(), input->height(), "--resize");
  recordValue(result, "inputSize", sizeText(input->width(), input->height()), "pixels");
  recordValue(result, "outputSize", sizeText(w, h), "pixels");
  recordValue(result, "filter", "area: area-weighted mean in linear light, exact integer weights");
  if (w != input->width() || h != input->height())
    ctx.put<ImageStack>(kRgbStack, std::make_shared<AreaResizeStack>(input, w, h));
  ctx.carrier.addLog("info", step.id,
                     "the fit reads the images reduced from " + sizeText(input->width(), input->height()) +
                         " to " + sizeText(w, h) + " pixels (area averaging)");
}

}  // namespace surrogate::stages
