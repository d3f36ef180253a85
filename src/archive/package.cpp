#include "archive/package.h"

#include <algorithm>
#include <map>
#include <set>

#include "archive/digest.h"
#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/resources.h"
#include "core/version.h"
#include "mapping/mapping.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

namespace {

constexpr const char* kCarrierPath = "assembly-files/carrier.xml";

constexpr const char* kReportPath = "finished-files/report.html";

std::string relativeSlash(const fs::path& p, const fs::path& root) {
  return p.lexically_relative(root).generic_u8string();
}

bool isOutputPath(const std::string& rel) {
  return rel.rfind("assembly-files/", 0) == 0 || rel.rfind("finished-files/", 0) == 0;
}

// Leftovers of an interrupted atomic write by Surrogate (".name.part-PID-N", core/atomic_file)
// in its own output folders: never payload. (In the input folders such a name is a file the
// photographer brought, and is recorded like any other.)
bool isSurrogateLeftover(const std::string& rel) {
  const std::string name = rel.substr(rel.find_last_of('/') + 1);
  return isOutputPath(rel) && !name.empty() && name[0] == '.' && name.find(".part-") != std::string::npos;
}

// Every file of the capture by the shared rule (package.h), relative, '/' separated, sorted.
// Symbolic links are listed too: the bag writer refuses them, naming them.
std::vector<std::string> captureFiles(const fs::path& capture) {
  std::vector<std::string> out;
  for (auto it = fs::recursive_directory_iterator(capture); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it.depth() == 0 && (name == capture::kWorkDir || name == capture::kSupersededDir)) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (capture::isSystemFile(name)) {
      if (it->is_directory() && !it->is_symlink()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_directory() && !it->is_symlink()) continue;
    const std::string rel = relativeSlash(it->path(), capture);
    if (!isSurrogateLeftover(rel)) out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}


}  // namespace

CarrierState checkCarrier(const fs::path& capture) {
  const fs::path file = capture / kCarrierPath;
  if (!fs::exists(file)) return {false, "the capture has not been processed (no " + std::string(kCarrierPath) + ")"};
  carrier::Carrier c;
  try {
    c = carrier::loadCarrier(file);
  } catch (const Error& e) {
    return {false, "the carrier cannot be read (" + e.message() + ")"};
  }
  CarrierState state;
  for (const std::string& rel : captureFiles(capture))
    if (isOutputPath(rel) && rel != kReportPath && rel != kCarrierPath && !c.findFileByPath(rel))
      state.unrecordedOutputs.push_back(rel);
  auto incomplete = [&](const std::string& why) {
    if (state.reason.empty()) state.reason = why;
  };
  for (const carrier::FileRecord& f : c.files) {
    std::error_code ec;
    const fs::path p = capture / fs::u8path(f.path);
    std::string problem;
    if (!fs::is_regular_file(fs::symlink_status(p, ec))) problem = f.path + " is missing";
    else if (fs::file_size(p, ec) != f.size) problem = f.path + " changed size since it was recorded";
    if (problem.empty()) continue;
    if (carrier::isEvidenceRole(f.role) && state.inputProblem.empty()) {
      state.inputProblem = problem;
      state.inputPath = f.path;
    }
    incomplete(problem);
  }
  if (c.process.empty()) incomplete("the carrier records no processing");
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    if (!r) incomplete("step " + s.id + " (" + s.component + ") never ran");
    else if (r->status != "completed") incomplete("step " + s.id + " (" + s.component + ") failed");
  }
  for (const std::string& rel : captureFiles(capture))
    if (!isOutputPath(rel) && !c.findFileByPath(rel))
      incomplete(rel + " is in the capture but not in its carrier");
  state.complete = state.reason.empty();
  return state;
}

std::vector<PayloadSource> capturePayload(const fs::path& capture) {
  const carrier::Carrier c = carrier::loadCarrier(capture / kCarrierPath);
  std::vector<std::string> unrecorded;
  std::vector<PayloadSource> out;
  for (const std::string& rel : captureFiles(capture)) {
    const carrier::FileRecord* f = c.findFileByPath(rel);
    if (!f && rel != kReportPath && rel != kCarrierPath) {
      unrecorded.push_back(rel);
      continue;
    }
    out.push_back(PayloadSource{"data/" + rel, capture / fs::u8path(rel), f ? f->sha256 : ""});
  }
  if (!unrecorded.empty()) {
    std::string list;
    for (std::size_t i = 0; i < unrecorded.size() && i < 10; ++i) list += (i ? ", " : "") + unrecorded[i];
    if (unrecorded.size() > 10) list += " and " + std::to_string(unrecorded.size() - 10) + " more";
    throw Error(ErrorKind::Input, capture.string(), "packing",
                std::to_string(unrecorded.size()) + " file(s) of the capture are not described by its "
                "carrier, and a package holds only what the carrier describes: " + list +
                ". Files in assembly-files/ and finished-files/ that Surrogate did not write: move "
                "them out of the capture. New inputs: run `surrogate run` first to record them");
  }
  // A recorded file that is missing is refused by the bag writer, naming it.
  for (const carrier::FileRecord& f : c.files)
    if (!std::binary_search(out.begin(), out.end(), PayloadSource{"data/" + f.path, {}, {}},
                            [](const PayloadSource& x, const PayloadSource& y) { return x.bagPath < y.bagPath; }))
      out.push_back(PayloadSource{"data/" + f.path, capture / fs::u8path(f.path), f.sha256});
  std::sort(out.begin(), out.end(), [](const PayloadSource& x, const PayloadSource& y) { return x.bagPath < y.bagPath; });
  return out;
}

PackResult packCapture(const fs::path& capture, const fs::path& out, const PackOptions& options) {
  const fs::path carrierFile = capture / kCarrierPath;
  const std::string carrierXml = readFile(carrierFile, "packing");
  const carrier::Carrier c = carrier::parseCarrier(carrierXml, carrierFile.string());

  PackResult result;
  result.packageId = "urn:sha256:" + sha256Hex(carrierXml);
  const std::int64_t packedAt = packagingEpoch();
  result.packagingTime = utcDateTime(packedAt);
  const std::string agent = std::string("Surrogate ") + surrogateVersion();

  // Metadata that needs only the carrier, derived before any payload byte is written, so a
  // mapping problem never leaves half a package behind.
  const std::string crm = mapping::deriveCrm(carrierXml, carrierFile.string());
  mapping::checkRdfWellFormed(crm, "metadata/crm.rdf");
  std::vector<TagFile> resources;
  for (const std::string& rel : mapping::packagedResources())
    resources.push_back({"metadata/" + rel, readFile(resourcePath(rel), "packing")});

  BagInput in;
  in.payload = capturePayload(capture);
  in.softwareAgent = agent;
  in.baggingDate = utcDate(packedAt);
  bool hasDescription = false;
  for (const auto& [key, value] : c.header.meta) {
    in.info.emplace_back(key, value);
    if (key == "External-Description") hasDescription = true;
  }
  if (!hasDescription)
    in.info.emplace_back("External-Description", "Highlight-RTI capture: " + c.header.title);
  in.info.emplace_back("Surrogate-Package-Identifier", result.packageId);
  in.info.emplace_back("Surrogate-Packaging-Time", result.packagingTime);
  in.progress = options.progress;
  in.tagFiles = [&](const std::vector<PayloadDigest>& payload) {
    mapping::PackageFacts facts;
    facts.packageId = result.packageId;
    facts.packagingTime = result.packagingTime;
    facts.softwareAgent = agent;
    for (const PayloadDigest& d : payload)
      facts.payload.push_back({d.bagPath, d.size, d.sha256, d.sha512});
    const std::string mets = mapping::deriveMets(carrierXml, facts, carrierFile.string());
    try {
      mapping::validateMets(mets, "metadata/mets.xml");
    } catch (const Error& e) {
      throw Error(ErrorKind::Internal, "metadata/mets.xml", "packing",
                  "the METS derived from the carrier is not valid, a bug in Surrogate (" +
                      e.message() + ")");
    }
    std::vector<TagFile> tags = resources;
    tags.push_back({"metadata/crm.rdf", crm});
    tags.push_back({"metadata/mets.xml", mets});
    return tags;
  };
  result.bag = writeBag(in, out);
  return result;
}

}  // namespace surrogate::archive
