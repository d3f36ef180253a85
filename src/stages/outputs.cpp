#include "stages/outputs.h"

#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "formats/pronom.h"
#include "image/png_encoder.h"

namespace surrogate::stages {

std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType) {
  return recordOutput(ctx, step, result, relativePath, digestFile(ctx.outputPath(relativePath)), role, format,
                      kind, mediaType);
}

std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const FileDigests& d, const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType) {
  WrittenFile written;
  written.digests = d;
  written.puid = formats::identifyPronomFile(ctx.outputPath(relativePath)).puid;  // from the bytes, as DROID
  return recordOutput(ctx, step, result, relativePath, written, role, format, kind, mediaType);
}

std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const WrittenFile& written, const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType) {
  // The plan refuses this before any step runs (prior_work.h); a record of prior work is
  // never replaced by one of Surrogate's results.
  if (const carrier::FileRecord* before = ctx.carrier.findFileByPath(relativePath); before && before->role == "prior")
    throw Error(ErrorKind::Input, relativePath, step.component,
                "is prior work (a file Surrogate did not write): Surrogate never writes over it; move it "
                "into a folder of its own, e.g. " + std::filesystem::path(relativePath).parent_path().generic_string() +
                    "/prior/, then run again");
  carrier::FileRecord f;
  f.path = relativePath;
  f.role = role;
  f.size = written.digests.size;
  f.sha256 = written.digests.sha256;
  f.format = format;
  f.mediaType = mediaType;
  f.puid = written.puid;
  f.createdBy = step.id;
  const std::string id = ctx.carrier.putFile(std::move(f));
  result.add("output").set("file", id).set("kind", kind);
  return id;
}

WrittenFile writePicture(const pipeline::Context& ctx, const Image& picture, const std::string& relativePath,
                         const std::function<void()>& encoded) {
  const std::filesystem::path path = ctx.outputPath(relativePath);
  const std::string bytes = image::encodePng(picture, path.string());
  if (ctx.settings.pictureWritten) ctx.settings.pictureWritten(relativePath, picture);
  if (encoded) encoded();
  writeFileAtomically(path, bytes);
  WrittenFile written;
  written.digests.size = bytes.size();
  written.digests.sha256 = sha256Hex(bytes);
  written.puid = formats::identifyPronomNamed(bytes, path.filename().string()).puid;  // from the bytes, as DROID
  return written;
}

std::string checkedOutputPath(const std::string& relativePath) {
  const std::filesystem::path p(relativePath);
  bool safe = !p.is_absolute() && relativePath.find('\\') == std::string::npos;
  for (const auto& part : p) safe = safe && part != ".." && part != ".";
  const std::string first = p.begin() == p.end() ? "" : p.begin()->string();
  safe = safe && (first == "assembly-files" || first == "finished-files") &&
         std::distance(p.begin(), p.end()) >= 2;
  if (!safe)
    throw Error(ErrorKind::Input, relativePath, "carrier",
                "is not an acceptable output name: outputs go inside assembly-files/ or "
                "finished-files/ of the capture");
  return relativePath;
}

std::vector<std::pair<std::string, std::string>> parametersOf(const carrier::Step& step) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const carrier::Param& p : step.params) out.emplace_back(p.name, p.value);
  return out;
}

}  // namespace surrogate::stages
