#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <unordered_set>

#include "archive/bag_text.h"
#include "capture/capture.h"
#include "carrier/xml.h"
#include "core/background_sink.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/file_names.h"
#include "verify/checks.h"
#include "mapping/mapping.h"

namespace fs = std::filesystem;

namespace surrogate::verify {

// checks.h
std::string firstDifference(const std::string& expected, const std::string& found) {
  const std::vector<std::string> a = splitLines(expected), b = splitLines(found);
  for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    const std::string x = i < a.size() ? a[i] : "(end of file)";
    const std::string y = i < b.size() ? b[i] : "(end of file)";
    if (x != y)
      return "line " + std::to_string(i + 1) + ": derived \"" + x.substr(0, 160) +
             "\", the bag has \"" + y.substr(0, 160) + "\"";
  }
  return "the texts differ in line endings";
}


namespace {

// carrier.evidence, for an audit's package: every file the audit copied from the work it
// audited is recorded, as an input (never a result), with the size and SHA-256 read from the
// source. A copy that differs from what was read, or evidence bagged as a result, is refused.
Check evidenceCheck(const carrier::Carrier& c) {
  std::vector<std::string> problems;
  for (const carrier::AuditedSource::Item& e : c.header.audited->files) {
    const carrier::FileRecord* f = c.findFileByPath(e.path);
    if (!f) problems.push_back(e.path + ": copied from the work audited, but the carrier records no such file");
    else if (f->role == "assembly" || f->role == "result")
      problems.push_back(e.path + ": copied from the work audited, but recorded as Surrogate's " + f->role);
    else if (f->size != e.size || f->sha256 != e.sha256)
      problems.push_back(e.path + ": read from " + e.from + " as " + std::to_string(e.size) + " bytes, SHA-256 " +
                         e.sha256.substr(0, 16) + "...; the carrier records " + std::to_string(f->size) + " bytes, " +
                         f->sha256.substr(0, 16) + "...");
  }
  return makeCheck("carrier.evidence", Severity::Fixity,
                   std::to_string(c.header.audited->files.size()) +
                       " files copied from the work audited are recorded with the bytes read from it",
                   "the audit's copies differ from what it read", problems);
}

}  // namespace

std::optional<carrier::Carrier> checkCarrier(const Inventory& inv, std::vector<Check>& checks) {
  std::optional<carrier::Carrier> parsed;
  std::vector<std::string> problems;
  const std::string* text = contentOf(inv, kCarrierPath);
  if (!text) {
    problems.push_back(std::string(kCarrierPath) + ": missing; a Surrogate package holds its "
                       "provenance carrier there");
  } else {
    try {
      parsed = carrier::parseCarrier(*text, kCarrierPath);
    } catch (const Error& e) {
      problems.push_back(e.text());
    }
  }
  checks.push_back(makeCheck("carrier.schema", Severity::Invalid,
                             "the carrier validates against xsd/carrier.xsd",
                             "the carrier is missing or not valid", problems));
  if (!parsed) return parsed;

  std::vector<std::string> pathProblems, fixity;
  // The carrier's paths, for the payload's files below (Carrier::findFileByPath searches the
  // list: once per payload file, that was quadratic in the number of files).
  std::unordered_set<std::string> recordedPaths;
  recordedPaths.reserve(parsed->files.size());
  for (const carrier::FileRecord& f : parsed->files) {
    recordedPaths.insert(f.path);
    // Judged as the path lies in the bag: a capture's "~notes.txt" is data/~notes.txt, which
    // no shell or unpacker takes for a home folder (the capture scan accepts it).
    std::string why;
    const auto safe = safeBagPath("data/" + f.path, &why);
    if (!safe) {
      pathProblems.push_back("file " + f.id + " \"" + shownName(f.path.substr(0, 200)) + "\": " + why);
      continue;
    }
    const std::string& inBag = *safe;
    const auto it = inv.files.find(inBag);
    if (it == inv.files.end()) {
      fixity.push_back(inBag + ": listed in the carrier (" + f.id + ", " + f.role +
                       ") but not in the bag");
    } else if (it->second.size != f.size || it->second.sha256 != f.sha256) {
      fixity.push_back(inBag + ": the carrier records " + std::to_string(f.size) + " bytes, SHA-256 " +
                       f.sha256.substr(0, 16) + "...; the bag holds " +
                       std::to_string(it->second.size) + " bytes, " +
                       it->second.sha256.substr(0, 16) + "...");
    }
  }
  // Every file in the payload is one the carrier records: an image added with the manifests
  // redone is found, and so is a result left by a run the carrier does not describe (a stale
  // .rti bagged beside the fresh ones). The exceptions are the HTML report, a view of the
  // carrier that holds the time it was made (docs/carrier.md), the carrier itself, and the
  // RO-Crate's metadata, derived from the carrier and checked by metadata.ro-crate.
  for (const auto& [path, file] : inv.files) {
    if (!pathProblems.empty()) break;  // one cause, one failure: the unsafe path
    if (path.compare(0, 5, "data/") != 0) continue;
    const std::string relative = path.substr(5);
    if (relative == capture::kReportPath || path == kCarrierPath || path == mapping::kRoCratePath) continue;
    if (!recordedPaths.count(relative))
      fixity.push_back(path + ": in the payload but not recorded in the carrier" +
                       (relative.compare(0, 15, "assembly-files/") == 0 ||
                                relative.compare(0, 15, "finished-files/") == 0
                            ? std::string(" (a result no recorded step made)")
                            : std::string(" (an input the record does not hold)")));
  }
  checks.push_back(makeCheck("carrier.paths", Severity::Invalid,
                             "every file the carrier lists has a safe relative path",
                             "the carrier names unsafe paths", pathProblems));
  checks.push_back(makeCheck("carrier.files", Severity::Fixity,
                             std::to_string(parsed->files.size()) +
                                 " files listed in the carrier are in the bag, same size and SHA-256; nothing else in the payload but the report",
                             "files differ from what the carrier records", fixity));
  if (parsed->header.audited) checks.push_back(evidenceCheck(*parsed));
  if (!pathProblems.empty()) parsed.reset();  // never re-execute a carrier with unsafe paths
  return parsed;
}

void checkMetadata(const fs::path& package, Inventory& inv, const std::string* carrierXml,
                   const Limits& limits, std::vector<Check>& checks, bool dropPayloadEntries) {
  const std::string metsPath = "metadata/mets.xml", crmPath = "metadata/crm.rdf";
  const auto mets = inv.files.find(metsPath), crm = inv.files.find(crmPath);
  const bool hasMets = mets != inv.files.end(), hasCrm = crm != inv.files.end();
  // The bag's own text, read again only when a check needs it (the inventory holds the digests).
  auto text = [&](const std::string& path) { return readBagFile(package, inv, path, limits); };
  auto run = [](const std::function<void()>& f) -> std::vector<std::string> {
    try {
      f();
    } catch (const Error& e) {
      // A missing schema (internal) or a package changing under us (fixity) is not a finding
      // about these files.
      if (e.kind() == ErrorKind::Internal || e.kind() == ErrorKind::Fixity) throw;
      return {e.text()};
    }
    return {};
  };
  std::vector<std::string> metsProblems, crmProblems, problems;
  if (!hasMets) metsProblems.push_back(metsPath + ": missing");
  if (!hasCrm) crmProblems.push_back(crmPath + ": missing");
  bool metsChecked = !hasMets, crmChecked = !hasCrm;

  if (carrierXml && hasMets && hasCrm) {
    // Package facts, as the packer recorded them (mapping.h). Made again only for a second
    // derivation (a result that differs, or cannot be streamed): when nothing after this
    // check needs the inventory's payload entries and manifest texts, they are let go once
    // the facts are made, and the first facts' payload list is given to the stylesheet
    // (mapping::deriveMetsTo with PackageFacts&&), so that the stylesheets' trees do not
    // stand beside them (100 000 files: the entries about 100 MB, the manifests 30 MB, the
    // list 40 MB). The sizes are then kept apart, in the list's order.
    std::vector<std::uint64_t> sizes;
    std::set<std::string> released;  // manifests whose text is read again from the package
    auto makeFacts = [&] {
      mapping::PackageFacts facts;
      if (const std::string* info = contentOf(inv, "bag-info.txt")) {
        const BagInfo bagInfo = parseBagInfo(*info);
        auto one = [&](const char* label) {
          const auto v = bagInfo.values(label);
          return v.empty() ? std::string() : v.front();
        };
        facts.packageId = one("Surrogate-Package-Identifier");
        facts.packagingTime = one("Surrogate-Packaging-Time");
        facts.softwareAgent = one("Bag-Software-Agent");
        facts.previousPackageId = one("Surrogate-Previous-Package-Identifier");
        facts.baseUri = one("Surrogate-Base-URI");
      }
      std::map<std::string, mapping::PayloadFile> payload;
      for (const char* algorithm : {"sha256", "sha512"}) {
        const std::string name = std::string("manifest-") + algorithm + ".txt";
        std::string again;
        const std::string* manifest = contentOf(inv, name);
        if (released.count(name)) manifest = &(again = text(name));
        if (!manifest) continue;
        for (ManifestEntry& e : parseManifest(*manifest, algorithm, digestHexLength(algorithm)).entries) {
          mapping::PayloadFile& p = payload[e.path];
          if (p.path.empty()) {
            p.path = e.path;
            const auto it = inv.files.find(e.path);
            if (it != inv.files.end()) p.size = it->second.size;
          }
          (std::string(algorithm) == "sha256" ? p.sha256 : p.sha512) = std::move(e.checksum);
        }
      }
      facts.payload.reserve(payload.size());
      for (auto& [path, p] : payload) facts.payload.push_back(std::move(p));
      if (sizes.size() == facts.payload.size())
        for (std::size_t i = 0; i < sizes.size(); ++i) facts.payload[i].size = sizes[i];
      return facts;
    };
    mapping::PackageFacts facts = makeFacts();
    // What crm.rdf depends on, kept apart: facts may be handed to the METS stylesheet first.
    const mapping::CrmFacts crmFacts = mapping::crmFactsOf(facts);
    // The carrier's text, given to the METS stylesheet with the facts in the same case (its
    // tree is what the stylesheet reads), and read again from the package if needed after.
    std::string* ownCarrier = nullptr;
    std::string carrierAgain;
    auto carrier = [&]() -> const std::string& {
      if (!ownCarrier || !ownCarrier->empty()) return *carrierXml;
      if (carrierAgain.empty()) carrierAgain = text(kCarrierPath);
      return carrierAgain;
    };
    if (dropPayloadEntries) {
      for (const mapping::PayloadFile& p : facts.payload) sizes.push_back(p.size);
      // What is left to do reads the tag files (readBagFile looks up only the path it reads)
      // and the carrier's text (carrierXml points into its entry, which stays).
      for (auto it = inv.files.lower_bound("data/"); it != inv.files.end() && it->first.rfind("data/", 0) == 0;)
        it = it->first == kCarrierPath ? std::next(it) : inv.files.erase(it);
      const auto entry = inv.files.find(kCarrierPath);
      if (entry != inv.files.end() && entry->second.content && &*entry->second.content == carrierXml &&
          !carrierXml->empty())
        ownCarrier = &*entry->second.content;
      for (const char* name : {"manifest-sha256.txt", "manifest-sha512.txt"}) {
        const auto it = inv.files.find(name);
        if (it == inv.files.end() || !it->second.content) continue;
        it->second.content.reset();
        released.insert(name);
      }
    }

    // Each derived document is hashed as it is serialised, and compared with the bag's by
    // digest: neither the texts nor the result trees (hundreds of MB, GB, for a package of many
    // files) are ever held whole. Only when they differ is the bag's text read again, to say
    // where.
    auto derive = [&](bool isMets, std::unique_ptr<mapping::MetsValidator>* validator) {
      std::optional<MultiDigest> digest;
      std::uint64_t size = 0;
      auto restart = [&] {
        digest.emplace(std::vector<DigestAlgorithm>{DigestAlgorithm::Sha256});
        size = 0;
        if (validator) *validator = std::make_unique<mapping::MetsValidator>(metsPath);
      };
      restart();
      const mapping::TextSink sink = [&](const char* data, std::size_t n) {
        digest->update(data, n);
        size += n;
        if (validator) (*validator)->feed(data, n);
      };
      bool streamed;
      {
        // The digest and the schema validator read the text on the other core while the
        // stylesheet makes it (100 000 files: the validator alone was 3 to 6 s of 28).
        BackgroundSink reader(sink);
        const mapping::TextSink handOver = [&](const char* data, std::size_t n) { reader.write(data, n); };
        if (!isMets) streamed = mapping::deriveCrmTo(carrier(), crmFacts, handOver, kCarrierPath);
        else if (ownCarrier) streamed = mapping::deriveMetsTo(std::move(*ownCarrier), std::move(facts), handOver, kCarrierPath);
        else if (dropPayloadEntries) streamed = mapping::deriveMetsTo(carrier(), std::move(facts), handOver, kCarrierPath);
        else streamed = mapping::deriveMetsTo(carrier(), facts, handOver, kCarrierPath);
        reader.finish();
      }
      if (!streamed) {
        // A result that could not be written while it was built (mapping.h): derived whole.
        restart();
        const std::string whole = isMets ? mapping::deriveMets(carrier(), makeFacts(), kCarrierPath)
                                         : mapping::deriveCrm(carrier(), crmFacts, kCarrierPath);
        if (!isMets) mapping::checkRdfWellFormed(whole, crmPath);
        sink(whole.data(), whole.size());
      }
      const InventoryFile& bag = (isMets ? mets : crm)->second;
      return bag.size == size && bag.sha256 == digest->hex(DigestAlgorithm::Sha256);
    };
    try {
      std::unique_ptr<mapping::MetsValidator> validator;
      if (derive(false, nullptr)) {
        crmChecked = true;  // the bag's crm.rdf is the derived one: RDF/XML (deriveCrmTo checks)
      } else {
        const std::string derived = mapping::deriveCrm(carrier(), crmFacts, kCarrierPath);
        const std::string bag = text(crmPath);
        problems.push_back(crmPath + ": " + firstDifference(derived, bag));
      }
      if (derive(true, &validator)) {
        // The bag's mets.xml is the derived one, whose text the validator has just read.
        metsProblems = run([&] { validator->finish(); });
        metsChecked = true;
      } else {
        const std::string bag = text(metsPath);
        // A package packed before the mappings' current edition (mapping.h, kMappingEdition)
        // holds the derivation of that edition's rules: the same carrier, said as then.
        mapping::PackageFacts earlier = makeFacts();
        earlier.mappingEdition = 1;
        if (mapping::deriveMets(carrier(), earlier, kCarrierPath) != bag) {
          const std::string derived = mapping::deriveMets(carrier(), makeFacts(), kCarrierPath);
          problems.push_back(metsPath + ": " + firstDifference(derived, bag));
        }
      }
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Internal || e.kind() == ErrorKind::Fixity) throw;
      problems.push_back(e.text());
    }
  }
  // Without a carrier to derive from, or when the bag's text differs: the bag's own files.
  if (!metsChecked) metsProblems = run([&] { mapping::validateMets(text(metsPath), metsPath); });
  if (!crmChecked) crmProblems = run([&] { mapping::checkRdfWellFormed(text(crmPath), crmPath); });
  checks.push_back(makeCheck("metadata.mets", Severity::Invalid,
                             "metadata/mets.xml validates against the METS and PREMIS schemas",
                             "metadata/mets.xml is missing or not valid", metsProblems));
  checks.push_back(makeCheck("metadata.crm", Severity::Invalid,
                             "metadata/crm.rdf is well-formed RDF/XML",
                             "metadata/crm.rdf is missing or not well-formed", crmProblems));
  if (!carrierXml || !hasMets || !hasCrm) return;
  checks.push_back(makeCheck("metadata.derived", Severity::Invalid,
                             "crm.rdf and mets.xml equal what the bundled stylesheets derive "
                             "from the carrier",
                             "the metadata differ from what the carrier gives", problems));
}

}  // namespace surrogate::verify
