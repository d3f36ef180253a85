#include "stages/decode_images.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>

#include "core/digest.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/resident.h"
#include "fit/basis.h"
#include "image/srgb.h"
#include "pipeline/decoded_stack.h"
#include "stages/stack_views.h"

namespace surrogate::stages {

namespace {

constexpr const char* kStep = "image decode";

pipeline::DecodedStack::Format formatOf(const image::DecodedPixels& p) {
  return {p.width(), p.height(), p.channels(), p.bytesPerSample(), p.transfer()};
}

std::string describe(const pipeline::DecodedStack::Format& f) {
  return std::to_string(f.width) + "x" + std::to_string(f.height) + " pixels, " +
         (f.channels == 1 ? "grey" : "RGB") + ", " + std::to_string(8 * f.bytesPerSample) + "-bit, " +
         (f.transfer == Transfer::Linear ? "linear" : "sRGB");
}

bool sameFormat(const pipeline::DecodedStack::Format& a, const pipeline::DecodedStack::Format& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         a.bytesPerSample == b.bytesPerSample && a.transfer == b.transfer;
}

// The fitters' view (display-referred RGB) and the detectors' (luminance) of the stack.
std::shared_ptr<ImageStack> rgbView(const std::shared_ptr<pipeline::DecodedStack>& decoded) {
  std::shared_ptr<ImageStack> rgb = decoded;
  if (decoded->channels() == 1) rgb = std::make_shared<GreyAsRgbStack>(rgb);
  if (decoded->transfer() == Transfer::Srgb) return rgb;
  const TableStack::Table& encode = image::srgbEncodingTable();
  return std::make_shared<TableStack>(rgb, std::array<TableStack::Table, 3>{encode, encode, encode}, Transfer::Srgb);
}

// How many images to decode at once: the threads, but no more than `budget` (what --memory
// leaves besides stacks held in memory) allows.
int concurrentDecodes(int threads, std::uint64_t budget, std::uint64_t pixels) {
  const std::uint64_t perImage = std::max<std::uint64_t>(1, residentBytesPerImage(pixels));
  const std::uint64_t byMemory = std::max<std::uint64_t>(1, budget / perImage);
  return static_cast<int>(std::min<std::uint64_t>(effectiveThreads(threads), byMemory));
}

// Before any pixel is decoded: what one image needs in memory against --memory, and, when they
// are to be spilled, the two stacks against the free space of the folder they spill to.
void checkResources(const std::vector<std::filesystem::path>& files, const image::ImageProbe& first,
                    const pipeline::RunSettings& run, std::uint64_t laterBytesPerPixel, bool spilled) {
  const std::uint64_t pixels = std::uint64_t(first.width) * std::uint64_t(first.height);
  const std::uint64_t resident = residentBytesPerImage(pixels) + pixels * laterBytesPerPixel;
  const std::string declared = std::to_string(first.width) + "x" + std::to_string(first.height);
  const std::uint64_t stackBytes = std::uint64_t(files.size()) * pixels * storedBytesPerPixel(first.kind);
  if (resident > run.memoryBudget) {
    const std::uint64_t gib = (resident + (1ull << 30) - 1) >> 30;
    throw Error(ErrorKind::Usage, "--memory " + memorySize(run.memoryBudget), kStep,
                "is too small for these images: " + files.front().filename().string() + " declares " +
                    declared + " pixels, and decoding one such image" +
                    (laterBytesPerPixel ? std::string(" and keeping the fitted models") : std::string()) +
                    " needs about " + memorySize(resident) + " in memory at once (the decoded stack of " +
                    std::to_string(files.size()) +
                    " images, " + memorySize(stackBytes) + ", would go to a temporary file, not memory); the "
                    "budget (--memory) is " + memorySize(run.memoryBudget) + ". Give --memory " +
                    std::to_string(gib) + "G or more if the computer has it; if the images are not "
                    "that large, their headers are damaged");
  }
  if (!spilled) return;
  const std::filesystem::path dir = pipeline::spillDirectory();
  if (const auto free = pipeline::spillSpaceAvailable(dir); free && *free < stackBytes) {
    throw Error(ErrorKind::Usage, dir.string(), kStep,
                "the decoded images (" + std::to_string(files.size()) + " x " + declared + " pixels) need " +
                    memorySize(stackBytes) + " of temporary space in this folder, which has " + memorySize(*free) +
                    " free; free some space there, or set TMPDIR to a folder on a disk with more "
                    "(e.g. TMPDIR=/scratch surrogate run ...)");
  }
}

}  // namespace

std::string pixelDigest(const void* data, std::size_t bytes) {
  MultiDigest d({DigestAlgorithm::Sha256});
  d.update(data, bytes);
  return d.hex(DigestAlgorithm::Sha256);
}

std::uint64_t residentBytesPerImage(std::uint64_t pixels) { return pixels * kResidentBytesPerPixel; }

std::uint64_t storedBytesPerPixel(image::SourceKind kind) { return kind == image::SourceKind::Jpeg ? 3 : 6; }

bool stackFitsInMemory(int count, std::uint64_t pixels, std::uint64_t bytesPerPixel, std::uint64_t budget,
                       std::uint64_t laterBytesPerPixel) {
  const std::uint64_t stack = static_cast<std::uint64_t>(std::max(count, 0)) * pixels * bytesPerPixel;
  const std::uint64_t besides = residentBytesPerImage(pixels) + pixels * laterBytesPerPixel;
  return besides < budget && stack <= (budget - besides) / 2;
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
                           std::uint64_t laterBytesPerPixel, bool digestsLater) {
  const int n = static_cast<int>(files.size());
  if (n == 0) throw Error(ErrorKind::Input, "", kStep, "there are no images to decode");
  // The headers first: nothing is decoded, or allocated for pixels, before the sizes they
  // declare are known to fit in memory and on disk.
  const image::ImageProbe first = image::probeImage(files.front());
  const std::uint64_t declared = std::uint64_t(first.width) * std::uint64_t(first.height);
  const bool inMemory =
      stackFitsInMemory(n, declared, storedBytesPerPixel(first.kind), run.memoryBudget, laterBytesPerPixel);
  checkResources(files, first, run, laterBytesPerPixel, !inMemory);

  DecodedStacks out;
  out.images.resize(n);
  // The stack is made when the first image gives its format: as soon as its decoder knows the
  // layout (a JPEG's header; camera raw once demosaiced), or, for the decoders that ask for no
  // destination (PNG, TIFF), once it is decoded. The others are decoded meanwhile (a camera raw
  // image takes about 0.7 s at 6 Mpx, and waiting for the first one left a core idle) and wait
  // for the stack only where they need it: for their slot, or to be stored.
  const pipeline::DecodedStack::Placement placement =
      inMemory ? pipeline::DecodedStack::Placement::Memory : pipeline::DecodedStack::Placement::TemporaryFile;
  std::shared_ptr<pipeline::DecodedStack> stack;
  std::mutex stackMutex;
  std::condition_variable stackMade;
  bool firstSettled = false;  // the stack is made, or the first image failed (stack stays empty)
  auto awaitStack = [&]() -> std::shared_ptr<pipeline::DecodedStack> {
    std::unique_lock<std::mutex> lock(stackMutex);
    stackMade.wait(lock, [&] { return firstSettled; });
    return stack;
  };
  std::atomic<int> done{0};

  auto decodeOne = [&](int i) {
    DecodedImage& d = out.images[i];
    image::DecodeOptions options;
    options.acceptDamage = i < static_cast<int>(acceptDamage.size()) && acceptDamage[i];
    options.maxPixels = declared;  // all images are alike: a larger header is damaged
    if (i == 0)  // the stack made from its layout, and the first image decoded into its slot
      options.destination = [&, n](int width, int height, int channels, int bytesPerSample,
                                   Transfer transfer) -> std::uint8_t* {
        std::shared_ptr<pipeline::DecodedStack> made = std::make_shared<pipeline::DecodedStack>(
            n, pipeline::DecodedStack::Format{width, height, channels, bytesPerSample, transfer}, placement);
        {
          std::lock_guard<std::mutex> lock(stackMutex);
          stack = made;
          firstSettled = true;
        }
        stackMade.notify_all();
        std::uint8_t* const slot = made->slot(0);  // nullptr in a temporary file: stored below
        if (slot) makeResidentAdvised(slot, static_cast<std::size_t>(made->imageBytes()));
        return slot;
      };
    else  // straight into the stack's slot, when the image is as the first
      options.destination = [&awaitStack, i](int width, int height, int channels, int bytesPerSample,
                                             Transfer transfer) -> std::uint8_t* {
        const std::shared_ptr<pipeline::DecodedStack> made = awaitStack();
        if (!made) return nullptr;  // the first image failed: its error ends the step
        const pipeline::DecodedStack::Format& f = made->format();
        const bool alike = f.bytesPerSample == bytesPerSample && f.transfer == transfer && f.width == width &&
                           f.height == height && f.channels == channels;
        if (!alike) return nullptr;
        // Backed in one call rather than a fault a page as libjpeg or LibRaw writes it.
        makeResidentAdvised(made->slot(i), static_cast<std::size_t>(made->imageBytes()));
        return made->slot(i);
      };
    image::DecodedPixels pixels = image::decodePixels(files[i], settings, &d.report, options);
    d.width = pixels.width();
    d.height = pixels.height();
    d.channels = pixels.channels();
    d.bitsPerSample = pixels.bitsPerSample();
    d.transfer = pixels.transfer();
    const pipeline::DecodedStack::Format format = formatOf(pixels);
    if (i == 0) {  // a decoder that asked for no destination: the stack from the decoded image
      std::lock_guard<std::mutex> lock(stackMutex);
      if (!stack) stack = std::make_shared<pipeline::DecodedStack>(n, format, placement);
    }
    const std::shared_ptr<pipeline::DecodedStack> made = i == 0 ? stack : awaitStack();
    // Decoded into its slot, the bytes stay there as the decoder wrote them, for the caller.
    const bool later = digestsLater && made && pixels.placed && pixels.placed == made->slot(i) &&
                       pixels.bytes() == made->imageBytes();
    if (!later) d.pixelSha256 = pixelDigest(pixels.data(), pixels.bytes());
    if (!made) return;  // the first image failed: its error ends the step
    if (!sameFormat(format, made->format())) {
      throwInputError(files[i].string(), kStep,
                      "decodes to " + describe(format) + ", another kind of image than the first (" +
                          describe(made->format()) + "); all images of a capture must be alike: "
                          "export them all the same way");
    }
    if (pixels.placed) made->markStored(i);  // decoded into its slot, already checked alike
    else if (pixels.isNarrow()) made->store(i, pixels.narrow.pixels);
    else made->store(i, pixels.wide.pixels);
    if (run.progress) run.progress("Decoding images", double(++done) / n);
  };
  // Settles the first image whichever way its decode ends, so that no other waits for ever.
  auto settleFirst = [&] {
    {
      std::lock_guard<std::mutex> lock(stackMutex);
      firstSettled = true;
    }
    stackMade.notify_all();
  };
  auto decodeFirst = [&] {
    try {
      decodeOne(0);
    } catch (...) {
      settleFirst();
      throw;
    }
    settleFirst();
  };

  // What the stack will hold in memory, from the first header (the decoded format may hold
  // less: a grey JPEG), for the number of images decoded at once.
  const std::uint64_t held = inMemory ? std::uint64_t(n) * declared * storedBytesPerPixel(first.kind) : 0;
  const int workers = concurrentDecodes(run.threads, run.memoryBudget - held, declared);
  parallelFor(static_cast<std::size_t>(n), 1, workers, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      if (i == 0) decodeFirst();
      else decodeOne(static_cast<int>(i));
    }
  });
  out.bytesInMemory = inMemory ? pipeline::DecodedStack::bytesFor(n, stack->format()) : 0;
  out.decoded = stack;
  out.rgb = rgbView(stack);
  out.luminance = std::make_shared<LuminanceStack>(stack);
  return out;
}

}  // namespace surrogate::stages
