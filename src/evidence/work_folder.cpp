// The audit's work folder: made, found again, or refused (evidence.h).
#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "archive/package_reader.h"
#include "capture/capture.h"
#include "capture/output_rule.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/file_names.h"
#include "core/text.h"
#include "evidence/evidence.h"
#include "evidence/prior_files.h"
#include "mapping/mapping.h"

namespace surrogate::evidence {

namespace fs = std::filesystem;

namespace {

constexpr const char* kStep = "audit";
constexpr const char* kBagCarrier = "data/assembly-files/carrier.xml";
// Written into a work folder before its evidence is in place, so that a folder this audit began
// and never ran (stopped before its carrier existed) is known as its own.
constexpr const char* kMarker = ".surrogate/audit-of";

// Absolute, normal, and without a trailing separator: "stela12/" and "./stela12" are one PRIOR.
fs::path absoluteNormal(const fs::path& p) {
  fs::path out = fs::absolute(p).lexically_normal();
  if (out.filename().empty() && out.has_parent_path() && out != out.root_path()) out = out.parent_path();
  return out;
}

bool isInside(const fs::path& inner, const fs::path& outer) {
  const fs::path rel = inner.lexically_relative(outer);
  return !rel.empty() && *rel.begin() != "..";
}

// Where a path really is, every symbolic link on the way followed (the part that does not
// exist yet kept as written): what "inside PRIOR" is judged on, so that neither PRIOR reached
// through a link nor a work folder reached through one can put the work inside PRIOR.
fs::path realPlace(const fs::path& p) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(p, ec);
  return ec ? absoluteNormal(p) : absoluteNormal(real);
}

// PRIOR as the thing it names: a symbolic link (to a folder or a package) followed, so that it
// is audited as what it points to; the audit still never writes into that.
fs::path resolvedPrior(const fs::path& given) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(given, ec);
  if (ec || !fs::exists(link))
    throwInputError(escapedText(given.string()), kStep, "does not exist: give the folder (or package) of the work to audit");
  const fs::path real = fs::canonical(given, ec);
  if (ec == std::errc::too_many_symbolic_link_levels)
    throwInputError(escapedText(given.string()), kStep, "is a loop of symbolic links; give the folder (or package) itself");
  if (ec)
    throwInputError(escapedText(given.string()), kStep,
                    fs::is_symlink(link) ? "is a symbolic link to " + escapedText(fs::read_symlink(given, ec).string()) +
                                               ", which does not exist: give the folder (or package) itself"
                                         : "cannot be read (" + ec.message() + "); check the path and your permissions");
  return real;
}

std::string sourceText(const fs::path& prior) { return escapedText(absoluteNormal(prior).string()); }

// Whether a work folder's record names this PRIOR: its real place (recorded since links are
// followed) or the path it was given as (recorded by earlier audits).
bool sameSource(const std::string& recorded, const fs::path& prior, const fs::path& given) {
  return recorded == sourceText(prior) || recorded == sourceText(given);
}

// Surrogate's own files in a capture processed by Surrogate: never evidence of another tool.
std::set<std::string> surrogateFiles(const carrier::Carrier& c) {
  std::set<std::string> out = {capture::kCarrierPath, capture::kReportPath};
  for (const carrier::FileRecord& f : c.files)
    if (f.role == "assembly" || f.role == "result") out.insert(f.path);
  return out;
}

bool inOutputFolder(const std::string& path) {
  return path.rfind(std::string(capture::kAssemblyDir) + "/", 0) == 0 ||
         path.rfind(std::string(capture::kFinishedDir) + "/", 0) == 0;
}

// A light file or model another tool left: what an audit is for.
bool isPriorWorkToAudit(const std::string& path) {
  if (!inOutputFolder(path)) return false;
  const std::string ext = lowerCase(fs::path(path).extension().string());
  return ext == ".lp" || ext == ".ptm" || ext == ".rti";
}

void requireSomethingToAudit(const std::vector<std::string>& relative, const std::string& prior) {
  if (std::any_of(relative.begin(), relative.end(), isPriorWorkToAudit)) return;
  throwInputError(prior, kStep,
                  "holds no prior work to audit: no .lp, .ptm or .rti in assembly-files/ or finished-files/ "
                  "that Surrogate did not write. An audit compares another tool's light file and model (such "
                  "as RTIBuilder's) with the photographs; to process the photographs themselves, use "
                  "`surrogate run`");
}

void requireHoldableNames(const std::vector<std::string>& relative, const std::string& prior) {
  const NameProblems problems = findNameProblems(relative, std::string("data/").size());
  if (!problems.empty())
    throwInputError(prior, kStep,
                    problems.describe("of the folder audited", "then audit a copy with the names changed"));
}

// ---- a folder -------------------------------------------------------------------------------

std::vector<std::string> folderEvidence(const fs::path& prior) {
  std::vector<std::string> files = listFiles(prior);
  const auto carrierAt = std::find(files.begin(), files.end(), std::string(capture::kCarrierPath));
  if (carrierAt != files.end()) {
    const carrier::Carrier c =
        carrier::parseCarrier(readSmallFile(prior / capture::kCarrierPath), (prior / capture::kCarrierPath).string());
    const std::set<std::string> own = surrogateFiles(c);
    files.erase(std::remove_if(files.begin(), files.end(), [&](const std::string& f) { return own.count(f) > 0; }),
                files.end());
  }
  return files;
}

carrier::AuditedSource hashFolder(const fs::path& prior, const Progress& progress) {
  carrier::AuditedSource a;
  const std::vector<std::string> files = folderEvidence(prior);
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (progress) progress("Reading the folder audited", static_cast<double>(i) / files.size());
    a.files.push_back(hashFile(prior, files[i]));
  }
  return a;
}

carrier::AuditedSource copyFolder(const fs::path& prior, const fs::path& staging, const Progress& progress) {
  const std::vector<std::string> files = folderEvidence(prior);
  requireSomethingToAudit(files, escapedText(prior.string()));
  requireHoldableNames(files, escapedText(prior.string()));
  carrier::AuditedSource a;
  a.kind = "folder";
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (progress) progress("Copying the folder audited", static_cast<double>(i) / files.size());
    a.files.push_back(copyFile(prior, files[i], staging));
  }
  return a;
}

// ---- a package ------------------------------------------------------------------------------

struct PackageEvidence {
  archive::Inventory inventory;
  std::map<std::string, std::string> bagPathOf;  // capture path -> bag path
  carrier::AuditedSource record;
};

PackageEvidence packageEvidence(const fs::path& package, const Progress& progress) {
  PackageEvidence out;
  out.inventory = archive::readPackage(package, archive::Limits{}, progress);
  std::set<std::string> own;
  std::optional<carrier::Carrier> packed;
  const auto carrierFile = out.inventory.files.find(kBagCarrier);
  if (carrierFile != out.inventory.files.end() && carrierFile->second.content) {
    packed = carrier::parseCarrier(*carrierFile->second.content, package.string() + ": " + kBagCarrier);
    own = surrogateFiles(*packed);
  }
  for (const auto& [bagPath, file] : out.inventory.files) {
    if (bagPath.rfind("data/", 0) != 0) continue;
    // The RO-Crate metadata the packer wrote into the payload, derived from the carrier: no
    // more another tool's work than the carrier is (and a capture may not hold one at its top).
    if (packed && bagPath == mapping::kRoCratePath) continue;
    const std::string relative = bagPath.substr(5);
    const std::string name = fs::path(relative).filename().string();
    if (own.count(relative) || capture::isSystemFile(name) || relative.rfind(".surrogate/", 0) == 0 ||
        relative.rfind(std::string(capture::kSupersededDir) + "/", 0) == 0)
      continue;
    if (packed)
      if (const carrier::FileRecord* r = packed->findFileByPath(relative); r && r->sha256 != file.sha256)
        throw Error(ErrorKind::Fixity, package.string(), kStep,
                    bagPath + " is not the file the package's carrier records (its SHA-256 differs): the package "
                              "is damaged or was changed. Run `surrogate verify " + package.string() + "` to see what");
    out.bagPathOf[relative] = bagPath;
    out.record.files.push_back({relative, bagPath, file.size, file.sha256});
  }
  if (out.record.files.empty())
    throw Error(ErrorKind::Input, package.string(), kStep,
                "has no files in its payload (data/) to audit: give a package made by `surrogate pack`, or a bag "
                "whose data/ folder is a capture with another tool's work in it");
  out.record.kind = "package";
  return out;
}

carrier::AuditedSource copyPackage(const fs::path& package, const fs::path& staging, const Progress& progress) {
  PackageEvidence e = packageEvidence(package, progress);
  std::vector<std::string> relative;
  for (const auto& item : e.record.files) relative.push_back(item.path);
  requireSomethingToAudit(relative, package.string());
  archive::extractFiles(
      package, e.inventory, staging,
      [&](const std::string& bagPath) -> fs::path {
        if (bagPath.rfind("data/", 0) != 0 || !e.bagPathOf.count(bagPath.substr(5))) return {};
        return fs::u8path(bagPath.substr(5));
      },
      archive::Limits{}, progress);
  // The package file itself as read, for the record (a bag folder has no one digest). Only
  // when copying: finding an earlier work folder again compares the payload's files alone.
  if (fs::is_regular_file(package)) {
    const carrier::AuditedSource::Item whole = hashFile(package.parent_path(), package.filename().string());
    e.record.packageSize = whole.size;
    e.record.packageSha256 = whole.sha256;
  }
  return e.record;
}

// ---- the work folder ------------------------------------------------------------------------

carrier::AuditedSource evidenceNow(const fs::path& prior, SourceKind kind, const Progress& progress) {
  return kind == SourceKind::Package ? packageEvidence(prior, progress).record : hashFolder(prior, progress);
}

std::string markerOf(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_regular_file(folder / kMarker, ec)) return "";
  std::string text = readFile(folder / kMarker, kStep);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

// Folders an earlier audit of the same PRIOR was filling when it was killed (AtomicFile's
// temporaries of `work` whose process is gone, core/atomic_file.h): removed, since nothing in
// them is anything but copies.
void removeAbandonedCopies(const fs::path& prior, const fs::path& work) {
  std::error_code ec;
  for (const AbandonedTemporary& part : abandonedTemporaries(work))
    if (fs::is_directory(fs::symlink_status(part.path, ec)) && markerOf(part.path) == sourceText(prior))
      fs::remove_all(part.path, ec);
}

// Copies into a folder under a temporary name beside `work`, renamed to `work` once complete.
carrier::AuditedSource makeWorkFolder(const fs::path& prior, SourceKind kind, const fs::path& work,
                                      const Progress& progress) {
  removeAbandonedCopies(prior, work);
  AtomicFile folder(work);
  std::error_code ec;
  fs::create_directories(folder.tempPath() / capture::kWorkDir, ec);
  if (ec) throw writeError(folder.tempPath(), kStep, ec.value());
  writeFileAtomically(folder.tempPath() / kMarker, sourceText(prior) + "\n");
  carrier::AuditedSource a = kind == SourceKind::Package ? copyPackage(prior, folder.tempPath(), progress)
                                                         : copyFolder(prior, folder.tempPath(), progress);
  a.source = sourceText(prior);
  a.copied = carrier::timestampNow();
  std::sort(a.files.begin(), a.files.end(),
            [](const auto& x, const auto& y) { return x.path < y.path; });
  folder.commitWithoutReplacing();
  return a;
}

std::optional<carrier::Carrier> workCarrier(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_regular_file(folder / capture::kCarrierPath, ec)) return std::nullopt;
  return carrier::loadCarrier(folder / capture::kCarrierPath);
}

}  // namespace

SourceKind sourceKind(const fs::path& priorArg) {
  const fs::path prior = resolvedPrior(absoluteNormal(priorArg));
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(prior, ec);
  if (fs::is_regular_file(st)) return SourceKind::Package;
  if (!fs::is_directory(st))
    throwInputError(escapedText(priorArg.string()), kStep,
                    "is neither a folder nor a package file (.zip, .tar): a device, pipe or socket");
  if (fs::is_regular_file(prior / capture::kCarrierPath, ec)) {
    const carrier::Carrier c =
        carrier::parseCarrier(readSmallFile(prior / capture::kCarrierPath), (prior / capture::kCarrierPath).string());
    if (c.header.audited) return SourceKind::WorkFolder;
  }
  if (fs::is_regular_file(prior / "bagit.txt", ec)) return SourceKind::Package;
  // The source folders listed through O_NOATIME (prior_files.h): capture::requireCaptureFolder
  // lists through opendir, which would update their access times, so it is asked only to
  // refuse a folder with no file in original-captures/, raw-images/ or jpeg-exports/, in the
  // words of every command. Whether those files are images the run in the work folder judges.
  for (const char* source : capture::kSourceFolders)
    if (holdsFile(prior / source)) return SourceKind::Folder;
  capture::requireCaptureFolder(prior);
  throwInputError(escapedText(prior.string()), kStep,
                  "is not a capture folder: it has no files in original-captures/, raw-images/ or jpeg-exports/");
}

fs::path defaultWorkFolder(const fs::path& prior) {
  const fs::path p = absoluteNormal(prior);
  const fs::path name = p.filename().empty() ? p.parent_path().filename() : p.filename();
  const fs::path parent = p.filename().empty() ? p.parent_path().parent_path() : p.parent_path();
  std::string stem = name.string();
  if (fs::is_regular_file(p)) {
    stem = name.stem().string();
    if (fs::path(stem).extension() == ".tar") stem = fs::path(stem).stem().string();  // x.tar.gz
  }
  return parent / (stem + "-audit");
}

std::string evidenceDifference(const carrier::AuditedSource& recorded, const carrier::AuditedSource& now) {
  std::map<std::string, const carrier::AuditedSource::Item*> before, after;
  for (const auto& f : recorded.files) before[f.path] = &f;
  for (const auto& f : now.files) after[f.path] = &f;
  std::vector<std::string> differences;
  for (const auto& [path, f] : before) {
    const auto it = after.find(path);
    if (it == after.end()) differences.push_back(shownName(f->from) + " is gone");
    else if (it->second->sha256 != f->sha256 || it->second->size != f->size)
      differences.push_back(shownName(f->from) + " changed (SHA-256 " + f->sha256.substr(0, 12) + "... then, " +
                            it->second->sha256.substr(0, 12) + "... now)");
  }
  for (const auto& [path, f] : after)
    if (!before.count(path)) differences.push_back(shownName(f->from) + " is new");
  if (differences.empty()) return "";
  return differences.front() +
         (differences.size() > 1 ? " (and " + std::to_string(differences.size() - 1) + " more differences)" : "");
}

WorkFolder prepareWorkFolder(const fs::path& priorArg, const std::optional<fs::path>& workArg, const Progress& progress) {
  const fs::path given = absoluteNormal(priorArg);
  const fs::path prior = resolvedPrior(given);  // a link followed: read from where it points
  const SourceKind kind = sourceKind(prior);
  WorkFolder out;
  if (kind == SourceKind::WorkFolder) {
    if (workArg && realPlace(*workArg) != prior)
      throw Error(ErrorKind::Usage, priorArg.string(), kStep,
                  "is the work folder of an earlier audit, audited again in place; give no -o, or audit its "
                  "source (named in its carrier) into another folder");
    out.folder = prior;
    out.reused = true;
    return out;
  }
  // The default is named after PRIOR as given (a link's name) and made beside it.
  out.folder = workArg ? absoluteNormal(*workArg) : defaultWorkFolder(given);
  const fs::path workPlace = realPlace(out.folder);
  if (workPlace == prior || isInside(workPlace, prior) || (kind == SourceKind::Folder && isInside(prior, workPlace)))
    throw Error(ErrorKind::Usage, "-o " + out.folder.string(), kStep,
                "lies inside the folder audited (or holds it); an audit never writes into what it audits: give "
                "a work folder outside it, e.g. -o " + defaultWorkFolder(given).string());
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(out.folder, ec))) {
    capture::checkOutputTarget(out.folder, "-o", capture::ExistingOutput::Refuse, capture::OutputPlace::OutsideCaptures);
    out.copied = makeWorkFolder(prior, kind, out.folder, progress);
    return out;
  }
  const std::optional<carrier::Carrier> c = fs::is_directory(out.folder, ec) ? workCarrier(out.folder) : std::nullopt;
  if (c && c->header.audited && sameSource(c->header.audited->source, prior, given)) {
    const std::string changed = evidenceDifference(*c->header.audited, evidenceNow(prior, kind, progress));
    if (!changed.empty())
      throwInputError(prior.string(), kStep,
                      "has changed since the audit in " + out.folder.string() + " copied it: " + changed +
                          ". That folder keeps the audit of the files as they were; to audit them as they are now, "
                          "give another work folder with -o");
    out.reused = true;
    return out;
  }
  if (!c && fs::is_directory(out.folder, ec) && sameSource(markerOf(out.folder), prior, given)) {
    // Begun by an audit of the same PRIOR and stopped before its first run made a carrier:
    // nothing in it but copies, made again.
    fs::remove_all(out.folder);
    out.copied = makeWorkFolder(prior, kind, out.folder, progress);
    return out;
  }
  throw Error(ErrorKind::Usage, "-o " + out.folder.string(), kStep,
              std::string("exists and is not the work folder of an audit of ") + priorArg.string() +
                  ": give another work folder with -o (the audit makes it)");
}

}  // namespace surrogate::evidence
