// The WebCopy stage: the web layout of a fitted model (publish/web_layout.h: info.json, the
// JPEG coefficient planes whole or as Deep Zoom tiles, index.html and viewer-data.js) written
// into finished-files/web/<model>/ (and finished-files/web/index.html linking the models) and recorded as results of the step, so that the package
// holds it as its access copy (docs/package.md) and `verify --reexecute` makes it again.
// Planned by `surrogate run --publish`, once per model fitted (pipeline::PlanSlot::Publish).
#pragma once

#include <string>

#include "pipeline/stage.h"

namespace surrogate::stages {

// The parameters of WebCopy (publish::PublishOptions without threads, which is not a setting
// of the result). Names and defaults are a record: never change them.
struct WebCopyOptions {
  std::string model = "ptm-lrgb";  // a basis fitted by an earlier RtiFit step
  // JPEG quality 1..100 of the planes: lower gives smaller files and a larger relighting error.
  int quality = 95;
  // auto (tiles for a side over 4096 texels), none or deepzoom.
  std::string tiles = "auto";
  // Side of a Deep Zoom tile, 16..4096 texels: fewer files against less data beyond the screen.
  int tileSize = 256;

  pipeline::Parameters toParameters() const;
  // Error(Input) naming the parameter for an unknown name, a model that is not a basis, a
  // quality or tile size out of range or an unknown tile layout.
  static WebCopyOptions fromParameters(const pipeline::Parameters& parameters);
};

// Where WebCopy writes the layout of `basis`: finished-files/web/<basis>.
std::string webCopyFolder(const std::string& basis);
// The page linking every model's folder: finished-files/web/index.html, written by the last
// WebCopy step of the process list.
std::string webIndexPath();

class WebCopyStage : public pipeline::DescribedStage<WebCopyStage> {
 public:
  static constexpr const char* kComponent = "WebCopy";
  static pipeline::StageInfo info();
  void run(const carrier::Step&, pipeline::Context&, carrier::Result&) override;
};

}  // namespace surrogate::stages
