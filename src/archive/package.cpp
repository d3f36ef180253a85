#include "archive/package.h"

#include <algorithm>
#include <map>
#include <set>

#include "archive/digest.h"
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

// Folders of a capture that are payload, whole (DESIGN.md, "The capture folder").
const char* const kPayloadFolders[] = {"original-captures", "raw-images", "jpeg-exports",
                                       "assembly-files", "finished-files"};

// Leftovers of an interrupted atomic write (".name.part-PID-N"): never payload.
bool isTemporary(const fs::path& p) {
  const std::string name = p.filename().string();
  return !name.empty() && name[0] == '.' && name.find(".part-") != std::string::npos;
}

std::string relativeSlash(const fs::path& p, const fs::path& root) {
  return p.lexically_relative(root).generic_u8string();
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
  if (c.process.empty()) return {false, "the carrier records no processing"};
  for (const carrier::Step& s : c.process) {
    const carrier::Result* r = c.findResult(s.id);
    if (!r) return {false, "step " + s.id + " (" + s.component + ") never ran"};
    if (r->status != "completed") return {false, "step " + s.id + " (" + s.component + ") failed"};
  }
  for (const carrier::FileRecord& f : c.files) {
    std::error_code ec;
    const fs::path p = capture / fs::u8path(f.path);
    if (!fs::is_regular_file(p, ec)) return {false, f.path + " is missing"};
    if (fs::file_size(p, ec) != f.size) return {false, f.path + " changed size since it was recorded"};
  }
  return {true, ""};
}

std::vector<PayloadSource> capturePayload(const fs::path& capture) {
  std::map<std::string, PayloadSource> byPath;  // relative path -> source
  auto add = [&](const fs::path& p) {
    const std::string rel = relativeSlash(p, capture);
    byPath[rel] = PayloadSource{"data/" + rel, p, ""};
  };
  for (const char* folder : kPayloadFolders) {
    const fs::path dir = capture / folder;
    if (!fs::is_directory(dir)) continue;
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
      if (it->is_directory(/*follows links*/) && !it->is_symlink()) continue;
      if (isTemporary(it->path())) continue;
      add(it->path());  // links and special files are refused by writeBag, naming them
    }
  }
  for (const auto& entry : fs::directory_iterator(capture)) {
    if (entry.path().extension() == ".lp" && !entry.is_directory()) add(entry.path());
  }
  const fs::path carrierFile = capture / kCarrierPath;
  if (fs::exists(carrierFile)) {
    const carrier::Carrier c = carrier::loadCarrier(carrierFile);
    for (const carrier::FileRecord& f : c.files) {
      const fs::path p = capture / fs::u8path(f.path);
      if (!byPath.count(f.path)) byPath[f.path] = PayloadSource{"data/" + f.path, p, ""};
      byPath[f.path].expectedSha256 = f.sha256;
    }
  }
  std::vector<PayloadSource> out;
  for (auto& [rel, source] : byPath) out.push_back(std::move(source));
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
