#include "archive/package.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/background_sink.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/file_names.h"
#include "core/resources.h"
#include "core/text.h"
#include "core/version.h"
#include "mapping/mapping.h"
#include "archive/package_readme.h"

namespace surrogate::archive {

namespace fs = std::filesystem;

namespace {

using capture::kCarrierPath;

using capture::kReportPath;

std::string relativeSlash(const fs::path& p, const fs::path& root) {
  return p.lexically_relative(root).generic_u8string();
}

bool isOutputPath(const std::string& rel) {
  return rel.rfind("assembly-files/", 0) == 0 || rel.rfind("finished-files/", 0) == 0;
}

// Leftovers of an interrupted atomic write by Surrogate in its own output folders: never
// payload (capture::isInterruptedWrite).
bool isSurrogateLeftover(const std::string& rel) {
  return isOutputPath(rel) && capture::isInterruptedWrite(rel.substr(rel.find_last_of('/') + 1));
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


// capturePayload with the carrier already read.
std::vector<PayloadSource> payloadOf(const fs::path& capture, const carrier::Carrier& c) {
  const auto byPath = c.filesByPath();
  std::vector<std::string> unrecorded;
  std::vector<PayloadSource> out;
  std::unordered_set<std::string> bagged;
  for (const std::string& rel : captureFiles(capture)) {
    const auto it = byPath.find(rel);
    const carrier::FileRecord* f = it == byPath.end() ? nullptr : it->second;
    if (!f && rel != kReportPath && rel != kCarrierPath) {
      unrecorded.push_back(rel);
      continue;
    }
    out.push_back(PayloadSource{"data/" + rel, capture / fs::u8path(rel), f ? f->sha256 : ""});
    bagged.insert(rel);
  }
  if (!unrecorded.empty()) {
    const std::string list = listedWithMore(unrecorded, 10);
    throw Error(ErrorKind::Input, capture.string(), "packing",
                std::to_string(unrecorded.size()) + " file(s) of the capture are not described by its "
                "carrier, and a package holds only what the carrier describes: " + list +
                ". Run `surrogate run` first to record them: new inputs as such, and files in "
                "assembly-files/ and finished-files/ that Surrogate did not write as prior work");
  }
  // A recorded file that is missing is refused by the bag writer, naming it.
  for (const carrier::FileRecord& f : c.files)
    if (bagged.insert(f.path).second)
      out.push_back(PayloadSource{"data/" + f.path, capture / fs::u8path(f.path), f.sha256});
  std::sort(out.begin(), out.end(), [](const PayloadSource& x, const PayloadSource& y) { return x.bagPath < y.bagPath; });
  return out;
}

}  // namespace

CarrierState checkCarrier(const fs::path& capture) {
  const fs::path file = capture / kCarrierPath;
  if (!fs::exists(file)) return {false, "the capture has not been processed (no " + std::string(kCarrierPath) + ")", "", "", {}};
  carrier::Carrier c;
  try {
    c = carrier::loadCarrier(file);
  } catch (const Error& e) {
    return {false, "the carrier cannot be read (" + e.message() + ")", "", "", {}};
  }
  const auto byPath = c.filesByPath();
  const std::vector<std::string> files = captureFiles(capture);
  CarrierState state;
  for (const std::string& rel : files)
    if (isOutputPath(rel) && rel != kReportPath && rel != kCarrierPath && !byPath.count(rel))
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
    // Said as what an earlier run did: `pack` prints it as the reason it processes again.
    if (!r) incomplete("an earlier run did not reach step " + s.id + " (" + s.component + ")");
    else if (r->status != "completed") incomplete("an earlier run stopped at step " + s.id + " (" + s.component + "), which failed");
  }
  for (const std::string& rel : files)
    if (!isOutputPath(rel) && !byPath.count(rel))
      incomplete(rel + " is in the capture but not in its carrier");
  state.complete = state.reason.empty();
  return state;
}

std::vector<PayloadSource> capturePayload(const fs::path& capture) {
  return payloadOf(capture, carrier::loadCarrier(capture / kCarrierPath));
}

PackageInfo packageInfo(const carrier::Carrier& c, const std::string& packageId,
                        const std::string& packagingTime, const std::string& previousPackageId,
                        const std::string& baseUri) {
  PackageInfo info;
  bool hasDescription = false;
  for (const auto& [key, value] : c.header.meta) {
    info.user.emplace_back(key, value);
    if (key == "External-Description") hasDescription = true;
  }
  if (!hasDescription)
    info.user.emplace_back("External-Description", "Highlight-RTI capture: " + c.header.title);
  info.own.emplace_back("Surrogate-Package-Identifier", packageId);
  info.own.emplace_back("Surrogate-Capture-Identifier", captureIdentifier(c));
  if (!previousPackageId.empty()) info.own.emplace_back("Surrogate-Previous-Package-Identifier", previousPackageId);
  if (!baseUri.empty()) info.own.emplace_back("Surrogate-Base-URI", baseUri);
  info.own.emplace_back("Surrogate-Packaging-Time", packagingTime);
  return info;
}

bool isSurrogateLabel(const std::string& label, const PackageInfo& info) {
  static const std::set<std::string> computed = {"bag-software-agent", "bagging-date", "bag-size",
                                                  "payload-oxum"};
  const std::string lower = lowerCase(label);
  if (computed.count(lower) || lower.rfind("surrogate-", 0) == 0) return true;
  for (const auto* labels : {&info.user, &info.own})
    for (const auto& [l, v] : *labels)
      if (lowerCase(l) == lower) return true;
  return false;
}

// The holder's fields are not recorded in the carrier: the carrier is the capture's
// provenance, and the package identifier is its SHA-256, so a field that names this one
// deposit (a repository's identifier, whom to contact) would change the capture's record and
// its identity, and would make pack process the capture again. Metadata that belongs to the
// capture itself goes into the carrier with --meta, where verify re-derives it; these fields
// are what RFC 8493 lets a bag's holder add, and verify lists them as such.
std::string holderFieldProblem(const std::string& label, const std::string& value,
                               const carrier::Carrier* c) {
  if (isSurrogateLabel(label, PackageInfo{}))
    return "is written by Surrogate itself (Payload-Oxum, Bagging-Date, Bag-Size, "
           "Bag-Software-Agent and every Surrogate-* label), which verify checks; choose "
           "another label";
  if (const std::string why = bagInfoLabelProblem(label); !why.empty()) return why;
  if (c && isSurrogateLabel(label, packageInfo(*c, "", "")))
    return "is already written by Surrogate from the carrier (its metadata, given with --meta, "
           "or External-Description), which verify checks against the carrier; change it with "
           "`surrogate run CAPTURE --meta " + label + "=VALUE`, or choose another label";
  if (value.find_first_of("\r\n") != std::string::npos)
    return "has a value with a line break; a holder's bag-info.txt value is one line (write "
           "it on one line)";
  if (std::any_of(value.begin(), value.end(),
                  [](unsigned char ch) { return (ch < ' ' && ch != '\t') || ch == 0x7f; }))
    return "has a value with a control character; give plain text";
  if (!isValidUtf8(value)) return "has a value that is not UTF-8 text";
  return "";
}

std::string packageIdentifier(const std::string& carrierSha256) { return "urn:sha256:" + carrierSha256; }

std::string captureIdentifier(const carrier::Carrier& c) {
  return c.files.empty() ? "urn:surrogate:capture:unidentified" : "urn:surrogate:capture:" + c.files.front().sha256;
}

bool isPackageIdentifier(const std::string& id) {
  static const std::regex form("urn:sha256:[0-9a-f]{64}");
  return std::regex_match(id, form);
}

std::string baseUriProblem(const std::string& uri) {
  static const std::regex scheme("[A-Za-z][A-Za-z0-9+.-]*:.+");
  if (!std::regex_match(uri, scheme))
    return "is not an absolute URI (a scheme such as https: first); give e.g. "
           "https://repository.example/capture/stela12/";
  if (std::any_of(uri.begin(), uri.end(), [](unsigned char ch) {
        return ch <= ' ' || ch == 0x7f || std::strchr("<>\"{}|\\^`", ch) != nullptr;
      }))
    return "holds white space or a character URIs do not allow (< > \" { } | \\ ^ `); "
           "percent-encode it";
  if (uri.back() != '/' && uri.back() != '#')
    return "must end in \"/\" or \"#\", so that the names crm.rdf adds to it (object, capture, "
           "file/f1, ...) stay apart; give " + uri + "/";
  return "";
}

namespace {
fs::path packagesRecord(const fs::path& capture) { return capture / capture::kWorkDir / "packages"; }
}  // namespace

std::vector<std::string> packagesMade(const fs::path& capture) {
  std::vector<std::string> out;
  std::ifstream in(packagesRecord(capture), std::ios::binary);
  std::string line;
  while (std::getline(in, line)) {
    const std::string id = line.substr(0, line.find(' '));
    if (isPackageIdentifier(id)) out.push_back(id);  // anything else is not a record of ours
  }
  return out;
}

std::string previousPackage(const fs::path& capture, const std::string& packageId) {
  const std::vector<std::string> made = packagesMade(capture);
  for (auto it = made.rbegin(); it != made.rend(); ++it)
    if (*it != packageId) return *it;
  return "";
}

namespace {
// Adds the package to the capture's record of packages (written whole under a temporary name,
// then renamed: a pack killed meanwhile leaves the record as it was).
void recordPackage(const fs::path& capture, const PackResult& r) {
  std::string text;
  {
    std::ifstream in(packagesRecord(capture), std::ios::binary);
    std::ostringstream all;
    all << in.rdbuf();
    text = all.str();
  }
  if (!text.empty() && text.back() != '\n') text += '\n';
  text += r.packageId + " " + r.packagingTime + "\n";
  fs::create_directories(packagesRecord(capture).parent_path());
  AtomicFile out(packagesRecord(capture));
  {
    std::ofstream f(out.tempPath(), std::ios::binary);
    f << text;
    if (!f.flush()) throw writeError(packagesRecord(capture), "packing", errno ? errno : EIO);
  }
  out.commit();
}
}  // namespace

std::vector<std::string> packageMetadataFiles() {
  std::vector<std::string> out = {"metadata/crm.rdf", "metadata/mets.xml"};
  for (const std::string& rel : mapping::packagedResources()) out.push_back("metadata/" + rel);
  for (const std::string& rel : bundledDocuments()) out.push_back("metadata/" + rel);
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

// Writes what `derive` hands its sink into `file` (created or truncated) as it comes: the METS
// of 100 000 files is about 450 MB, whose result tree would take about 2 GB (mapping.h).
// Returns what `derive` returns (false: the bytes are not the derivation; see deriveMetsTo). A
// failed write is reported as one of `package`, the name the user gave.
bool deriveInto(const fs::path& file, const fs::path& package,
                const std::function<bool(const mapping::TextSink&)>& derive) {
  auto cannot = [&] { throw writeError(package, "packing", errno ? errno : EIO); };
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "wb"), &std::fclose);
  if (!f) cannot();
  const bool streamed = derive([&](const char* data, std::size_t n) {
    if (std::fwrite(data, 1, n, f.get()) != n) cannot();
  });
  if (std::fclose(f.release()) != 0) cannot();
  return streamed;
}

}  // namespace

PackResult packCapture(const fs::path& capture, const fs::path& out, const PackOptions& options) {
  const fs::path carrierFile = capture / kCarrierPath;
  const std::string carrierXml = readFile(carrierFile, "packing");
  const carrier::Carrier c = carrier::parseCarrier(carrierXml, carrierFile.string());

  PackResult result;
  result.packageId = packageIdentifier(sha256Hex(carrierXml));
  result.captureId = captureIdentifier(c);
  result.previousPackageId = previousPackage(capture, result.packageId);
  if (!options.baseUri.empty())
    if (const std::string why = baseUriProblem(options.baseUri); !why.empty())
      throw Error(ErrorKind::Usage, "--base-uri " + options.baseUri, "packing", why);
  const std::int64_t packedAt = packagingEpoch();
  result.packagingTime = utcDateTime(packedAt);
  const std::string agent = std::string("Surrogate ") + surrogateVersion();
  for (const auto& [label, value] : options.bagInfo)  // before anything is written
    if (const std::string why = holderFieldProblem(label, value, &c); !why.empty())
      throw Error(ErrorKind::Usage, "--bag-info " + label, "packing", "\"" + label + "\" " + why);

  // What the package will hold, judged before anything is written: a name it cannot hold
  // (core/file_names.h, the rule the capture scan applies and verify applies to the package)
  // is refused here, never found by verify. The carrier may be older than the rule.
  std::vector<PayloadSource> payload = payloadOf(capture, c);
  for (const PayloadSource& p : payload)
    if (p.bagPath == mapping::kRoCratePath)
      throw Error(ErrorKind::Input, shownName((capture / "ro-crate-metadata.json").string()), "packing",
                  "the capture has a file of this name at its top, where a package holds the "
                  "RO-Crate metadata Surrogate writes; move it into a folder of the capture, "
                  "run `surrogate run` to record the move, then pack again");
  {
    std::vector<std::string> names;
    names.reserve(payload.size());
    for (const PayloadSource& p : payload) names.push_back(p.bagPath.substr(5));  // less "data/"
    // A .tar or .zip holds the bag in a folder named after it (bag_output.cpp): "STEM/data/...".
    const std::string prefix = bagFormatFor(out) == BagFormat::Directory
                                   ? std::string("data/") : out.stem().string() + "/data/";
    const NameProblems problems = findNameProblems(names, prefix.size());
    if (!problems.empty())
      throw Error(ErrorKind::Input, shownName(capture.string()), "packing",
                  problems.describe("that the carrier records",
                                    "run `surrogate run` to record the capture again, then pack again"));
  }
  // Metadata that needs only the carrier, derived before any payload byte is written, so a
  // mapping problem never leaves half a package behind. The derived documents go into
  // temporary files beside the output (AtomicFile's names, never committed: removed when
  // packing ends, and by removeStaleParts after a pack that was killed), from which writeBag
  // copies them; their bytes are deriveCrm's / deriveMets's (the fallback below).
  checkOutput(out, options.replace);
  const AtomicFile crmFile(out), metsFile(out);
  const mapping::CrmFacts crmFacts{result.packageId, result.previousPackageId, options.baseUri};
  if (!deriveInto(crmFile.tempPath(), out, [&](const mapping::TextSink& sink) {
        return mapping::deriveCrmTo(carrierXml, crmFacts, sink, carrierFile.string());
      })) {
    const std::string crm = mapping::deriveCrm(carrierXml, crmFacts, carrierFile.string());
    mapping::checkRdfWellFormed(crm, "metadata/crm.rdf");
    (void)deriveInto(crmFile.tempPath(), out, [&](const mapping::TextSink& sink) {
      sink(crm.data(), crm.size());
      return true;
    });
  }
  // The RO-Crate's metadata, in the payload (the payload folder is the crate), from the carrier
  // like crm.rdf: written before any payload byte, copied by writeBag like a capture file.
  const AtomicFile crateFile(out);
  {
    mapping::CrateFacts facts;
    facts.packageId = result.packageId;
    facts.packagingTime = result.packagingTime;
    for (const PayloadSource& p : payload) facts.hasReport |= p.bagPath == std::string("data/") + kReportPath;
    const std::string crate = mapping::deriveRoCrate(carrierXml, facts, carrierFile.string());
    (void)deriveInto(crateFile.tempPath(), out, [&](const mapping::TextSink& sink) {
      sink(crate.data(), crate.size());
      return true;
    });
    payload.push_back(PayloadSource{mapping::kRoCratePath, crateFile.tempPath(), ""});
    std::sort(payload.begin(), payload.end(),
              [](const PayloadSource& x, const PayloadSource& y) { return x.bagPath < y.bagPath; });
  }
  std::vector<TagFile> resources;
  for (const std::string& rel : mapping::packagedResources())
    resources.push_back({"metadata/" + rel, readFile(resourcePath(rel), "packing"), {}});
  for (const std::string& rel : bundledDocuments())
    resources.push_back({"metadata/" + rel, readFile(resourcePath(rel), "packing"), {}});
  {
    ReadmeFacts readme;
    readme.packageId = result.packageId;
    readme.packagingTime = result.packagingTime;
    readme.softwareAgent = agent;
    readme.previousPackageId = result.previousPackageId;
    readme.baseUri = options.baseUri;
    for (const PayloadSource& p : payload) readme.hasReport |= p.bagPath == std::string("data/") + kReportPath;
    resources.push_back({kReadmePath, packageReadme(c, readme), {}});
  }

  BagInput in;
  in.payload = std::move(payload);
  in.softwareAgent = agent;
  in.baggingDate = utcDate(packedAt);
  PackageInfo info = packageInfo(c, result.packageId, result.packagingTime, result.previousPackageId, options.baseUri);
  in.info = std::move(info.user);
  in.ownInfo = std::move(info.own);
  in.holderInfo = options.bagInfo;
  in.progress = options.progress;
  in.replace = options.replace;
  in.tagFiles = [&](const std::vector<PayloadDigest>& payload) {
    mapping::PackageFacts facts;
    facts.packageId = result.packageId;
    facts.packagingTime = result.packagingTime;
    facts.softwareAgent = agent;
    facts.previousPackageId = result.previousPackageId;
    facts.baseUri = options.baseUri;
    facts.payload.reserve(payload.size());
    for (const PayloadDigest& d : payload)
      facts.payload.push_back({d.bagPath, d.size, d.sha256, d.sha512});
    std::unique_ptr<mapping::MetsValidator> validator;
    const bool streamed = deriveInto(metsFile.tempPath(), out, [&](const mapping::TextSink& sink) {
      validator = std::make_unique<mapping::MetsValidator>("metadata/mets.xml");
      // The file and the schema validator take the text on the other core while the
      // stylesheet makes it.
      BackgroundSink reader([&](const char* data, std::size_t n) {
        sink(data, n);
        validator->feed(data, n);
      });
      const bool whole = mapping::deriveMetsTo(carrierXml, facts, [&](const char* data, std::size_t n) {
        reader.write(data, n);
      }, carrierFile.string());
      reader.finish();
      return whole;
    });
    if (!streamed) {
      const std::string mets = mapping::deriveMets(carrierXml, facts, carrierFile.string());
      (void)deriveInto(metsFile.tempPath(), out, [&](const mapping::TextSink& sink) {
        validator = std::make_unique<mapping::MetsValidator>("metadata/mets.xml");
        sink(mets.data(), mets.size());
        validator->feed(mets.data(), mets.size());
        return true;
      });
    }
    try {
      validator->finish();
    } catch (const Error& e) {
      throw Error(ErrorKind::Internal, "metadata/mets.xml", "packing",
                  "the METS derived from the carrier is not valid, a bug in Surrogate (" +
                      e.message() + ")");
    }
    std::vector<TagFile> tags = resources;
    tags.push_back({"metadata/crm.rdf", {}, crmFile.tempPath()});
    tags.push_back({"metadata/mets.xml", {}, metsFile.tempPath()});
    return tags;
  };
  result.bag = writeBag(in, out);
  recordPackage(capture, result);
  return result;
}

}  // namespace surrogate::archive
