#include "stages/decode_stage.h"

#include "pipeline/context.h"
#include "stages/decode_images.h"
#include "stages/inputs.h"
#include "stages/outputs.h"

namespace surrogate::stages {

void DecodeStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const image::RawDecodeSettings settings =
      image::RawDecodeSettings::fromParameters(parametersOf(step));
  std::vector<std::filesystem::path> files;
  for (const InputImage& in : *inputs) files.push_back(ctx.pathOf(in.fileId));
  const DecodedStacks decoded = decodeImages(files, settings, ctx.settings);

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
        wb += (wb.empty() ? "" : " ") + carrier::formatNumber(m);
      item.set("whiteBalance", wb);
    }
    item.set("pixelSha256", d.pixelSha256);
    if (!d.report.channelBlackLevels.empty()) {
      std::string levels;
      for (int b : d.report.channelBlackLevels) levels += (levels.empty() ? "" : " ") + std::to_string(b);
      result.add("imageValue").set("image", (*inputs)[i].fileId).set("name", "channelBlackLevels")
          .set("value", levels).set("unit", "raw levels R G B G2");
    }
    for (const std::string& w : d.report.warnings)
      ctx.carrier.addLog("warning", step.id, (*inputs)[i].relativePath + ": " + w);
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
    ctx.carrier.addLog("warning", step.id,
                       std::to_string(outside.size()) + " of the " + std::to_string(inputs->size()) +
                           " images decoded (e.g. " + outside.front() +
                           ") were processed by other software (raw development, white balance, "
                           "edits) outside any record; their XMP, where present, is kept in the "
                           "files section" +
                           (originalsExist ? ". Use the camera originals (--source original) for "
                                             "a fully recorded result"
                                           : ""));
  result.add("value").set("name", "fitInputTransfer").set("value", "srgb");
  result.add("value").set("name", "detectionInputTransfer")
      .set("value", decoded.luminance->transfer() == Transfer::Linear ? "linear" : "srgb");
  ctx.put(kRgbStack, decoded.rgb);
  ctx.put(kLuminanceStack, decoded.luminance);
}

}  // namespace surrogate::stages
