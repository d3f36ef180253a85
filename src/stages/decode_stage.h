// ImageDecode: decodes every input image once into two streaming stacks on the context:
//   rgb-stack        display-referred (sRGB-encoded) 16-bit RGB, what the fitters read
//   luminance-stack  Rec. 709 luminance of the decoded values (linear for camera raw), what
//                    sphere and highlight detection read
// Camera raw and DNG go through LibRaw with every setting fixed by the step's parameters
// (recorded, re-applied on re-execution); JPEG/TIFF/PNG through OpenCV. Each decoded image is
// recorded with its decoder, levels and a SHA-256 of its pixels, so a verifier can tell a
// decoder change from a processing change.
#pragma once

#include "pipeline/stage.h"

namespace surrogate::stages {

class DecodeStage : public pipeline::Stage {
 public:
  std::string component() const override { return "ImageDecode"; }
  std::string version() const override { return "1"; }
  void run(const carrier::Step& step, pipeline::Context& context,
           carrier::Result& result) override;
};

}  // namespace surrogate::stages
