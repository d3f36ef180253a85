#include "stages/decode_images.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include "core/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "fit/basis.h"
#include "pipeline/spill_stack.h"

namespace surrogate::stages {

namespace {

constexpr const char* kStep = "image decode";

std::string pixelDigest(const Image& im) {
  MultiDigest d({DigestAlgorithm::Sha256});
  d.update(im.pixels.data(), im.pixels.size() * sizeof(std::uint16_t));
  return d.hex(DigestAlgorithm::Sha256);
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

// The two stacks, 16-bit RGB and 16-bit luminance, per pixel of one image.
constexpr std::uint64_t kStackBytesPerPixel = (3 + 1) * sizeof(std::uint16_t);

// How many images to decode at once: the threads, but no more than `budget` (what --memory
// leaves besides stacks held in memory) allows.
int concurrentDecodes(int threads, std::uint64_t budget, std::uint64_t pixels) {
  const std::uint64_t perImage = std::max<std::uint64_t>(1, residentBytesPerImage(pixels));
  const std::uint64_t byMemory = std::max<std::uint64_t>(1, budget / perImage);
  return static_cast<int>(std::min<std::uint64_t>(effectiveThreads(threads), byMemory));
}

// Sizes as --memory writes them (binary units): "21.6G", "512M".
std::string size(std::uint64_t bytes) {
  const char* units[] = {"K", "M", "G", "T"};
  double v = static_cast<double>(bytes) / 1024;
  int u = 0;
  while (v >= 1024 && u < 3) {
    v /= 1024;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, v < 10 ? "%.1f%s" : "%.0f%s", v, units[u]);
  return text;
}

// Before any pixel is decoded: what one image needs in memory against --memory, and, when they
// are to be spilled, the two stacks against the free space of the folder they spill to.
void checkResources(const std::vector<std::filesystem::path>& files, const image::ImageProbe& first,
                    const pipeline::RunSettings& run, std::uint64_t laterBytesPerPixel, bool spilled) {
  const std::uint64_t pixels = std::uint64_t(first.width) * std::uint64_t(first.height);
  const std::uint64_t resident = residentBytesPerImage(pixels) + pixels * laterBytesPerPixel;
  const std::string declared = std::to_string(first.width) + "x" + std::to_string(first.height);
  const std::uint64_t stackBytes = pipeline::spillBytes(static_cast<int>(files.size()), first.width, first.height, 3) +
                                   pipeline::spillBytes(static_cast<int>(files.size()), first.width, first.height, 1);
  if (resident > run.memoryBudget) {
    const std::uint64_t gib = (resident + (1ull << 30) - 1) >> 30;
    throw Error(ErrorKind::Usage, "--memory " + size(run.memoryBudget), kStep,
                "is too small for these images: " + files.front().filename().string() + " declares " +
                    declared + " pixels, and decoding one such image" +
                    (laterBytesPerPixel ? std::string(" and keeping the fitted models") : std::string()) +
                    " needs about " + size(resident) + " in memory at once (the decoded stack of " +
                    std::to_string(files.size()) +
                    " images, " + size(stackBytes) + ", would go to a temporary file, not memory); the "
                    "budget (--memory) is " + size(run.memoryBudget) + ". Give --memory " +
                    std::to_string(gib) + "G or more if the computer has it; if the images are not "
                    "that large, their headers are damaged");
  }
  if (!spilled) return;
  const std::filesystem::path dir = pipeline::spillDirectory();
  if (const auto free = pipeline::spillSpaceAvailable(dir); free && *free < stackBytes) {
    throw Error(ErrorKind::Usage, dir.string(), kStep,
                "the decoded images (" + std::to_string(files.size()) + " x " + declared + " pixels) need " +
                    size(stackBytes) + " of temporary space in this folder, which has " + size(*free) +
                    " free; free some space there, or set TMPDIR to a folder on a disk with more "
                    "(e.g. TMPDIR=/scratch surrogate run ...)");
  }
}

}  // namespace

std::uint64_t residentBytesPerImage(std::uint64_t pixels) { return pixels * kResidentBytesPerPixel; }

bool stacksFitInMemory(int count, std::uint64_t pixels, std::uint64_t budget, std::uint64_t laterBytesPerPixel) {
  const std::uint64_t stacks = static_cast<std::uint64_t>(std::max(count, 0)) * pixels * kStackBytesPerPixel;
  const std::uint64_t besides = residentBytesPerImage(pixels) + pixels * laterBytesPerPixel;
  return besides < budget && stacks <= (budget - besides) / 2;
}

std::uint64_t modelBytesPerPixel(const std::string& basis) {
  const fit::Basis b = fit::parseBasis(basis);
  if (b == fit::Basis::PtmLrgb) return 9;
  if (b == fit::Basis::PtmRgb) return 18;
  return 3 * static_cast<std::uint64_t>(fit::basisTerms(b));
}

DecodedStacks decodeImages(const std::vector<std::filesystem::path>& files,
                           const image::RawDecodeSettings& settings,
                           const pipeline::RunSettings& run,
                           const std::vector<bool>& acceptDamage,
                           std::uint64_t laterBytesPerPixel) {
  const int n = static_cast<int>(files.size());
  if (n == 0) throw Error(ErrorKind::Input, "", kStep, "there are no images to decode");
  // The headers first: nothing is decoded, or allocated for pixels, before the sizes they
  // declare are known to fit in memory and on disk.
  const image::ImageProbe first = image::probeImage(files.front());
  const std::uint64_t declared = std::uint64_t(first.width) * std::uint64_t(first.height);
  const bool inMemory = stacksFitInMemory(n, declared, run.memoryBudget, laterBytesPerPixel);
  checkResources(files, first, run, laterBytesPerPixel, !inMemory);

  DecodedStacks out;
  out.images.resize(n);
  // In memory: the images as decoded, moved into MemoryImageStacks at the end. Spilled: the
  // temporary files, created when the first image gives the size.
  std::vector<Image> rgbImages(inMemory ? n : 0), lumImages(inMemory ? n : 0);
  std::shared_ptr<pipeline::SpillStack> rgb, lum;
  struct Shape {
    int width = 0, height = 0;
    Transfer transfer = Transfer::Srgb;
  } shape;
  std::atomic<int> done{0};

  auto decodeOne = [&](int i) {
    DecodedImage& d = out.images[i];
    image::DecodeOptions options;
    options.acceptDamage = i < static_cast<int>(acceptDamage.size()) && acceptDamage[i];
    options.maxPixels = declared;  // all images are alike: a larger header is damaged
    const Image im = image::decodeImage(files[i], settings, &d.report, options);
    d.width = im.width;
    d.height = im.height;
    d.channels = im.channels;
    d.bitsPerSample = im.bitsPerSample;
    d.transfer = im.transfer;
    d.pixelSha256 = pixelDigest(im);
    if (i == 0) {  // decoded alone, before the others start
      shape = {im.width, im.height, im.transfer};
      if (!inMemory) {
        rgb = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 3, Transfer::Srgb);
        lum = std::make_shared<pipeline::SpillStack>(n, im.width, im.height, 1, im.transfer);
      }
    }
    if (im.width != shape.width || im.height != shape.height || im.transfer != shape.transfer) {
      throwInputError(files[i].string(), kStep,
                      "decodes to " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                          " pixels of another kind than the first image (" +
                          std::to_string(shape.width) + "x" + std::to_string(shape.height) +
                          "); all images of a capture must be alike");
    }
    Image l = luminance(im);
    Image c = im.transfer == Transfer::Linear ? image::srgbEncode(toRgb(im)) : toRgb(im);
    if (inMemory) {
      lumImages[i] = std::move(l);
      rgbImages[i] = std::move(c);
    } else {
      lum->write(i, l);
      rgb->write(i, c);
    }
    if (run.progress) run.progress("Decoding images", double(++done) / n);
  };

  decodeOne(0);  // fixes the stacks' size
  const std::uint64_t held = inMemory ? n * declared * kStackBytesPerPixel : 0;
  const int workers = concurrentDecodes(run.threads, run.memoryBudget - held, declared);
  parallelFor(static_cast<std::size_t>(n - 1), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) decodeOne(static_cast<int>(i) + 1);
  });
  if (inMemory) {
    out.rgb = std::make_shared<MemoryImageStack>(std::move(rgbImages));
    out.luminance = std::make_shared<MemoryImageStack>(std::move(lumImages));
    out.bytesInMemory = held;
  } else {
    out.rgb = rgb;
    out.luminance = lum;
  }
  return out;
}

}  // namespace surrogate::stages
