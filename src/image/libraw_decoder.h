// Private to src/image: camera raw and DNG through LibRaw (the thread-safe libraw_r build).
//
//   open_file (parse headers) -> unpack (read the mosaic) -> dcraw_process (black, white balance,
//   demosaic, colour matrix) -> copy_mem_image (16-bit RGB, linear gamma), into
//   DecodeOptions::destination's buffer when it gives one
//
// One LibRaw object per call, on the heap (it is several hundred kilobytes), so calls from
// several threads never share state. LibRaw's data-error callback is collected rather than
// printed: the end of the file is an Error (truncated); corrupt data is damage, refused
// (DamagedImageError) unless DecodeOptions::acceptDamage.
#pragma once

#include <filesystem>

#include "image/decode.h"

namespace surrogate::image {

// 16-bit samples in `wide`, or at `placed` (see DecodedPixels).
DecodedPixels decodeCameraRaw(const std::filesystem::path& path, const RawDecodeSettings& settings,
                              DecodeReport* report, const DecodeOptions& options);

// Header parse only (open_file): the size decodeCameraRaw gives with default settings.
// Reading the mosaic (unpack) would find damaged pixel data, but costs about 0.2 s per 24 Mpx
// file; decodeCameraRaw finds it instead, with the same message.
ImageProbe probeCameraRaw(const std::filesystem::path& path);

}  // namespace surrogate::image
