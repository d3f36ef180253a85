#include "stages/outputs.h"

#include "core/digest.h"
#include "core/error.h"

namespace surrogate::stages {

std::string recordOutput(pipeline::Context& ctx, const carrier::Step& step,
                         carrier::Result& result, const std::string& relativePath,
                         const std::string& role, const std::string& format,
                         const std::string& kind, const std::string& mediaType) {
  const FileDigests d = digestFile(ctx.outputPath(relativePath));
  carrier::FileRecord f;
  f.path = relativePath;
  f.role = role;
  f.size = d.size;
  f.sha256 = d.sha256;
  f.format = format;
  f.mediaType = mediaType;
  f.createdBy = step.id;
  const std::string id = ctx.carrier.putFile(std::move(f));
  result.add("output").set("file", id).set("kind", kind);
  return id;
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
