// Standard metadata derived from the carrier by stylesheets (libxslt): CIDOC-CRM + CRMdig as
// RDF/XML, METS 1.12.1 with PREMIS 3 in its administrative sections, and RO-Crate 1.1 JSON-LD.
//
// Every piece of package metadata is a function of the carrier (data/assembly-files/carrier.xml)
// and of a few package-level facts the carrier cannot hold (its own digest, the packaging
// time). The stylesheets ship inside the package (metadata/xslt/), so a reader can re-derive
// crm.rdf and mets.xml in 50 years with any XSLT 1.0 processor:
//
//   xsltproc --stringparam package-id ID --stringparam packaging-time T
//            --stringparam payload-uri /abs/payload.xml xslt/carrier-to-mets.xsl carrier.xml
//
// In code (the packer writes them, the verifier re-derives and compares):
//
//   std::string crm  = mapping::deriveCrm(carrierXml);
//   std::string mets = mapping::deriveMets(carrierXml, facts);
//   mapping::validateMets(mets, "metadata/mets.xml");          // METS + PREMIS XSDs, offline
//   mapping::checkRdfWellFormed(crm, "metadata/crm.rdf");
//
// Safety: the carrier and the stylesheets are parsed without network, DTDs or entity
// substitution; the XSLT processor may not read or write files or the network (the one
// document a stylesheet may load is the in-memory payload list, URI "surrogate:payload").
// Schema imports of remote URLs (METS -> xlink) are mapped to the vendored copies in xsd/;
// libxml2 never touches the network.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace surrogate::mapping {

// One file of the bag's payload (under data/), as it is in the manifests.
struct PayloadFile {
  std::string path;  // relative to the bag root, '/' separated, starting with "data/"
  std::uint64_t size = 0;
  std::string sha256, sha512;  // lower-case hex
};

// Facts about the package that the carrier cannot hold. The packer records them in
// bag-info.txt so a verifier can rebuild the same PackageFacts from a bag:
//   packageId      <- bag-info "Surrogate-Package-Identifier"
//   packagingTime  <- bag-info "Surrogate-Packaging-Time"
//   softwareAgent  <- bag-info "Bag-Software-Agent"
//   payload        <- manifest-sha256.txt + manifest-sha512.txt (+ sizes of the files),
//                     sorted by path (byte order)
//   previousPackageId <- bag-info "Surrogate-Previous-Package-Identifier" (absent: none)
//   baseUri        <- bag-info "Surrogate-Base-URI" (absent: the default, urn: identifiers)
// The edition of the mappings' rules (the stylesheets' parameter mapping-edition). 2 (issue
// 56): the RO-Crate root always names a licence, mets.xml gives data/ro-crate-metadata.json and
// other JSON and JavaScript their formats. 1: the packages made before. Packing writes the
// current edition; the verifier accepts a package's metadata derived with either, as both say
// only what the carrier says (docs/package.md, "Editions of the mappings").
inline constexpr int kMappingEdition = 2;

struct PackageFacts {
  std::string packageId;      // "urn:sha256:<carrier sha256>"
  std::string packagingTime;  // xs:dateTime (UTC, "...Z") of the packaging event
  std::string softwareAgent;  // "Surrogate <version>"
  // The package an earlier pack made of this capture, before its record last changed
  // (archive/package.h, previousPackage): this package is a revision of it. Empty: none known.
  std::string previousPackageId;
  // Where crm.rdf mints its node URIs (pack --base-uri); empty: under the capture identifier.
  std::string baseUri;
  std::vector<PayloadFile> payload;
  int mappingEdition = kMappingEdition;
};

// The package facts crm.rdf depends on (PackageFacts less the payload, time and agent).
struct CrmFacts {
  std::string packageId, previousPackageId, baseUri;
};
CrmFacts crmFactsOf(const PackageFacts& facts);

// Carrier XML -> CIDOC-CRM + CRMdig RDF/XML (xslt/carrier-to-crm.xsl). Deterministic: the
// same carrier gives the same bytes. Throws Error(Input) naming `source` if the carrier is
// not well-formed, Error(Internal) if the stylesheet fails.
std::string deriveCrm(const std::string& carrierXml,
                      const std::string& source = "assembly-files/carrier.xml");
// The same for a package: the package (its identifier, the one it revises) is described too,
// and node URIs are minted under facts.baseUri when given.
std::string deriveCrm(const std::string& carrierXml, const CrmFacts& facts,
                      const std::string& source = "assembly-files/carrier.xml");

// What the RO-Crate says besides the carrier: PackageFacts' identifier and time, and whether the payload holds the report (the one payload file the carrier does not list,
// besides the crate's own metadata file).
struct CrateFacts {
  std::string packageId, packagingTime;
  bool hasReport = false;
  int mappingEdition = kMappingEdition;
};

// Carrier XML + facts -> RO-Crate 1.1 metadata, JSON-LD (xslt/carrier-to-ro-crate.xsl: the
// payload folder as the crate; Process, Workflow and Provenance Run Crate 0.5). Deterministic.
// The packer writes it as data/ro-crate-metadata.json; the verifier derives it again.
std::string deriveRoCrate(const std::string& carrierXml, const CrateFacts& facts,
                          const std::string& source = "assembly-files/carrier.xml");

// Carrier XML + package facts -> METS 1.12.1 with PREMIS 3 (xslt/carrier-to-mets.xsl).
// Deterministic for the same inputs.
std::string deriveMets(const std::string& carrierXml, const PackageFacts& facts,
                       const std::string& source = "assembly-files/carrier.xml");

// deriveCrm / deriveMets without the text or the result tree in memory: the same bytes are
// handed to `sink` while the stylesheet runs, and each finished part of the result is freed
// once it is written (a verifier hashes them and compares with the bag's file; a package of
// 100 000 files has a METS of 400-500 MB, whose tree would take about 2 GB). deriveCrmTo
// also checks that the result's root is rdf:RDF (Error(Internal) otherwise: a bug in the
// stylesheet).
//
// Returns false in the one case where the text cannot be written before the stylesheet is
// done with it: an element that receives text after element children already written
// indented (the bundled stylesheets make none). What `sink` was given is then not the
// derivation; derive again with deriveCrm / deriveMets.
using TextSink = std::function<void(const char* data, std::size_t size)>;
[[nodiscard]] bool deriveCrmTo(const std::string& carrierXml, const TextSink& sink,
                               const std::string& source = "assembly-files/carrier.xml");
[[nodiscard]] bool deriveCrmTo(const std::string& carrierXml, const CrmFacts& facts, const TextSink& sink,
                               const std::string& source = "assembly-files/carrier.xml");
[[nodiscard]] bool deriveMetsTo(const std::string& carrierXml, const PackageFacts& facts,
                                const TextSink& sink,
                                const std::string& source = "assembly-files/carrier.xml");
// The same, releasing facts.payload (left empty) as soon as the stylesheet has read it: the
// list is then held once (as the stylesheet's tree), not twice, while the METS is derived
// (100 000 files: about 40 MB less).
[[nodiscard]] bool deriveMetsTo(const std::string& carrierXml, PackageFacts&& facts,
                                const TextSink& sink,
                                const std::string& source = "assembly-files/carrier.xml");
// And the carrier's text as well (left empty once the stylesheet's tree of it is built: 25 MB
// for 100 000 files).
[[nodiscard]] bool deriveMetsTo(std::string&& carrierXml, PackageFacts&& facts,
                                const TextSink& sink,
                                const std::string& source = "assembly-files/carrier.xml");

// validateMets for text that arrives in pieces (e.g. from deriveMetsTo), without building the
// document: memory stays bounded by the document's depth and IDs, not its size.
//
//   MetsValidator v("metadata/mets.xml");
//   deriveMetsTo(carrier, facts, [&](const char* p, std::size_t n) { v.feed(p, n); });
//   v.finish();   // Error(Input) naming the source, as validateMets
class MetsValidator {
 public:
  explicit MetsValidator(const std::string& source);
  ~MetsValidator();
  MetsValidator(const MetsValidator&) = delete;
  MetsValidator& operator=(const MetsValidator&) = delete;
  void feed(const char* data, std::size_t size);
  void finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Validates METS (and the PREMIS inside its mdWrap/xmlData) against the vendored schemas
// (xsd/mets-1.12.1.xsd, xsd/premis-3.0.xsd, xsd/xlink.xsd), offline. Throws Error(Input)
// naming `source` with the first errors and their line numbers.
void validateMets(const std::string& metsXml, const std::string& source);

// Checks that `rdfXml` is well-formed XML whose root is rdf:RDF; throws Error(Input) naming
// `source` otherwise. (Full RDF parsing is left to rapper in the tests.)
void checkRdfWellFormed(const std::string& rdfXml, const std::string& source);

// Where the stylesheets and schemas are (via core resourcePath; Error(Internal) if missing).
std::filesystem::path crmStylesheetPath();   // xslt/carrier-to-crm.xsl
std::filesystem::path metsStylesheetPath();  // xslt/carrier-to-mets.xsl
std::filesystem::path roCrateStylesheetPath();  // xslt/carrier-to-ro-crate.xsl

// Where the RO-Crate's metadata file is in a package's payload.
inline constexpr const char* kRoCratePath = "data/ro-crate-metadata.json";

// The resources (relative to the resource root, e.g. "xslt/carrier-to-crm.xsl",
// "xsd/mets-1.12.1.xsd") that explain a package; the packer copies each to
// metadata/<relative> in the bag. Sorted.
std::vector<std::string> packagedResources();

// The version of the libxslt linked, e.g. "1.1.35".
std::string libxsltVersion();

}  // namespace surrogate::mapping
