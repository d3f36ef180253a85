#include "stages/decode_stage.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "archive/digest.h"
#include "core/parallel.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "pipeline/spill_stack.h"
#include "stages/inputs.h"

namespace surrogate::stages {

namespace {

std::string pixelDigest(const Image& im) {
  archive::MultiDigest d({archive::DigestAlgorithm::Sha256});
  d.update(im.pixels.data(), im.pixels.size() * sizeof(std::uint16_t));
  return d.hex(archive::DigestAlgorithm::Sha256);
}

Image toRgb(const Image& im) {
  if (im.channels == 3) return im;
  Image rgb(im.width, im.height, 3);
  rgb.bitsPerSample = im.bitsPerSample;
  rgb.transfer = im.transfer;
  for (std::size_t i = 0; i < im.pixels.size(); ++i)
    rgb.pixels[3 * i] = rgb.pixels[3 * i + 1] = rgb.pixels[3 * i + 2] = im.pixels[i];
  return rgb;
}

// How many images to decode at once: the threads, but no more than the memory budget allows
// (a decoded image plus the decoder's working memory, about 4 copies of 16-bit RGB).
int concurrentDecodes(const pipeline::RunSettings& s, int width, int height) {
  const std::size_t perImage = std::size_t(width) * height * 3 * 2 * 4;
  const std::size_t byMemory = std::max<std::size_t>(1, s.memoryBudget / std::max<std::size_t>(perImage, 1));
  return static_cast<int>(std::min<std::size_t>(effectiveThreads(s.threads), byMemory));
}

}  // namespace

void DecodeStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const image::RawDecodeSettings settings = image::RawDecodeSettings::fromParameters(
      [&] {
        std::vector<std::pair<std::string, std::string>> p;
        for (const carrier::Param& param : step.params) p.emplace_back(param.name, param.value);
        return p;
      }());
  const int n = static_cast<int>(inputs->size());

  // The first image fixes the stack's size (ingest already checked all are the same).
  struct Decoded {
    image::DecodeReport report;
    int width = 0, height = 0, channels = 0, bits = 0;
    Transfer transfer = Transfer::Srgb;
    std::string digest;
  };
  std::vector<Decoded> decoded(n);
  std::shared_ptr<pipeline::SpillStack> rgb, lum;
  std::mutex createMutex;
  std::atomic<int> done{0};

  auto decodeOne = [&](int i) {
    Decoded& d = decoded[i];
    const Image im = image::decodeImage(ctx.pathOf((*inputs)[i].fileId), settings, &d.report);
    d.width = im.width;
    d.height = im.height;
    d.channels = im.channels;
    d.bits = im.bitsPerSample;
    d.transfer = im.transfer;
    d.digest = pixelDigest(im);
    {
      std::lock_guard<std::mutex> lock(createMutex);
      if (!rgb) {
        rgb = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 3, Transfer::Srgb);
        lum = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 1, im.transfer);
      }
    }
    if (im.width != rgb->width() || im.height != rgb->height()) {
      throwInputError((*inputs)[i].relativePath, "image decode",
                      "decodes to " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                          " pixels, unlike the first image (" + std::to_string(rgb->width()) + "x" +
                          std::to_string(rgb->height()) + "); all images must have the same size");
    }
    lum->write(i, luminance(im));
    rgb->write(i, im.transfer == Transfer::Linear ? image::srgbEncode(toRgb(im)) : toRgb(im));
    ctx.progress("Decoding images", double(++done) / n);
  };

  decodeOne(0);
  const int workers = concurrentDecodes(ctx.settings, rgb->width(), rgb->height());
  parallelFor(static_cast<std::size_t>(n - 1), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) decodeOne(static_cast<int>(i) + 1);
  });

  for (int i = 0; i < n; ++i) {
    const Decoded& d = decoded[i];
    carrier::DataItem& item = result.add("decoded");
    item.set("image", (*inputs)[i].fileId)
        .set("decoder", d.report.decoder)
        .set("width", d.width)
        .set("height", d.height)
        .set("channels", d.channels)
        .set("bitsPerSample", d.bits)
        .set("transfer", d.transfer == Transfer::Linear ? "linear" : "srgb");
    if (d.report.blackLevel >= 0) item.set("blackLevel", d.report.blackLevel);
    if (d.report.whiteLevel >= 0) item.set("whiteLevel", d.report.whiteLevel);
    if (!d.report.whiteBalanceMultipliers.empty()) {
      std::string wb;
      for (double m : d.report.whiteBalanceMultipliers)
        wb += (wb.empty() ? "" : " ") + carrier::formatNumber(m);
      item.set("whiteBalance", wb);
    }
    item.set("pixelSha256", d.digest);
  }
  result.add("value").set("name", "fitInputTransfer").set("value", "srgb");
  result.add("value").set("name", "detectionInputTransfer")
      .set("value", lum->transfer() == Transfer::Linear ? "linear" : "srgb");
  ctx.put(kRgbStack, std::static_pointer_cast<ImageStack>(rgb));
  ctx.put(kLuminanceStack, std::static_pointer_cast<ImageStack>(lum));
}

}  // namespace surrogate::stages
