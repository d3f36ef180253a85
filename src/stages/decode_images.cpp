#include "stages/decode_images.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "archive/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "pipeline/spill_stack.h"

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
// (a decoded image plus the decoder's working memory: about 4 copies of 16-bit RGB).
int concurrentDecodes(const pipeline::RunSettings& s, int width, int height) {
  const std::size_t perImage = std::max<std::size_t>(1, std::size_t(width) * height * 3 * 2 * 4);
  const std::size_t byMemory = std::max<std::size_t>(1, s.memoryBudget / perImage);
  return static_cast<int>(std::min<std::size_t>(effectiveThreads(s.threads), byMemory));
}

}  // namespace

DecodedStacks decodeImages(const std::vector<std::filesystem::path>& files,
                           const image::RawDecodeSettings& settings,
                           const pipeline::RunSettings& run) {
  const int n = static_cast<int>(files.size());
  DecodedStacks out;
  out.images.resize(n);
  std::shared_ptr<pipeline::SpillStack> rgb, lum;
  std::mutex createMutex;
  std::atomic<int> done{0};

  auto decodeOne = [&](int i) {
    DecodedImage& d = out.images[i];
    const Image im = image::decodeImage(files[i], settings, &d.report);
    d.width = im.width;
    d.height = im.height;
    d.channels = im.channels;
    d.bitsPerSample = im.bitsPerSample;
    d.transfer = im.transfer;
    d.pixelSha256 = pixelDigest(im);
    {
      std::lock_guard<std::mutex> lock(createMutex);
      if (!rgb) {
        rgb = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 3, Transfer::Srgb);
        lum = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 1, im.transfer);
      }
    }
    if (im.width != rgb->width() || im.height != rgb->height() || im.transfer != lum->transfer()) {
      throwInputError(files[i].string(), "image decode",
                      "decodes to " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                          " pixels of another kind than the first image (" +
                          std::to_string(rgb->width()) + "x" + std::to_string(rgb->height()) +
                          "); all images of a capture must be alike");
    }
    lum->write(i, luminance(im));
    rgb->write(i, im.transfer == Transfer::Linear ? image::srgbEncode(toRgb(im)) : toRgb(im));
    if (run.progress) run.progress("Decoding images", double(++done) / n);
  };

  if (n == 0) throw Error(ErrorKind::Input, "", "image decode", "there are no images to decode");
  decodeOne(0);  // fixes the stacks' size
  const int workers = concurrentDecodes(run, rgb->width(), rgb->height());
  parallelFor(static_cast<std::size_t>(n - 1), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) decodeOne(static_cast<int>(i) + 1);
  });
  out.rgb = rgb;
  out.luminance = lum;
  return out;
}

}  // namespace surrogate::stages
