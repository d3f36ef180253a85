// Private to src/stages: what the pre-processing stages (WhiteBalance, Crop, Resize) share.
//
// The pre-processing stages: recorded steps that change the photographs the fit reads, never
// the files (the originals stay untouched) and never the light estimation (sphere and
// highlight detection always read the full, decoded frame). `surrogate run` plans them after
// the light stages and before RtiFit, in this order: WhiteBalance, Crop, Resize; a carrier may
// order them otherwise, and re-execution follows the carrier. Each replaces the "rgb-stack"
// the fit reads with a view computed on demand (see stack_views.h): no copy, bounded memory,
// identical values at any thread count.
//
// Parameters: see preprocess.h (CropOptions, ResizeOptions, WhiteBalanceOptions).
#pragma once

#include <string>

#include "carrier/carrier.h"
#include "core/error.h"
#include "core/stack.h"
#include "stages/preprocess.h"

namespace surrogate::stages {

// "WxH", as messages and records show a size.
inline std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// Whether `r` lies wholly inside the frame of the images of `s`.
inline bool inside(const PixelRect& r, const ImageStack& s) {
  return r.x >= 0 && r.y >= 0 && r.width > 0 && r.height > 0 &&
         static_cast<long long>(r.x) + r.width <= s.width() &&
         static_cast<long long>(r.y) + r.height <= s.height();
}

// Error(Usage) for a rectangle (`option` r) outside the images the step receives.
[[noreturn]] inline void outsideFrame(const std::string& option, const PixelRect& r, const ImageStack& s,
                                      const carrier::Step& step) {
  throw Error(ErrorKind::Usage, option + " " + r.text(), step.component,
              "the rectangle reaches outside the " + sizeText(s.width(), s.height()) +
                  " images this step receives (carrier step " + step.id +
                  "); give X,Y,W,H with X+W <= " + std::to_string(s.width()) + " and Y+H <= " +
                  std::to_string(s.height()));
}

// A <value name=... value=... unit=...> item of the step's result.
inline void recordValue(carrier::Result& result, const std::string& name, const std::string& value,
                        const std::string& unit = "") {
  carrier::DataItem& item = result.add("value").set("name", name).set("value", value);
  if (!unit.empty()) item.set("unit", unit);
}

}  // namespace surrogate::stages
