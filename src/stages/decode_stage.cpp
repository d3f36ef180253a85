#include "stages/decode_stage.h"

#include "carrier/advice.h"

#include <algorithm>

#include "pipeline/context.h"
#include "image/raw_settings.h"
#include "stages/decode_images.h"
#include "stages/learned_fit_stage.h"
#include "stages/rti_fit_stage.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "core/parallel.h"
#include "core/text.h"

namespace surrogate::stages {

namespace {

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

// The `accept-decoder-warning` interventions: per input, the one that accepts damage in exactly
// the bytes the file has now (its value is "sha256:<hex>" of the file when it was accepted).
std::vector<const carrier::Intervention*> acceptedDamage(const carrier::Step& step, pipeline::Context& ctx,
                                                         const InputImages& inputs) {
  std::vector<const carrier::Intervention*> accepted(inputs.size(), nullptr);
  for (const carrier::Intervention* i : step.interventionsOfKind(kAcceptDecoderWarning)) {
    const auto in = std::find_if(inputs.begin(), inputs.end(),
                                 [&](const InputImage& x) { return x.relativePath == i->target; });
    if (in == inputs.end()) {
      ctx.carrier.addLog("info", step.id,
                         "the accepted damage in " + i->target + " (" + i->reason + ") does not apply: this "
                         "run does not decode that file (excluded, or the other source)", i->who);
      continue;
    }
    const carrier::FileRecord* f = ctx.carrier.findFile(in->fileId);
    if (!f || i->value != "sha256:" + f->sha256) {
      carrier::addWarning(
          ctx.carrier, step.id,
          {i->target + " has changed since its damage was accepted, so that acceptance no longer applies to it",
           carrier::Usable::Yes,
           "the file is read as any other: if its decoder still reports damage, the run stops and says so",
           "nothing if the file was replaced by a sound copy; if the damage is reported again, look at the file and "
           "accept it anew with --accept-damaged " + i->target + " --reason \"...\"",
           "accepted for " + i->value + "; the file is now sha256:" + (f ? f->sha256 : std::string("?"))},
          i->who);
      continue;
    }
    accepted[static_cast<std::size_t>(in - inputs.begin())] = i;
  }
  return accepted;
}

std::string mebibytes(std::uint64_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }

std::string stackPlacement(const DecodedStacks& d, std::size_t count, std::uint64_t budget) {
  const std::uint64_t bytes = pipeline::DecodedStack::bytesFor(static_cast<int>(count), d.decoded->format());
  const std::string what = std::to_string(8 * d.decoded->format().bytesPerSample) + "-bit samples, " + mebibytes(bytes);
  if (d.bytesInMemory > 0)
    return "the " + std::to_string(count) + " decoded images are held in memory (" + what + " of the " +
           mebibytes(budget) + " --memory budget)";
  return "the " + std::to_string(count) + " decoded images (" + what +
         ") are in a temporary file: with room for the rest of the run they do not fit the " + mebibytes(budget) +
         " --memory budget; a larger --memory keeps them in memory and runs faster";
}

// The pixel digests decodeImages left to this step (the images decoded into the stack's
// memory), taken later where a core would otherwise idle (pipeline::Context::defer): beside the
// colour chart search, which runs on one thread, and the rest when the runner needs them.
// Hashing 36 images of 1200x800 was 58 ms of CPU inside this step (SHA-256 at 1.8 GB/s), about
// 29 ms of its time on two cores. The items hold an empty pixelSha256 meanwhile, which the
// record fills in, so the carrier's text is the same as when they were taken here.
void deferPixelDigests(const carrier::Step& step, pipeline::Context& ctx, const DecodedStacks& decoded) {
  auto digests = std::make_shared<std::vector<std::string>>(decoded.images.size());
  std::vector<std::function<void()>> tasks;
  for (std::size_t i = 0; i < decoded.images.size(); ++i)
    if (decoded.images[i].pixelSha256.empty())
      tasks.push_back([stack = decoded.decoded, digests, i] {
        (*digests)[i] = pixelDigest(stack->slot(static_cast<int>(i)), static_cast<std::size_t>(stack->imageBytes()));
      });
  if (tasks.empty()) return;
  ctx.defer(
      std::move(tasks),
      [&carrier = ctx.carrier, id = step.id, digests] {
        for (carrier::Result& r : carrier.data) {
          if (r.step != id) continue;
          std::size_t k = 0;  // the k-th "decoded" item is the k-th image's
          for (carrier::DataItem& item : r.items)
            if (item.element == "decoded" && k < digests->size()) {
              const std::string& digest = (*digests)[k++];
              if (!digest.empty()) item.set("pixelSha256", digest);
            }
        }
      },
      {kRgbStack, kDecodedRgbStack, kLuminanceStack});
}

}  // namespace

pipeline::StageInfo DecodeStage::info() {
  // 2: JPEG, PNG and TIFF decoded by libjpeg, libpng and libtiff called directly (the same
  // pixels as OpenCV's imread gave, so the same pixelSha256; `decoded/@decoder` names the
  // library); images whose decoder reports damaged data refused unless accepted.
  // 3: 8-bit sources kept at one byte a sample, and pixelSha256 taken over those bytes (it was
  // over the samples widened to 16 bits); the pixels the later steps read are unchanged.
  pipeline::StageInfo info = pipeline::withOptions<image::RawDecodeSettings>(
      {kComponent, "3",
       "Decode each image once (LibRaw for raw/DNG; libjpeg, libpng, libtiff for JPEG, PNG, TIFF)",
       pipeline::PlanSlot::Decode});
  info.reads = pipeline::alwaysReads({kInputImages});
  return info;
}

void DecodeStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const image::RawDecodeSettings settings =
      image::RawDecodeSettings::fromParameters(parametersOf(step));
  std::vector<std::filesystem::path> files;
  for (const InputImage& in : *inputs) files.push_back(ctx.pathOf(in.fileId));
  const std::vector<const carrier::Intervention*> accepted = acceptedDamage(step, ctx, *inputs);
  std::vector<bool> acceptDamage;
  for (const carrier::Intervention* a : accepted) acceptDamage.push_back(a != nullptr);
  // The fitted models this run will hold (the derived maps keep every one): counted, with the
  // decoding, against --memory before anything is decoded.
  std::uint64_t modelBytes = 0;
  for (const carrier::Step& s : ctx.carrier.process)
    if (s.component == RtiFitStage::kComponent && s.hasParam("basis")) modelBytes += modelBytesPerPixel(s.param("basis"));
    else if (s.component == LearnedFitStage::kComponent)  // its coefficient bytes, one per plane
      modelBytes += static_cast<std::uint64_t>(LearnedFitOptions::fromParameters(parametersOf(s)).planes);
  DecodedStacks decoded;
  try {
    // The pixel digests of images decoded into memory left for later (deferPixelDigests).
    decoded = decodeImages(files, settings, ctx.settings, acceptDamage, modelBytes,
                           effectiveThreads(ctx.settings.threads) > 1);
  } catch (const image::DamagedImageError& e) {
    // Refused with the library's words; what the user can do about it, with this capture's names.
    std::string rel = e.file(), stem = e.file();
    for (std::size_t i = 0; i < files.size(); ++i)
      if (files[i].string() == e.file()) {
        rel = (*inputs)[i].relativePath;
        stem = (*inputs)[i].stem;
      }
    throw Error(ErrorKind::Input, e.file(), e.step(),
                e.message() + ". If the damage is acceptable (the shot cannot be taken again and the "
                "rest of the image is sound), accept it, recorded with your reason: --accept-damaged " +
                    rel + " --reason \"...\"; or leave the shot out: --exclude " + stem + " --reason \"...\"");
  }

  for (std::size_t i = 0; i < inputs->size(); ++i) {
    const DecodedImage& d = decoded.images[i];
    carrier::DataItem& item = result.add("decoded");
    item.set("image", (*inputs)[i].fileId)
        .set("decoder", d.report.decoder)
        .set("width", d.width)
        .set("height", d.height)
        .set("channels", d.channels)
        .set("bitsPerSample", d.bitsPerSample)
        .set("transfer", d.transfer == Transfer::Linear ? "linear" : "srgb");
    if (d.report.blackLevel >= 0) item.set("blackLevel", d.report.blackLevel);
    if (d.report.whiteLevel >= 0) item.set("whiteLevel", d.report.whiteLevel);
    if (!d.report.whiteBalanceMultipliers.empty()) {
      std::string wb;
      for (double m : d.report.whiteBalanceMultipliers)
        wb += (wb.empty() ? "" : " ") + formatNumber(m);
      item.set("whiteBalance", wb);
    }
    item.set("pixelSha256", d.pixelSha256);  // empty until deferPixelDigests records it
    if (!d.report.channelBlackLevels.empty()) {
      std::string levels;
      for (int b : d.report.channelBlackLevels) levels += (levels.empty() ? "" : " ") + std::to_string(b);
      result.add("imageValue").set("image", (*inputs)[i].fileId).set("name", "channelBlackLevels")
          .set("value", levels).set("unit", "raw levels R G B G2");
    }
    // The raw decoder's own fallbacks (white balance, demosaic): the picture is whole, its
    // colour or fine detail may differ a little from its neighbours'.
    for (const std::string& w : d.report.warnings)
      carrier::addWarning(ctx.carrier, step.id,
                          {(*inputs)[i].relativePath + ": " + w, carrier::Usable::Yes,
                           "the photograph is whole; its colour or fine detail may differ slightly from the others'",
                           "nothing if it looks like its neighbours in the report; if not, develop the raw files in "
                           "your own software and run on their exports (--source export)",
                           ""});
    if (const carrier::Intervention* a = accepted[i]) {
      if (d.report.decoderWarnings.empty()) {
        ctx.carrier.addLog("info", step.id,
                           (*inputs)[i].relativePath + ": damage was accepted (" + a->reason +
                               "), but its decoder reported none", a->who);
      } else {
        const std::string words = joined(d.report.decoderWarnings);
        result.add("imageValue").set("image", (*inputs)[i].fileId).set("name", "decoderWarning").set("value", words);
        ctx.carrier.addLog("intervention", step.id,
                           (*inputs)[i].relativePath + " decoded although its decoder reports damaged data (" +
                               words + "); the damaged part holds what the decoder made up. Accepted: " +
                               a->reason, a->who);
      }
    }
  }
  // Inputs processed by other software before Surrogate saw them (exports, or files whose XMP
  // holds an editing history): the auditor must see that part of the processing is unrecorded.
  std::vector<std::string> outside;
  bool originalsExist = false;
  for (const InputImage& in : *inputs) {
    const carrier::FileRecord* f = ctx.carrier.findFile(in.fileId);
    if (!f || !f->unrecordedProcessing) continue;
    originalsExist = originalsExist || !f->pairedWith.empty();
    result.add("imageValue").set("image", in.fileId).set("name", "unrecordedProcessing").set("value", "true");
    outside.push_back(in.relativePath);
  }
  if (!outside.empty())
    carrier::addWarning(
        ctx.carrier, step.id,
        {std::to_string(outside.size()) + " of the " + std::to_string(inputs->size()) +
             " photographs used (e.g. " + outside.front() + ") were processed by other software (raw development, "
             "white balance, edits) before Surrogate saw them, and that processing is not in this record",
         carrier::Usable::Yes,
         "the results are sound for viewing, but a reader of the record cannot see every step between the camera "
         "and the result",
         originalsExist ? "use the camera originals for a fully recorded result: run again with --source original"
                        : "if you have the camera's raw files, put them in original-captures/ and run again; "
                          "otherwise nothing (the files are flagged in the record)",
         "flagged unrecordedProcessing; their XMP, where present, is kept in the files section"});
  result.add("value").set("name", "fitInputTransfer").set("value", "srgb");
  result.add("value").set("name", "detectionInputTransfer")
      .set("value", decoded.luminance->transfer() == Transfer::Linear ? "linear" : "srgb");
  deferPixelDigests(step, ctx, decoded);
  ctx.put(kRgbStack, decoded.rgb);
  ctx.put(kDecodedRgbStack, decoded.rgb);
  ctx.put(kLuminanceStack, decoded.luminance);
  ctx.put(kStackFrame, std::make_shared<StackFrame>(StackFrame{decoded.rgb->width(), decoded.rgb->height()}));
  // Stacks kept in memory count against --memory for the rest of the run (they replace any
  // earlier ones on the blackboard). The log says where they are: a spilled run is slower.
  ctx.settings.heldBytes = decoded.bytesInMemory;
  ctx.carrier.addLog("info", step.id, stackPlacement(decoded, files.size(), ctx.settings.memoryBudget));
}

}  // namespace surrogate::stages
