#include "image/decode.h"

#include <algorithm>
#include <cstring>

#include "image/decoder_messages.h"
#include "image/export_decoder.h"
#include "image/libraw_decoder.h"

namespace surrogate::image {

namespace {

std::string damageMessage(const std::string& library, const std::vector<std::string>& warnings) {
  std::string said;
  for (const std::string& w : warnings) said += (said.empty() ? "\"" : "; \"") + w + "\"";
  return "the image data is damaged: " + library + " reports " + said +
         " (decoded, the damaged part would be made up by the decoder); copy the file from the "
         "card again";
}

std::string megapixels(std::uint64_t pixels) {
  return std::to_string((pixels + 500'000) / 1'000'000) + " Mpx";
}

}  // namespace

DamagedImageError::DamagedImageError(const std::string& file, std::string library,
                                     std::vector<std::string> warnings)
    : Error(ErrorKind::Input, file, "image decode", damageMessage(library, warnings)),
      library_(std::move(library)),
      warnings_(std::move(warnings)) {}

void DecoderMessages::add(const char* text) noexcept {
  try {
    ++count_;
    std::string t = text ? text : "";
    while (!t.empty() && (t.back() == '\n' || t.back() == ' ' || t.back() == '.')) t.pop_back();
    if (t.empty()) t = "(no text)";
    if (distinct_.size() < kKept && std::find(distinct_.begin(), distinct_.end(), t) == distinct_.end())
      distinct_.push_back(std::move(t));
  } catch (...) {
    // Out of memory inside a library callback: the count still says something was reported.
  }
}

std::vector<std::string> DecoderMessages::summary() const {
  std::vector<std::string> out;
  for (const std::string& d : distinct_) out.push_back(library_ + ": " + d);
  if (count_ > distinct_.size())
    out.push_back(library_ + ": ... (" + std::to_string(count_) + " warnings in all)");
  return out;
}

void settle(const DecoderMessages& messages, const std::filesystem::path& path,
            const DecodeOptions& options, DecodeReport* report) {
  if (messages.count() == 0) return;
  if (!options.acceptDamage) {
    std::vector<std::string> words = messages.distinct();
    if (messages.count() > words.size())
      words.push_back("... " + std::to_string(messages.count()) + " warnings in all");
    throw DamagedImageError(path.string(), messages.library(), words);
  }
  if (report)
    for (const std::string& s : messages.summary()) report->decoderWarnings.push_back(s);
}

void checkDeclaredSize(const std::filesystem::path& path, std::uint64_t width, std::uint64_t height,
                       const DecodeOptions& options) {
  const std::uint64_t pixels = width * height;  // both < 2^32: no overflow
  const std::uint64_t limit = std::min(options.maxPixels, kMaxImagePixels);
  if (pixels <= limit) return;
  const std::string declared = std::to_string(width) + "x" + std::to_string(height) + " pixels (" +
                               megapixels(pixels) + ")";
  if (pixels > kMaxImagePixels)
    throwInputError(path.string(), "image decode",
                    "its header declares " + declared + ", more than the " + megapixels(kMaxImagePixels) +
                        " Surrogate reads: the header is damaged, or this is not a photograph");
  throwInputError(path.string(), "image decode",
                  "its header declares " + declared + ", more than the " + megapixels(limit) +
                      " expected here (the other images of the capture are smaller): the header is "
                      "damaged; copy the file from the card again");
}

ImageProbe probeImage(const std::filesystem::path& path) {
  const SourceKind kind = classifyImageFile(path);
  const ImageProbe probe = kind == SourceKind::CameraRaw ? probeCameraRaw(path) : checkExportStructure(path, kind);
  checkDeclaredSize(path, static_cast<std::uint64_t>(probe.width), static_cast<std::uint64_t>(probe.height),
                    DecodeOptions{});
  return probe;
}

const void* DecodedPixels::data() const {
  if (placed) return placed;
  return isNarrow() ? static_cast<const void*>(narrow.pixels.data()) : static_cast<const void*>(wide.pixels.data());
}

std::size_t DecodedPixels::bytes() const {
  if (placed && placedNarrow) return std::size_t(narrow.width) * narrow.height * narrow.channels;
  if (placed) return std::size_t(wide.width) * wide.height * wide.channels * sizeof(std::uint16_t);
  return isNarrow() ? narrow.pixels.size() : wide.pixels.size() * sizeof(std::uint16_t);
}

Image DecodedPixels::widened() const {
  if (!isNarrow() && placed) {
    Image out(wide.width, wide.height, wide.channels);
    out.bitsPerSample = wide.bitsPerSample;
    out.transfer = wide.transfer;
    std::memcpy(out.pixels.data(), placed, bytes());
    return out;
  }
  if (!isNarrow()) return wide;
  return widen(static_cast<const std::uint8_t*>(data()), narrow.width, narrow.height, narrow.channels,
               narrow.transfer);
}

DecodedPixels decodePixels(const std::filesystem::path& path, const RawDecodeSettings& settings,
                           DecodeReport* report, const DecodeOptions& options) {
  const SourceKind kind = classifyImageFile(path);
  if (kind != SourceKind::CameraRaw) return decodeExport(path, kind, report, options);
  return decodeCameraRaw(path, settings, report, options);
}

Image decodeImage(const std::filesystem::path& path, const RawDecodeSettings& settings,
                  DecodeReport* report, const DecodeOptions& options) {
  DecodedPixels pixels = decodePixels(path, settings, report, options);
  if (pixels.isNarrow()) return pixels.widened();
  return std::move(pixels.wide);
}

}  // namespace surrogate::image
