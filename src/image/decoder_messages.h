// Private to src/image: what a decoding library said about one image's data, collected through
// the library's own message hooks (never its printing to stderr), and what Surrogate does with
// it: refuse the image (DamagedImageError) or, when the caller accepts damage, report it.
//
//   DecoderMessages messages("libjpeg");
//   ... the library's warning hook calls messages.add(text) ...
//   settle(messages, path, options, report);   // throws unless options.acceptDamage
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "image/decode.h"

namespace surrogate::image {

class DecoderMessages {
 public:
  explicit DecoderMessages(std::string library) : library_(std::move(library)) {}

  // Called from inside a C library's callback: never throws.
  void add(const char* text) noexcept;
  std::size_t count() const { return count_; }
  const std::string& library() const { return library_; }
  const std::vector<std::string>& distinct() const { return distinct_; }
  // "libjpeg: <message>" per distinct message, then "libjpeg: ... (N warnings in all)" when
  // more were given than kept.
  std::vector<std::string> summary() const;

 private:
  static constexpr std::size_t kKept = 5;
  std::string library_;
  std::vector<std::string> distinct_;
  std::size_t count_ = 0;
};

// No messages: nothing. Otherwise, without options.acceptDamage: throws DamagedImageError; with
// it: appends the summary to report->decoderWarnings (when report is given).
void settle(const DecoderMessages& messages, const std::filesystem::path& path,
            const DecodeOptions& options, DecodeReport* report);

// Throws Error(Input) naming the file when width x height is more than options.maxPixels (or
// kMaxImagePixels): called with the header's figures, before any pixel buffer is allocated.
void checkDeclaredSize(const std::filesystem::path& path, std::uint64_t width, std::uint64_t height,
                       const DecodeOptions& options);

}  // namespace surrogate::image
