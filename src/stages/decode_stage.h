// ImageDecode: decodes every input image once into two streaming stacks on the context:
//   rgb-stack        display-referred (sRGB-encoded) 16-bit RGB, what the fitters read
//   luminance-stack  Rec. 709 luminance of the decoded values (linear for camera raw), what
//                    sphere and highlight detection read
// Camera raw and DNG go through LibRaw with every setting fixed by the step's parameters
// (recorded, re-applied on re-execution); JPEG/TIFF/PNG through libjpeg, libtiff and libpng.
// Each decoded image is recorded with its decoder, levels and a SHA-256 of its pixels, so a
// verifier can tell a decoder change from a processing change.
//
// Decoding is strict: an image whose decoder reports damaged data is refused with the
// library's words, unless an intervention `accept-decoder-warning` (target: the file's path in
// the capture; value: "sha256:<hex>" of the bytes accepted) accepts it; the decoder's words are
// then recorded as `imageValue decoderWarning` and in the log with who accepted it and why.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

inline constexpr const char* kAcceptDecoderWarning = "accept-decoder-warning";

class DecodeStage : public pipeline::DescribedStage<DecodeStage> {
 public:
  static constexpr const char* kComponent = "ImageDecode";
  static pipeline::StageInfo info();  // in decode_stage.cpp, with the version history
  void run(const carrier::Step& step, pipeline::Context& context,
           carrier::Result& result) override;
};

}  // namespace surrogate::stages
