#include "archive/package_summary.h"

#include "archive/bag_text.h"
#include "carrier/carrier.h"
#include "core/error.h"
#include "core/text.h"

namespace surrogate::archive {

namespace {

constexpr const char* kCarrierPath = "data/assembly-files/carrier.xml";
constexpr const char* kRoCratePath = "data/ro-crate-metadata.json";

}  // namespace

std::string packageRole(const std::string& path, const std::map<std::string, std::string>& carrierRoles,
                        bool surrogate) {
  if (!surrogate) return path.compare(0, 5, "data/") == 0 ? "payload" : "bag files";
  if (path == kCarrierPath) return "carrier";
  if (path == kRoCratePath) return "RO-Crate metadata";  // written by pack, never in the carrier
  if (path.compare(0, 5, "data/") == 0) {
    const auto it = carrierRoles.find(path.substr(5));
    if (it != carrierRoles.end()) {
      const std::string& r = it->second;
      if (r == "original" || r == "sidecar") return "originals";
      if (r == "export") return "exports";
      if (r == "result") return "results";
      if (r == "assembly" || r == "lp") return "assembly";
      if (r == "prior") return "prior work";  // made by another tool, found in the output folders
      return "other payload";
    }
    const std::string rest = path.substr(5);
    if (rest.compare(0, 18, "original-captures/") == 0) return "originals";
    if (rest.compare(0, 13, "jpeg-exports/") == 0) return "exports";
    if (rest.compare(0, 15, "finished-files/") == 0) return "results";
    if (rest.compare(0, 15, "assembly-files/") == 0) return "assembly";
    return "other payload";
  }
  if (path.compare(0, 9, "metadata/") == 0) return "metadata";
  return "bag files";
}

std::string PackageSummary::bagInfoValue(const std::string& label) const {
  for (const auto& [k, v] : bagInfo)
    if (lowerCase(k) == lowerCase(label)) return v;
  return "";
}

PackageSummary describePackage(const std::filesystem::path& package, const Limits& limits) {
  const Inventory inv = readPackage(package, limits);
  PackageSummary s;
  s.format = inv.kind;
  const auto carrierFile = inv.files.find(kCarrierPath);
  std::map<std::string, std::string> carrierRoles;
  if (carrierFile != inv.files.end()) {
    if (!carrierFile->second.content) {
      s.carrierProblem = "too large to read";
    } else {
      try {
        s.carrier = carrier::parseCarrier(*carrierFile->second.content, kCarrierPath);
        for (const carrier::FileRecord& f : s.carrier->files) carrierRoles[f.path] = f.role;
      } catch (const Error& e) {
        s.carrierProblem = e.text();
      }
    }
  }
  const auto info = inv.files.find("bag-info.txt");
  if (info != inv.files.end() && info->second.content) {
    // bag-info.txt in the encoding bagit.txt names (older bags: UTF-16, ISO-8859-1).
    std::string encoding = "UTF-8";
    if (const auto decl = inv.files.find("bagit.txt"); decl != inv.files.end() && decl->second.content) {
      const Declaration d = parseDeclaration(*decl->second.content);
      if (!d.encoding.empty()) encoding = d.encoding;
    }
    std::string why;
    if (const auto text = decodeTagText(*info->second.content, encoding, &why)) s.bagInfo = parseBagInfo(*text).fields;
  }
  for (const auto& [label, value] : s.bagInfo)
    if (lowerCase(label) == "surrogate-package-identifier") s.surrogate = true;
  s.surrogate = s.surrogate || carrierFile != inv.files.end();

  static const char* kRoleOrder[] = {"originals", "exports", "assembly", "carrier", "results",
                                     "prior work", "other payload", "RO-Crate metadata", "payload", "metadata",
                                     "bag files"};
  std::map<std::string, RoleTotal> totals;
  for (const auto& [file, f] : inv.files) {
    if (manifestName(file) && manifestName(file)->first == "manifest") s.manifests.push_back(file);
    const std::string role = packageRole(file, carrierRoles, s.surrogate);
    totals[role].files += 1;
    totals[role].bytes += f.size;
    s.files += 1;
    s.bytes += f.size;
    if (role == "results") s.results.emplace_back(file.substr(5), f.size);
  }
  for (const char* role : kRoleOrder)
    if (totals.count(role)) {
      RoleTotal t = totals[role];
      t.role = role;
      s.roles.push_back(t);
    }
  return s;
}

}  // namespace surrogate::archive
