// Decoding a list of images once into the stack the pipeline reads, with two views of it:
//   rgb        display-referred (sRGB-encoded) RGB, as 16-bit samples: what the fitters read
//   luminance  Rec. 709 luminance of the decoded values (linear for camera raw): what sphere
//              and highlight detection read
// Each image is kept once, at its source's depth (pipeline::DecodedStack: a JPEG one byte a
// sample); the views compute their rows from it as they are read (stages/stack_views.h), with
// the values 16-bit copies of both would hold. Images are decoded in parallel, as many at once
// as the threads and the memory budget allow; the stack and the per-image reports are in input
// order whatever the thread count.
//
// The stack stays in memory when it fits the budget (stackFitsInMemory: at most half of what
// --memory leaves after decoding one image and the fitted models), and only otherwise goes to
// a temporary file. Held in memory, it counts against the budget for the rest of the run:
// DecodedStacks::bytesInMemory, which the caller adds to RunSettings::heldBytes so that the
// bands of later steps are sized to what is left.
//
// Bounded for any input: before anything is decoded, the first image's header gives the size;
// if decoding one such image needs more memory than --memory (residentBytesPerImage), or the
// stack more than the free space of the folder it spills to ($TMPDIR), it is refused
// (Error(Usage), naming --memory or the folder); an image whose header declares more pixels
// than the first is refused before its pixels are allocated, and one that decodes to another
// size, depth, channel count or transfer than the first is refused once decoded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/stack.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "pipeline/decoded_stack.h"

namespace surrogate::stages {

struct DecodedImage {
  image::DecodeReport report;
  int width = 0, height = 0, channels = 0, bitsPerSample = 0;
  Transfer transfer = Transfer::Srgb;
  // SHA-256 of the decoded samples as the decoder gave them, before any conversion: one byte a
  // sample for 8-bit sources, two (little-endian) for 16-bit ones and camera raw. Empty when
  // left to the caller (decodeImages' digestsLater): the image was decoded into its slot of the
  // stack in memory, where its bytes stay as the decoder wrote them (pixelDigest of the slot).
  std::string pixelSha256;
};

// The SHA-256 (hex) of `bytes` bytes of decoded samples, as DecodedImage::pixelSha256.
std::string pixelDigest(const void* data, std::size_t bytes);

struct DecodedStacks {
  std::shared_ptr<ImageStack> rgb;        // views of `decoded`
  std::shared_ptr<ImageStack> luminance;
  std::shared_ptr<pipeline::DecodedStack> decoded;
  std::vector<DecodedImage> images;
  std::uint64_t bytesInMemory = 0;  // what `decoded` holds in memory; 0 when spilled
};

// Bytes a pixel of the decoded stack takes, told from the first image's kind before anything
// is decoded: 3 for JPEG (8-bit RGB), at most 6 for the others (16-bit RGB; an 8-bit PNG or
// TIFF takes 3 once decoded).
std::uint64_t storedBytesPerPixel(image::SourceKind kind);

// Whether the stack of `count` images of `pixels` pixels, `bytesPerPixel` each, stays in
// memory under `budget` (bytes), with `laterBytesPerPixel` held besides (see decodeImages).
// The other half of the budget is for the bands the later steps stream and for decoding
// several images at once.
bool stackFitsInMemory(int count, std::uint64_t pixels, std::uint64_t bytesPerPixel, std::uint64_t budget,
                       std::uint64_t laterBytesPerPixel = 0);

// `acceptDamage[i]`: decode image i even if its decoder reports damaged data (the warnings are
// then in images[i].report.decoderWarnings); otherwise such an image is refused with
// image::DamagedImageError. Missing entries are false.
// `laterBytesPerPixel`: what the run holds per pixel after decoding besides the stacks' bands
// (the fitted models the derived maps keep: modelBytesPerPixel); counted in the check against
// --memory so that a run refused for its size is refused before anything is decoded.
// `digestsLater`: the pixel digest of an image decoded into its slot of a stack in memory is
// left to the caller (DecodedImage::pixelSha256 empty), which can take it later, where a core
// is free; the others' are taken here.
DecodedStacks decodeImages(const std::vector<std::filesystem::path>& files,
                           const image::RawDecodeSettings& settings,
                           const pipeline::RunSettings& run,
                           const std::vector<bool>& acceptDamage = {},
                           std::uint64_t laterBytesPerPixel = 0, bool digestsLater = false);

// What decoding one image of `pixels` pixels holds in memory at once: the decoded image, a
// 16-bit copy where the source is raw, and the decoder's working memory (measured: see
// kResidentBytesPerPixel). Everything else of a run streams in bands sized to the budget; the
// stack is in memory or in a temporary file (stackFitsInMemory).
// Measured (surrogate run, --threads 1, 10 x 3 Mpx): 16 bytes per pixel above the process's
// own 80 MB for decoding and light estimation; a whole run 33 (ptm-lrgb), 33 (hsh2), 47 (hsh3)
// and 42 (ptm-lrgb and hsh2), i.e. at most this plus the fitted models' bytes per pixel.
inline constexpr std::uint64_t kResidentBytesPerPixel = 24;
std::uint64_t residentBytesPerImage(std::uint64_t pixels);

// Bytes per pixel of a fitted model held in memory: PTM LRGB 6 coefficients + RGB (9), PTM RGB
// 18, HSH 3 x terms (12 for hsh2, 27 for hsh3). For the check of decodeImages.
std::uint64_t modelBytesPerPixel(const std::string& basis);

}  // namespace surrogate::stages
