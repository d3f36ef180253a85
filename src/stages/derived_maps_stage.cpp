#include "stages/derived_maps_stage.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <numeric>
#include <thread>
#include <vector>

#include "capture/capture.h"
#include "carrier/advice.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/text.h"
#include "fit/fit.h"
#include "fit/learned.h"
#include "fit/render.h"
#include "image/decode.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/outputs.h"
#include "stages/rti_fit_stage.h"

namespace surrogate::stages {

namespace {
constexpr const char* kModelParameter = "model";

// The previews DerivedMaps renders: a raking light from the upper left (elevation 20 deg,
// azimuth 135 deg), from the top, and a specular-enhanced view, as photographers look at RTI
// first.
struct Preview {
  const char* name;
  double elevationDeg, azimuthDeg;
  bool specular;
};
constexpr Preview kPreviews[] = {{"preview-raking.png", 20, 135, false},
                                 {"preview-top.png", 70, 90, false},
                                 {"preview-specular.png", 45, 135, true}};
constexpr const char* kNormalsFile = "normals.png";
constexpr const char* kAlbedoFile = "albedo.png";

std::string finished(const std::string& name) { return std::string(capture::kFinishedDir) + "/" + name; }

// PNG files written on threads of their own while the next picture is computed: computing a
// map already uses every core, but libdeflate compresses one file on one core, and encoding is
// most of the stage's time (the 16-bit normals of 3000x2000 take about 0.5 s). As many files are
// encoded at once as there are threads, by encoders that take the pictures in the order given
// (the normals, the longest to encode, first); the next picture is computed meanwhile, and is
// queued for the first encoder free. The pictures are computed as fast as memory allows, not
// one per file encoded: waiting for an encoder to be free before computing the next had left
// a core idle while the last picture, computed late, was encoded alone (36 x 1200x800: the
// stage's last third on one core). Memory holds the pictures queued and being encoded, up to
// an eighth of what --memory leaves for streaming, and never fewer than the encoders take at
// once: at 60 x 24 Mpx (pictures of 144 MB) the three of the five with two threads it held
// before, at 1200x800 all five (17 MB). An encoded picture is let go of at once, its PNG bytes
// once on disk (the next encoding starts while a file waits for the disk, its fsync, which
// holds no core). Each file's bytes come from its pixels alone, and the carrier records them
// on the caller's thread in the order given, so the files and the carrier are the same at any
// thread count. With one thread, each is written before the next is computed.
class OverlappedPngWrites {
 public:
  explicit OverlappedPngWrites(const pipeline::Context& ctx)
      : ctx_(ctx),
        encoders_(effectiveThreads(ctx.settings.threads) > 1 ? effectiveThreads(ctx.settings.threads) : 0),
        maxHeldBytes_(ctx.settings.streamingBudget() / 8) {}
  OverlappedPngWrites(const OverlappedPngWrites&) = delete;
  OverlappedPngWrites& operator=(const OverlappedPngWrites&) = delete;
  // Leaving by an error: the pictures queued are not written, those being encoded are let end.
  ~OverlappedPngWrites() { stop(); }

  // Writes `image` as the file `relativePath` (writePicture), then calls `record` with what the
  // write knows of the file (on this thread, after the previous records).
  void add(Image image, std::string relativePath, std::function<void(const WrittenFile&)> record) {
    if (encoders_ == 0) {
      record(writePicture(ctx_, image, relativePath));
      return;
    }
    auto job = std::make_unique<Job>();
    job->bytes = image.pixels.size() * sizeof(image.pixels[0]);
    job->image = std::move(image);
    job->path = std::move(relativePath);
    std::future<WrittenFile> written = job->result.get_future();
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] {
        return held_ < encoders_ || heldBytes_ + job->bytes <= maxHeldBytes_;
      });
      ++held_;
      heldBytes_ += job->bytes;
      queue_.push_back(std::move(job));
      while (static_cast<int>(threads_.size()) < std::min<int>(encoders_, static_cast<int>(queue_.size()) + busy_))
        threads_.emplace_back([this] { encode(); });
    }
    changed_.notify_all();
    pending_.push_back({std::move(written), std::move(record)});
    // Records what is written, in order, up to the first write still running.
    while (!pending_.empty() &&
           pending_.front().write.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
      finishOldest();
  }

  // Whether files are written while the next picture is computed (else each before the next).
  bool overlapped() const { return encoders_ > 0; }

  // Waits for every pending write (rethrowing the first error) and records them in order.
  void finish() {
    while (!pending_.empty()) finishOldest();
    stop();
  }

 private:
  struct Job {
    Image image;
    std::string path;
    std::size_t bytes = 0;
    std::promise<WrittenFile> result;
  };
  struct Pending {
    std::future<WrittenFile> write;
    std::function<void(const WrittenFile&)> record;
  };

  // An encoder: the queue's pictures in order until it is empty and stop() is called.
  void encode() {
    for (;;) {
      std::unique_ptr<Job> job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;
        job = std::move(queue_.front());
        queue_.pop_front();
        ++busy_;
      }
      // Counted out once the picture is encoded, or however the write ends, so that add()
      // never waits for a write that has failed.
      bool counted = true;
      const auto out = [&] {
        if (!counted) return;
        counted = false;
        job->image = Image();
        {
          std::lock_guard<std::mutex> lock(mutex_);
          --held_;
          heldBytes_ -= job->bytes;
        }
        changed_.notify_all();
      };
      try {
        WrittenFile file = writePicture(ctx_, job->image, job->path, out);
        out();
        job->result.set_value(std::move(file));
      } catch (...) {
        out();
        job->result.set_exception(std::current_exception());
      }
      std::lock_guard<std::mutex> lock(mutex_);
      --busy_;
    }
  }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      queue_.clear();  // their futures report a broken promise, which nothing waits for
    }
    changed_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
  }

  void finishOldest() {
    Pending p = std::move(pending_.front());
    pending_.pop_front();
    p.record(p.write.get());
  }

  const pipeline::Context& ctx_;
  const int encoders_;              // files encoded at once; 0: each written at once, on the caller's thread
  const std::size_t maxHeldBytes_;  // pictures queued and being encoded, beyond `encoders_` of them
  std::deque<Pending> pending_;     // the caller's: writes not yet recorded, in order
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable changed_;  // a picture queued or let go of, or stopping
  std::deque<std::unique_ptr<Job>> queue_;  // under mutex_, as the counts below
  int held_ = 0;                   // pictures queued or being encoded
  std::size_t heldBytes_ = 0;
  int busy_ = 0;                   // encoders with a picture
  bool stopping_ = false;
};
}  // namespace

pipeline::Parameters DerivedMapsOptions::toParameters() const { return {{kModelParameter, model}}; }

DerivedMapsOptions DerivedMapsOptions::fromParameters(const pipeline::Parameters& parameters) {
  DerivedMapsOptions o;
  for (const auto& [name, value] : parameters) {
    if (name != kModelParameter)
      throw Error(ErrorKind::Input, name + "=" + value, "derived maps",
                  "is not a parameter of DerivedMaps (model)");
    try {
      if (!fit::isLearnedBasisName(value)) fit::parseBasis(value);
    } catch (const Error&) {
      throw Error(ErrorKind::Input, name + "=" + value, "derived maps",
                  "is not a model Surrogate fits (ptm-lrgb, ptm-rgb, hsh2, hsh3, rbf, bln)");
    }
    o.model = value;  // as recorded: the key RtiFit or LearnedFit put the model under (modelKey)
  }
  return o;
}

pipeline::StageInfo DerivedMapsStage::info() {
  pipeline::StageInfo info = pipeline::withOptions<DerivedMapsOptions>(
      // Version 2: the Lambertian fit of normals and albedo multiplies the coefficients by the
      // fit matrix composed with the basis (src/fit/lambert.h), a different rounding that can
      // move a sample by one level; its PNG files are encoded with fixed Up filters and
      // run-length deflate (src/image/png_encoder.h). Version 3: those PNG files compressed by
      // libdeflate at level 1 (src/image/png_encoder.h). Version 4: the PNG files carry an iTXt
      // chunk (PNG 1.2, fmt/13) and their PRONOM identifier is recorded (formats/pronom.h); the
      // pixels are the same. Version 5: albedo.png is the model at the normal (the intensity a
      // light along the normal gives, in the model's encoding: src/fit/normals.h), no longer
      // |b| of the Lambertian fit, which overshoots it for sRGB-encoded models.
      {kComponent, "5", "Surface normals, albedo and relit previews from a model",
       pipeline::PlanSlot::AfterModels});
  info.forModel = [](const std::string& basis) {
    DerivedMapsOptions o;
    // A learned basis first: the maps of the model as a viewer shows it (LearnedFit).
    o.model = fit::isLearnedBasisName(basis) ? basis : fit::basisName(fit::parseBasis(basis));
    return o.toParameters();
  };
  info.outputs = [](const carrier::Step&) {
    std::vector<std::string> out = {finished(kNormalsFile), finished(kAlbedoFile)};
    for (const Preview& p : kPreviews) out.push_back(finished(p.name));
    return out;
  };
  info.reads = [](const carrier::Step& step) {
    return std::vector<std::string>{modelKey(DerivedMapsOptions::fromParameters(parametersOf(step)).model)};
  };
  return info;
}

namespace {

// The pixels whose normal is not the model's own (fit/normals.h, FALLBACK), in words: a few
// are usual (info); above 5 % a warning says the map is still usable and what a user who
// measures shape from it can do. PTM: no brightest direction, so the Lambertian fit stands in
// (as HSH and learned normals use everywhere); the others: no fit at all, left facing the camera.
void logNormalFallback(pipeline::Context& ctx, const carrier::Step& step, const std::string& basis, int fallback,
                       double pixels) {
  const double fraction = fallback / pixels;
  const bool ptm = basis.rfind("ptm", 0) == 0;
  const std::string figure = std::to_string(fallback) + " pixels (" + fixedDecimals(100 * fraction, 2) + " %)" +
                             (ptm ? " had no valid PTM maximum and took the least-squares Lambertian normal"
                                  : " had no Lambertian normal and were left facing the camera");
  if (!(fraction > 0.05)) {
    ctx.carrier.addLog("info", step.id, figure);
    return;
  }
  carrier::Advice a;
  a.detail = figure;
  if (ptm) {
    a.what = "In " + fixedDecimals(100 * fraction, 0) + " % of the picture the PTM has no single brightest light "
             "direction (usual in shadows, shiny or dark areas), so the normal map takes their direction from a "
             "matte-surface fit instead, the method the HSH normals use everywhere";
    a.usable = carrier::Usable::Yes;
    a.why = "the normal map is complete and the relighting is not affected";
    a.todo = "nothing for viewing; if you measure shape from the normals, compare them with those of the HSH fit "
             "(run again with --basis hsh2 --basis ptm-lrgb: the first basis named gives the normals)";
  } else {
    a.what = "In " + fixedDecimals(100 * fraction, 0) + " % of the picture the " + basis + " fit gives no surface "
             "direction (the pixels stay dark under every light), so the normal map shows them facing the camera";
    a.usable = carrier::Usable::WithCare;
    a.why = "the normals of those pixels are a placeholder, the rest of the map and the relighting are not affected";
    a.todo = "check the normal map's dark or shadowed areas; if they matter, photograph them with lights that reach them";
  }
  carrier::addWarning(ctx.carrier, step.id, a);
}

}  // namespace

void DerivedMapsStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const std::string basis = DerivedMapsOptions::fromParameters(parametersOf(step)).model;
  const auto model = ctx.get<fit::Relightable>(modelKey(basis));
  // Five pictures of about equal cost (normals, albedo, three previews): the bar moves by one
  // fifth as each is written.
  int pictures = 0;
  const auto written = [&ctx, &pictures] { ctx.progress("Normals, albedo and previews", pictures++ / 5.0); };
  written();
  OverlappedPngWrites writes(ctx);
  const auto record = [&](const std::string& name, const WrittenFile& file, const char* kind) {
    recordOutput(ctx, step, result, finished(name), file, "result", "PNG", kind, "image/png");
    written();
  };

  int fallback = 0;
  // Normals and albedo made together (a PTM finds each texel's normal once for both) when the
  // normals are written meanwhile anyway, which holds both pictures; with one thread, one by one.
  Image normals, albedo;
  if (writes.overlapped()) {
    model->normalAndAlbedoMaps(&normals, &albedo, &fallback, ctx.settings.threads);
  } else {
    normals = model->normalMap(&fallback, ctx.settings.threads);
  }
  writes.add(std::move(normals), finished(kNormalsFile), [&](const WrittenFile& file) {
    record(kNormalsFile, file, "normals");
    result.add("value").set("name", "normalFallbackPixels").set("value", std::to_string(fallback));
    logNormalFallback(ctx, step, basis, fallback, double(model->width()) * model->height());
  });
  if (!writes.overlapped()) albedo = model->albedoMap(ctx.settings.threads);
  writes.add(std::move(albedo), finished(kAlbedoFile),
             [&](const WrittenFile& file) { record(kAlbedoFile, file, "albedo"); });
  for (const Preview& p : kPreviews) {
    const double e = p.elevationDeg * M_PI / 180, a = p.azimuthDeg * M_PI / 180;
    fit::RenderOptions options;
    options.specular = p.specular && basis.rfind("ptm", 0) == 0;
    options.threads = ctx.settings.threads;
    const std::array<double, 3> light{std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    writes.add(model->render(light, options), finished(p.name),
               [&record, &p](const WrittenFile& file) { record(p.name, file, "preview"); });
  }
  writes.finish();
}

}  // namespace surrogate::stages
