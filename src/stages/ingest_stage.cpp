#include "stages/ingest_stage.h"

#include "carrier/advice.h"

#include <algorithm>
#include <atomic>
#include <optional>
#include <set>
#include <unordered_map>

#include "capture/capture.h"
#include "core/digest.h"
#include "core/parallel.h"
#include "core/text.h"
#include "formats/pronom.h"
#include "image/decode.h"
#include "meta/metadata.h"
#include "pipeline/context.h"
#include "stages/inputs.h"
#include "stages/prior_work.h"

namespace surrogate::stages {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "capture ingest";
// The report: written after every run, never recorded (a view of the carrier).
using capture::kReportPath;

struct KnownFormat {
  const char* ext;
  const char* mediaType;
};

// Media type by extension. The PRONOM identifier is not among them: it comes from the bytes
// (formats/pronom.h), as DROID and Siegfried find it.
const KnownFormat* byExtension(const std::string& ext) {
  static const KnownFormat kKnown[] = {
      {".cr2", "image/x-canon-cr2"}, {".crw", "image/x-canon-crw"}, {".cr3", "image/x-canon-cr3"},
      {".nef", "image/x-nikon-nef"}, {".dng", "image/x-adobe-dng"}, {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},       {".tif", "image/tiff"},        {".tiff", "image/tiff"},
      {".png", "image/png"},         {".lp", "text/plain"},         {".xmp", "application/rdf+xml"},
  };
  for (const KnownFormat& k : kKnown)
    if (ext == k.ext) return &k;
  return nullptr;
}

// Media type and PRONOM identifier. The identifier comes from the file's bytes; an image's
// media type from its content (the format the probe found: JPEG, PNG, TIFF, DNG), not its name:
// a PNG named .jpg is image/png. Camera raws other than DNG share the TIFF container, so their
// extension names the camera format. Returns a warning when the name says another format than
// the content.
std::optional<carrier::Advice> setFormatIdentifiers(carrier::FileRecord& f, const fs::path& abs, bool isImage) {
  f.puid = formats::identifyPronomFile(abs).puid;
  const std::string ext = lowerCase(fs::path(f.path).extension().string());
  const KnownFormat* named = byExtension(ext);
  if (!isImage) {
    if (named) f.mediaType = named->mediaType;
    return {};
  }
  const char* contentExt = f.format == "JPEG" ? ".jpg" : f.format == "PNG" ? ".png" : f.format == "TIFF" ? ".tif" : "";
  if (!*contentExt && (f.format == "DNG" || ext == ".dng" || image::isDngFile(abs))) {
    f.format = "DNG";
    contentExt = ".dng";
  }
  const KnownFormat* content = *contentExt ? byExtension(contentExt) : named;
  if (content) f.mediaType = content->mediaType;
  if (named && content && std::string(named->mediaType) != content->mediaType)
    return carrier::Advice{f.path + " is a " + f.format + " file named " + ext + ": it is recorded and read as " +
                               content->mediaType + " (from its content, not its name)",
                           carrier::Usable::Yes, "the photograph is read correctly",
                           "rename it to " + std::string(contentExt) + " so that other software opens it as what it is",
                           ""};
  return {};
}

carrier::Attributes cameraAttributes(const meta::CameraMetadata& m) {
  carrier::Attributes a;
  auto text = [&](const char* name, const std::optional<std::string>& v) {
    if (v && !v->empty()) a.emplace_back(name, *v);
  };
  auto number = [&](const char* name, const auto& v) {
    if (v) a.emplace_back(name, formatNumber(static_cast<double>(*v)));
  };
  auto integer = [&](const char* name, const auto& v) {
    if (v) a.emplace_back(name, std::to_string(*v));
  };
  text("make", m.make);
  text("model", m.model);
  text("serial", m.bodySerial);
  text("lens", m.lens);
  number("focalLengthMm", m.focalLengthMm);
  number("fNumber", m.fNumber);
  text("exposureTime", m.exposureTime);
  number("exposureSeconds", m.exposureSeconds);
  integer("iso", m.iso);
  text("dateTimeOriginal", m.dateTimeOriginal);
  integer("orientation", m.orientation);
  integer("pixelWidth", m.pixelWidth);
  integer("pixelHeight", m.pixelHeight);
  number("focalPlaneXResolution", m.focalPlaneXResolution);
  number("focalPlaneYResolution", m.focalPlaneYResolution);
  integer("focalPlaneResolutionUnit", m.focalPlaneResolutionUnit);
  return a;
}

bool isExportFormat(const std::string& format) {
  return format == "JPEG" || format == "TIFF" || format == "PNG";
}

// An XMP packet that records processing by other software: an editing history (Photoshop,
// Lightroom, Bridge write xmpMM:History or photoshop:History) or Camera Raw development
// settings (crs:). A JPEG/TIFF/PNG "original" carrying one was made by that software, not by
// the camera, so its processing is not in Surrogate's record.
bool editedOutside(const std::string& xmp) {
  for (const char* marker : {"xmpMM:History", "photoshop:History", "crs:Version", "crs:ProcessVersion",
                             "crs:RawFileName"})
    if (xmp.find(marker) != std::string::npos) return true;
  return false;
}

struct PendingFile {
  std::string path;
  std::string role;
  std::string format;
  bool isImage = false;
  int width = 0, height = 0;
  std::string pairedPath;
  bool unrecorded = false;
};

// Why a recorded file of this role may not change, for the fixity failure's message.
std::string whyEvidence(const std::string& role) {
  if (role == "prior")
    return "Prior work (a file another tool made) is evidence: Surrogate never records a new "
           "baseline for it. Restore the file from a backup";
  return "An original is evidence: Surrogate never records a new baseline for it. Restore the "
         "file from the card or a backup";
}

// An original, export, sidecar, dome .lp or prior file, once recorded, is evidence: if its
// bytes changed or it vanished since the previous record, the run stops with a fixity failure
// naming it, unless an `accept-changed-original` intervention accepts exactly what the file is
// now.
void checkAgainstPrevious(const carrier::Step& step, pipeline::Context& ctx) {
  if (!ctx.previous) return;
  const auto recorded = ctx.carrier.filesByPath();  // one look-up per file, not one search
  for (const carrier::FileRecord& before : ctx.previous->files) {
    if (!carrier::isEvidenceRole(before.role)) continue;
    const auto found = recorded.find(before.path);
    const carrier::FileRecord* now = found == recorded.end() ? nullptr : found->second;
    if (now && now->sha256 == before.sha256 && now->size == before.size) continue;
    const std::string state = now ? "sha256:" + now->sha256 : "removed";
    const carrier::Intervention* accepted = nullptr;
    for (const carrier::Intervention* i : step.interventionsOfKind("accept-changed-original"))
      if (i->target == before.path && i->value == state) accepted = i;
    if (accepted) {
      ctx.carrier.addLog("intervention", step.id,
                         before.path + (now ? " changed" : " was removed") +
                             " since it was recorded (SHA-256 was " + before.sha256 +
                             "); accepted: " + accepted->reason,
                         accepted->who);
      continue;
    }
    const std::string what =
        now ? "has changed since it was recorded (SHA-256 " + before.sha256.substr(0, 16) +
                  "..., " + std::to_string(before.size) + " bytes; now " + now->sha256.substr(0, 16) +
                  "..., " + std::to_string(now->size) + " bytes)"
            : "was recorded in the carrier (SHA-256 " + before.sha256.substr(0, 16) +
                  "...) but is no longer in the capture";
    throw Error(ErrorKind::Fixity, before.path, kStep,
                what + ". " + whyEvidence(before.role) + "; if the change is deliberate, accept "
                "it with --accept-changed " + before.path + " --reason \"why\"");
  }
}

// Every file the capture brings, in a fixed order: shots (original, export), .lp, sidecars,
// other files, prior work (`prior`: the files of assembly-files/ and finished-files/ that are).
std::vector<PendingFile> pendingFiles(const capture::CaptureLayout& layout, const std::vector<std::string>& prior) {
  std::vector<PendingFile> pending;
  const bool exportsAreOriginals = !layout.hasOriginals();
  for (const capture::Shot& shot : layout.shots) {
    if (shot.original) {
      pending.push_back({shot.original->relativePath, "original", shot.original->format, true,
                         shot.original->width, shot.original->height,
                         shot.exported ? shot.exported->relativePath : "", false});
    }
    if (shot.exported) {
      pending.push_back({shot.exported->relativePath, exportsAreOriginals ? "original" : "export",
                         shot.exported->format, true, shot.exported->width,
                         shot.exported->height,
                         shot.original ? shot.original->relativePath : "",
                         !exportsAreOriginals});
    }
  }
  if (layout.lp) pending.push_back({*layout.lp, "lp", "LP", false, 0, 0, "", false});
  for (const std::string& s : layout.sidecars)
    pending.push_back({s, "sidecar", "XMP", false, 0, 0, "", false});
  for (const std::string& o : layout.others) {
    std::string ext = fs::path(o).extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    pending.push_back({o, "other", ext.size() > 1 ? ext.substr(1) : "unknown", false, 0, 0, "", false});
  }
  for (const std::string& p : prior) pending.push_back({p, "prior", "", false, 0, 0, "", false});
  return pending;
}

// One file's record, with what went wrong reading it (logged as warnings, never fatal).
struct ReadFile {
  carrier::FileRecord record;
  std::optional<carrier::Advice> formatWarning;
  std::string metadataWarning;
};

// Hashes the file and reads its metadata (images: EXIF/XMP; sidecars: their XMP).
ReadFile readFile(const PendingFile& p, const fs::path& capture) {
  const fs::path abs = capture / p.path;
  const FileDigests d = digestFile(abs);
  ReadFile out;
  carrier::FileRecord& f = out.record;
  f.path = p.path;
  f.role = p.role;
  f.size = d.size;
  f.sha256 = d.sha256;
  f.format = p.format;
  f.unrecordedProcessing = p.unrecorded;
  if (p.role == "prior") {
    const PriorFile prior = describePriorFile(abs, p.path);
    f.priorKind = prior.kind;
    f.madeBy = prior.madeBy;
    f.format = prior.format;
    f.mediaType = prior.mediaType;
    f.puid = formats::identifyPronomFile(abs).puid;
    if (!prior.warning.empty())
      out.formatWarning = carrier::Advice{prior.warning, carrier::Usable::Yes,
                                          "the file is kept and packed as found; only what made it is not recorded",
                                          "nothing, unless you need to know what made it: then check that it is the "
                                          "file you meant to keep beside the capture",
                                          ""};
    return out;
  }
  out.formatWarning = setFormatIdentifiers(f, abs, p.isImage);
  try {
    if (p.isImage) {
      f.imageSize = std::make_pair(p.width, p.height);
      const meta::CameraMetadata m = meta::readMetadata(abs);
      f.camera = cameraAttributes(m);
      f.cameraRaw = m.rawText;
      f.xmp = m.xmpPacket;
      f.xmpEscaped = m.xmpEscaped;
      if (p.role == "original" && isExportFormat(p.format) && editedOutside(f.xmp))
        f.unrecordedProcessing = true;
    } else if (p.role == "sidecar") {
      // A damaged sidecar is still an original to keep and hash; only its reading fails.
      f.xmp = meta::readXmpSidecar(abs, &f.xmpEscaped);
    }
  } catch (const Error& e) {
    out.metadataWarning = e.message();  // the warning names the file itself
  }
  return out;
}

// Reads every pending file in parallel; the records are in the order of `pending`.
std::vector<ReadFile> readFiles(const std::vector<PendingFile>& pending, pipeline::Context& ctx, int threads) {
  std::vector<ReadFile> read(pending.size());
  std::atomic<std::size_t> done{0};
  parallelFor(pending.size(), 1, threads, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      read[i] = readFile(pending[i], ctx.capture);
      ctx.progress("Hashing and reading metadata", double(++done) / pending.size());
    }
  });
  return read;
}

// Puts the records in the carrier, with their warnings, and pairs originals with exports.
void recordFiles(pipeline::Context& ctx, const carrier::Step& step, const std::vector<PendingFile>& pending,
                 const std::vector<ReadFile>& read) {
  std::vector<carrier::FileRecord> records;
  records.reserve(read.size());
  for (const ReadFile& r : read) records.push_back(r.record);
  ctx.carrier.putFiles(std::move(records));  // one pass: putFile per file was quadratic
  for (const ReadFile& r : read) {
    if (r.formatWarning) carrier::addWarning(ctx.carrier, step.id, *r.formatWarning);
    if (!r.metadataWarning.empty()) {
      const bool sidecar = r.record.role == "sidecar";
      carrier::addWarning(
          ctx.carrier, step.id,
          {r.record.path + (sidecar ? ": the XMP sidecar cannot be read" : ": its camera metadata (EXIF, XMP) cannot be read"),
           carrier::Usable::Yes,
           sidecar ? "the sidecar is kept and packed as found, but what it says is not in the record"
                   : "the photograph is used as usual, but the record lacks its camera settings (exposure, lens, date)",
           sidecar ? "open the sidecar in a text editor or your photo software to see whether it is damaged; a "
                     "repaired copy is read on the next run"
                   : "nothing for the result; if the camera settings matter for the record, check the file in the "
                     "camera maker's software",
           r.metadataWarning});
    }
  }
  std::unordered_map<std::string, carrier::FileRecord*> byPath;
  for (carrier::FileRecord& f : ctx.carrier.files) byPath.emplace(f.path, &f);
  for (const PendingFile& p : pending) {
    if (p.pairedPath.empty()) continue;
    byPath.at(p.path)->pairedWith = byPath.at(p.pairedPath)->id;
  }
}

// The files of assembly-files/ and finished-files/ that are prior work (prior_work.h); the
// others are Surrogate's own, recorded again by the steps that write them. One the carrier
// does not record is a leftover of an interrupted run, which this run replaces: logged.
std::vector<std::string> priorWorkOf(pipeline::Context& ctx, const carrier::Step& step,
                                     const capture::CaptureLayout& layout) {
  const std::vector<std::string> planned = plannedOutputs(ctx.carrier);
  std::vector<std::string> prior;
  for (const std::string& path : layout.outputFolderFiles) {
    if (isPriorWork(path, ctx.previous, planned)) prior.push_back(path);
    else if (!ctx.previous->findFileByPath(path) && path != kReportPath)
      ctx.carrier.addLog("info", step.id, path + " is not in the carrier but lies where this run writes: "
                         "taken for what an interrupted run of Surrogate left, and replaced");
  }
  return prior;
}

// The files of the capture that are not photographs: kept (other files, prior work) or left
// out (system files).
void logOtherFiles(pipeline::Context& ctx, const carrier::Step& step, const capture::CaptureLayout& layout) {
  for (const std::string& o : layout.others)
    ctx.carrier.addLog("info", step.id, "kept " + o + " as an other file of the capture (recorded "
                       "and packed, not an image the pipeline reads)");
  for (const carrier::FileRecord& f : ctx.carrier.files)
    if (f.role == "prior")
      ctx.carrier.addLog("info", step.id, "kept " + f.path + " as prior work (" + f.priorKind +
                         (f.madeBy.empty() ? "; the file does not say what made it" : "; the file says: " + f.madeBy) +
                         "): made by another tool, recorded and packed, never modified or written over");
  for (const std::string& junk : layout.systemFiles)
    ctx.carrier.addLog("info", step.id, "left out " + junk + ": a file the operating system made, "
                       "not part of the capture (not recorded, not packed)");
}

// Processing that other software did and this record cannot hold.
void logUnrecordedProcessing(pipeline::Context& ctx, const carrier::Step& step, const capture::CaptureLayout& layout) {
  for (const carrier::FileRecord& f : ctx.carrier.files)
    if (f.role == "original" && f.unrecordedProcessing)
      carrier::addWarning(ctx.carrier, step.id,
                          {f.path + " is a " + f.format + " whose XMP records processing by other software (editing "
                               "history or raw development settings), which is not in this record",
                           carrier::Usable::Yes,
                           "the result is sound, but a reader of the record cannot see that processing",
                           "if you have the unprocessed camera file, use it instead; otherwise nothing (the file is "
                           "flagged and its XMP is kept)",
                           "flagged unrecordedProcessing"});
  if (layout.hasOriginals() && layout.hasExports()) {
    ctx.carrier.addLog("info", step.id,
                       "the files in jpeg-exports/ were made by other software: their processing "
                       "is not recorded (flagged unrecordedProcessing in the files section)");
  }
}

// The shots the exclude-image interventions name; each must name a shot of this capture.
std::set<std::string> excludedShots(pipeline::Context& ctx, const carrier::Step& step,
                                    const capture::CaptureLayout& layout) {
  std::set<std::string> excluded;
  for (const carrier::Intervention* i : step.interventionsOfKind("exclude-image")) {
    const auto stem = capture::findShotStem(layout, i->target);
    if (!stem) {
      throw Error(ErrorKind::Usage, i->target, kStep,
                  "is excluded but no image of the capture has that name; give the file name "
                  "as it is in original-captures/ or jpeg-exports/");
    }
    excluded.insert(*stem);
    ctx.carrier.addLog("intervention", step.id,
                       "excluded " + *stem + " from processing: " + i->reason, i->who);
  }
  return excluded;
}

// The images the pipeline reads (the source's choice, less the excluded shots), recorded as
// the step's inputs.
std::shared_ptr<InputImages> chooseInputs(pipeline::Context& ctx, carrier::Result& result,
                                          const capture::CaptureLayout& layout, capture::Source source,
                                          const std::set<std::string>& excluded) {
  const std::vector<capture::ImageFile> chosen = capture::selectImages(layout, source);
  const auto recorded = ctx.carrier.filesByPath();
  auto inputs = std::make_shared<InputImages>();
  for (const capture::ImageFile& image : chosen) {
    const std::string stem = fs::path(image.relativePath).stem().string();
    const std::string id = recorded.at(image.relativePath)->id;
    if (excluded.count(stem)) {
      result.add("imageValue").set("image", id).set("name", "excluded").set("value", "true");
      continue;
    }
    result.add("input").set("file", id).set("kind", "image");
    inputs->push_back({id, image.relativePath, stem});
  }
  const bool usesOriginals = !chosen.empty() && layout.hasOriginals() &&
                             chosen.front().relativePath.rfind(layout.originalsDir + "/", 0) == 0;
  result.add("value").set("name", "source").set("value", usesOriginals ? "original" : "export");
  result.add("value").set("name", "images").set("value", std::to_string(inputs->size()));
  if (layout.lp) {
    result.add("input").set("file", ctx.carrier.findFileByPath(*layout.lp)->id).set("kind", "lp");
  }
  return inputs;
}

}  // namespace

pipeline::StageInfo IngestStage::info() {
  // 2: other files of the capture recorded (role "other"), system files left out, links
  // refused, the dome .lp chosen by the "lp" parameter, recorded originals compared.
  // 3: every file's PRONOM identifier from its bytes (formats/pronom.h): JPEG, DNG, PNG and
  //    XMP ones too, which had none; camera raws are no longer identified by extension.
  // Its parameters (source, lp) come from the request, not from defaults (run/plan.cpp).
  pipeline::StageInfo info{kComponent, "3", "Read the capture folder, hash every file, read EXIF/XMP",
                           pipeline::PlanSlot::Ingest};
  info.reads = pipeline::alwaysReads({});
  return info;
}

void IngestStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const int threads = effectiveThreads(ctx.settings.threads);
  const capture::Source source = capture::parseSource(step.param("source", "auto"));
  ctx.progress("Reading the capture", 0);
  const std::string lp = step.param("lp", "");
  const std::shared_ptr<const ScannedCapture> scanned =
      ctx.has(kScannedCapture) ? ctx.get<const ScannedCapture>(kScannedCapture) : nullptr;
  std::optional<capture::CaptureLayout> ownScan;
  if (!scanned || scanned->lp != lp) ownScan = capture::scanCapture(ctx.capture, threads, lp);
  const capture::CaptureLayout& layout = ownScan ? *ownScan : scanned->layout;
  const std::vector<PendingFile> pending = pendingFiles(layout, priorWorkOf(ctx, step, layout));
  recordFiles(ctx, step, pending, readFiles(pending, ctx, threads));
  logOtherFiles(ctx, step, layout);
  checkAgainstPrevious(step, ctx);
  logUnrecordedProcessing(ctx, step, layout);
  const std::set<std::string> excluded = excludedShots(ctx, step, layout);
  auto inputs = chooseInputs(ctx, result, layout, source, excluded);
  if (inputs->empty())
    throwInputError(ctx.capture.string(), kStep, "every image is excluded: nothing to process");
  ctx.put(kInputImages, inputs);
}

}  // namespace surrogate::stages
