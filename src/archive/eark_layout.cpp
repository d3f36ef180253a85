// The package as an E-ARK SIP: the bag packed into a hidden folder beside DIR, its files moved
// to their CSIP places, the representation's METS and then the package's METS written with
// libxml2's text writer (files in path order, so the same package gives the same bytes), and
// the folder renamed to DIR.
#include "archive/eark_layout.h"

#include <libxml/xmlwriter.h>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "core/atomic_file.h"
#include "core/digest.h"
#include "core/error.h"
#include "core/version.h"

namespace fs = std::filesystem;

namespace surrogate::archive {

namespace {

constexpr const char* kStep = "packing (E-ARK SIP)";
constexpr const char* kProfile = "https://earksip.dilcis.eu/profile/E-ARK-SIP-v2-2-0.xml";
// CSIP's content category vocabulary (CSIPVocabularyContentCategory): the originals are
// digital photographs, everything else is derived from them.
constexpr const char* kContentCategory = "Photographs \u2013 Digital";
// No content information type specification covers RTI captures: CSIP's "OTHER", named.
constexpr const char* kOtherContentInformationType = "Surrogate Highlight-RTI capture";

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

// Bag prefix -> SIP prefix, the first that matches; a tag file no pair names is kept under
// metadata/other/bagit/ (bagit.txt, bag-info.txt, the manifests, ...).
const std::vector<std::pair<std::string, std::string>>& places() {
  static const std::vector<std::pair<std::string, std::string>> p = {
      {"data/", "representations/rep1/data/"},
      {"metadata/mets.xml", "metadata/preservation/mets.xml"},
      {"metadata/crm.rdf", "metadata/descriptive/crm.rdf"},
      {"metadata/xsd/", "schemas/"},
      {"metadata/", "documentation/"},
  };
  return p;
}
constexpr const char* kOtherTags = "metadata/other/bagit/";

struct SipFile {
  std::string path;  // in the SIP
  std::uint64_t size = 0;
  std::string sha256, mime;
};

std::string lowerExtension(const std::string& path) {
  const auto slash = path.rfind('/');
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return e;
}

// The IANA media type of a file by its extension (CSIP68 asks for one on every file); the
// carrier's own record wins for payload files (mediaType).
std::string mediaTypeOf(const std::string& path) {
  static const std::map<std::string, std::string> byExtension = {
      {"xml", "application/xml"}, {"xsd", "application/xml"},  {"xsl", "application/xslt+xml"},
      {"rdf", "application/rdf+xml"}, {"md", "text/markdown"}, {"txt", "text/plain"},
      {"png", "image/png"}, {"jpg", "image/jpeg"}, {"jpeg", "image/jpeg"}, {"tif", "image/tiff"},
      {"tiff", "image/tiff"}, {"dng", "image/x-adobe-dng"}, {"html", "text/html"}, {"htm", "text/html"},
      {"json", "application/json"}, {"js", "text/javascript"}, {"xmp", "application/rdf+xml"},
      {"dzi", "application/xml"}, {"lp", "text/plain"}, {"log", "text/plain"},
  };
  const auto it = byExtension.find(lowerExtension(path));
  return it != byExtension.end() ? it->second : "application/octet-stream";
}

// libxml2's text writer into a file, every call checked.
class Writer {
 public:
  explicit Writer(const fs::path& file) : file_(file), w_(xmlNewTextWriterFilename(file.c_str(), 0)) {
    check(w_ != nullptr);
    check(xmlTextWriterSetIndent(w_, 1) >= 0 && xmlTextWriterSetIndentString(w_, BAD_CAST "  ") >= 0);
    check(xmlTextWriterStartDocument(w_, "1.0", "UTF-8", nullptr) >= 0);
  }
  ~Writer() {
    if (w_) xmlFreeTextWriter(w_);
  }
  Writer& start(const char* name) {
    check(xmlTextWriterStartElement(w_, BAD_CAST name) >= 0);
    return *this;
  }
  Writer& attr(const char* name, const std::string& value) {
    check(xmlTextWriterWriteAttribute(w_, BAD_CAST name, BAD_CAST value.c_str()) >= 0);
    return *this;
  }
  Writer& text(const std::string& value) {
    check(xmlTextWriterWriteString(w_, BAD_CAST value.c_str()) >= 0);
    return *this;
  }
  Writer& end() {
    check(xmlTextWriterEndElement(w_) >= 0);
    return *this;
  }
  void finish() {
    check(xmlTextWriterEndDocument(w_) >= 0);
    xmlFreeTextWriter(w_);
    w_ = nullptr;
  }

 private:
  void check(bool ok) {
    if (!ok) throw Error(ErrorKind::Internal, file_.string(), kStep, "cannot be written (disk full or no permission?)");
  }
  fs::path file_;
  xmlTextWriterPtr w_;
};

void rootAttributes(Writer& w, const std::string& objid, const std::string& label) {
  w.attr("xmlns:mets", "http://www.loc.gov/METS/")
      .attr("xmlns:xlink", "http://www.w3.org/1999/xlink")
      .attr("xmlns:csip", "https://DILCIS.eu/XML/METS/CSIPExtensionMETS")
      .attr("xmlns:sip", "https://DILCIS.eu/XML/METS/SIPExtensionMETS")
      .attr("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance")
      .attr("OBJID", objid);
  if (!label.empty()) w.attr("LABEL", label);
  w.attr("TYPE", kContentCategory)
      .attr("csip:CONTENTINFORMATIONTYPE", "OTHER")
      .attr("csip:OTHERCONTENTINFORMATIONTYPE", kOtherContentInformationType)
      .attr("PROFILE", kProfile);
}

// The header both METS share: when, a SIP, made by Surrogate (CSIP10-16); the package's also
// names who submits it (SIP15-18).
void header(Writer& w, const std::string& created, const std::pair<std::string, std::string>* submitter) {
  w.start("mets:metsHdr").attr("CREATEDATE", created).attr("RECORDSTATUS", "NEW").attr("csip:OAISPACKAGETYPE", "SIP");
  w.start("mets:agent").attr("ROLE", "CREATOR").attr("TYPE", "OTHER").attr("OTHERTYPE", "SOFTWARE");
  w.start("mets:name").text("Surrogate").end();
  w.start("mets:note").attr("csip:NOTETYPE", "SOFTWARE VERSION").text(surrogateVersion()).end();
  w.end();
  if (submitter) {
    // ROLE OTHER/SUBMITTER, as SIP 2.2's own example names a submitter: CSIP12-16 (and the
    // E-ARK validator's rules) hold every agent of ROLE CREATOR to be the software.
    w.start("mets:agent").attr("ROLE", "OTHER").attr("OTHERROLE", "SUBMITTER").attr("TYPE", submitter->first);
    w.start("mets:name").text(submitter->second).end();
    w.end();
  }
  w.end();
}

void fileElement(Writer& w, const std::string& id, const SipFile& f, const std::string& href,
                 const std::string& created) {
  w.start("mets:file").attr("ID", id).attr("MIMETYPE", f.mime).attr("SIZE", std::to_string(f.size))
      .attr("CREATED", created).attr("CHECKSUM", f.sha256).attr("CHECKSUMTYPE", "SHA-256");
  w.start("mets:FLocat").attr("LOCTYPE", "URL").attr("xlink:type", "simple").attr("xlink:href", href).end();
  w.end();
}

void mdRef(Writer& w, const SipFile& f, const std::string& otherType, const std::string& created) {
  w.start("mets:mdRef").attr("LOCTYPE", "URL").attr("xlink:type", "simple").attr("xlink:href", f.path)
      .attr("MDTYPE", "OTHER").attr("OTHERMDTYPE", otherType).attr("MIMETYPE", f.mime)
      .attr("SIZE", std::to_string(f.size)).attr("CREATED", created).attr("CHECKSUM", f.sha256)
      .attr("CHECKSUMTYPE", "SHA-256").end();
}

SipFile describe(const fs::path& root, const std::string& path) {
  SipFile f;
  f.path = path;
  const FileDigests d = digestFile(root / path);
  f.size = d.size;
  f.sha256 = d.sha256;
  f.mime = mediaTypeOf(path);
  return f;
}

// Who submits the package (SIP15, one agent): the carrier's Source-Organization, else its
// first creator, else whoever ran its last command.
std::pair<std::string, std::string> submitterOf(const carrier::Carrier& c) {
  for (const auto& [key, value] : c.header.meta)
    if (key == "Source-Organization" && !value.empty()) return {"ORGANIZATION", value};
  if (!c.header.creators.empty()) return {"INDIVIDUAL", c.header.creators.front().name};
  if (!c.header.runs.empty()) return {"INDIVIDUAL", c.header.runs.back().who};
  return {"INDIVIDUAL", "not recorded"};
}

}  // namespace

std::string sipPathOf(const std::string& bagPath) {
  for (const auto& [bag, sip] : places())
    if (startsWith(bagPath, bag)) return sip + bagPath.substr(bag.size());
  return kOtherTags + bagPath;
}

std::optional<std::string> bagPathOf(const std::string& sipPath) {
  if (startsWith(sipPath, kOtherTags)) {
    const std::string bag = sipPath.substr(std::string(kOtherTags).size());
    if (!bag.empty() && sipPathOf(bag) == sipPath) return bag;
    return std::nullopt;
  }
  for (const auto& [bag, sip] : places())
    if (startsWith(sipPath, sip)) {
      const std::string candidate = bag + sipPath.substr(sip.size());
      if (sipPathOf(candidate) == sipPath) return candidate;
    }
  return std::nullopt;
}

EarkResult packEark(const fs::path& capture, const fs::path& given, const PackOptions& options) {
  checkPackageName(given);  // the folder's name is the SIP's OBJID and LABEL
  fs::path dir = given.lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir, ec)) && !(fs::is_directory(fs::symlink_status(dir, ec)) && fs::is_empty(dir, ec)))
    throw Error(ErrorKind::Usage, dir.string(), kStep,
                "already exists; an E-ARK SIP is written into a new or empty folder: remove it or choose another name");
  EarkResult result;
  result.objectId = dir.filename().string();
  const carrier::Carrier recorded = carrier::loadCarrier(capture / capture::kCarrierPath);
  std::vector<std::string> removed = removeStaleParts(dir);

  AtomicFile stage(dir);
  const fs::path root = stage.tempPath();
  fs::create_directory(root);
  PackOptions bagOptions = options;
  bagOptions.replace = false;
  const fs::path bag = root / "bag";
  result.pack = packCapture(capture, bag, bagOptions);
  result.pack.bag.removedLeftovers.insert(result.pack.bag.removedLeftovers.begin(), removed.begin(), removed.end());
  const std::string created = result.pack.packagingTime;

  std::map<std::string, std::string> carrierMedia;  // payload path -> the carrier's media type
  for (const carrier::FileRecord& f : recorded.files)
    if (!f.mediaType.empty()) carrierMedia["data/" + f.path] = f.mediaType;

  // Every file of the bag to its place; its digest from packing where the bag has it.
  std::vector<SipFile> files;
  for (const PayloadDigest& p : result.pack.bag.payload) {
    SipFile f;
    f.path = sipPathOf(p.bagPath);
    f.size = p.size;
    f.sha256 = p.sha256;
    const auto media = carrierMedia.find(p.bagPath);
    f.mime = media != carrierMedia.end() ? media->second : mediaTypeOf(p.bagPath);
    files.push_back(f);
  }
  for (const std::string& t : result.pack.bag.tagFiles) {
    SipFile f = describe(bag, t);
    f.path = sipPathOf(t);
    files.push_back(f);
  }
  for (const SipFile& f : files) {
    const auto back = bagPathOf(f.path);
    fs::create_directories((root / f.path).parent_path());
    fs::rename(bag / *back, root / f.path, ec);
    if (ec) throw writeError(root / f.path, kStep, ec.value());
  }
  fs::remove_all(bag, ec);  // only the emptied folders are left
  std::sort(files.begin(), files.end(), [](const SipFile& a, const SipFile& b) { return a.path < b.path; });

  // The representation's METS: its data, paths relative to its folder.
  const std::string repPrefix = "representations/rep1/";
  {
    Writer w(root / kRepresentationMets);
    w.start("mets:mets");
    rootAttributes(w, "rep1", "");
    w.attr("xsi:schemaLocation",
           "http://www.loc.gov/METS/ ../../schemas/mets-1.12.1.xsd http://www.w3.org/1999/xlink ../../schemas/xlink.xsd");
    header(w, created, nullptr);
    w.start("mets:fileSec").attr("ID", "filesec");
    w.start("mets:fileGrp").attr("ID", "grp-data").attr("USE", "Data");
    std::size_t n = 0;
    for (const SipFile& f : files)
      if (startsWith(f.path, repPrefix)) fileElement(w, "file-" + std::to_string(++n), f, f.path.substr(repPrefix.size()), created);
    w.end().end();
    w.start("mets:structMap").attr("ID", "structmap").attr("TYPE", "PHYSICAL").attr("LABEL", "CSIP");
    w.start("mets:div").attr("ID", "div-rep1").attr("LABEL", "rep1");
    w.start("mets:div").attr("ID", "div-data").attr("LABEL", "Data");
    w.start("mets:fptr").attr("FILEID", "grp-data").end();
    w.end().end().end();
    w.end();
    w.finish();
  }
  const SipFile repMets = describe(root, kRepresentationMets);

  // The package's METS.
  {
    const auto submitter = submitterOf(recorded);
    Writer w(root / kSipMets);
    w.start("mets:mets");
    rootAttributes(w, result.objectId, recorded.header.title);
    w.attr("xsi:schemaLocation",
           "http://www.loc.gov/METS/ schemas/mets-1.12.1.xsd http://www.w3.org/1999/xlink schemas/xlink.xsd");
    header(w, created, &submitter);
    std::vector<std::string> provenance;
    for (const SipFile& f : files)
      if (f.path == "metadata/descriptive/crm.rdf") {
        w.start("mets:dmdSec").attr("ID", "dmd-crm").attr("CREATED", created).attr("STATUS", "CURRENT");
        mdRef(w, f, "CIDOC-CRM", created);
        w.end();
      }
    w.start("mets:amdSec");
    std::size_t n = 0;
    for (const SipFile& f : files) {
      const bool mets = f.path == "metadata/preservation/mets.xml", bagit = startsWith(f.path, kOtherTags);
      if (!mets && !bagit) continue;
      const std::string id = mets ? "digiprov-mets-premis" : "digiprov-bagit-" + std::to_string(++n);
      w.start("mets:digiprovMD").attr("ID", id).attr("CREATED", created).attr("STATUS", "CURRENT");
      mdRef(w, f, mets ? "METS+PREMIS" : "BagIt", created);
      w.end();
      provenance.push_back(id);
    }
    w.end();
    w.start("mets:fileSec").attr("ID", "filesec");
    n = 0;
    for (const auto& [use, folder] : {std::pair<std::string, std::string>{"Documentation", "documentation/"},
                                      {"Schemas", "schemas/"}}) {
      w.start("mets:fileGrp").attr("ID", "grp-" + folder.substr(0, folder.size() - 1)).attr("USE", use);
      for (const SipFile& f : files)
        if (startsWith(f.path, folder)) fileElement(w, "file-" + std::to_string(++n), f, f.path, created);
      w.end();
    }
    w.start("mets:fileGrp").attr("ID", "grp-rep1").attr("USE", "Representations/rep1")
        .attr("csip:CONTENTINFORMATIONTYPE", "OTHER")
        .attr("csip:OTHERCONTENTINFORMATIONTYPE", kOtherContentInformationType);
    fileElement(w, "file-rep1-mets", repMets, kRepresentationMets, created);
    w.end().end();

    std::string admid;
    for (const std::string& id : provenance) admid += (admid.empty() ? "" : " ") + id;
    w.start("mets:structMap").attr("ID", "structmap").attr("TYPE", "PHYSICAL").attr("LABEL", "CSIP");
    w.start("mets:div").attr("ID", "div-package").attr("LABEL", result.objectId);
    w.start("mets:div").attr("ID", "div-metadata").attr("LABEL", "Metadata").attr("DMDID", "dmd-crm").attr("ADMID", admid).end();
    w.start("mets:div").attr("ID", "div-documentation").attr("LABEL", "Documentation");
    w.start("mets:fptr").attr("FILEID", "grp-documentation").end().end();
    w.start("mets:div").attr("ID", "div-schemas").attr("LABEL", "Schemas");
    w.start("mets:fptr").attr("FILEID", "grp-schemas").end().end();
    // CSIP 2.2: the content division (CSIP103, CSIP119) and, beside it, the representation's
    // division pointing at its METS, xlink:title naming its file group (CSIP105-112).
    w.start("mets:div").attr("ID", "div-representations").attr("LABEL", "Representations");
    w.start("mets:fptr").attr("FILEID", "grp-rep1").end().end();
    w.start("mets:div").attr("ID", "div-rep1").attr("LABEL", "Representations/rep1");
    w.start("mets:mptr").attr("LOCTYPE", "URL").attr("xlink:type", "simple").attr("xlink:href", kRepresentationMets)
        .attr("xlink:title", "grp-rep1").end();
    w.end().end().end();
    w.finish();
  }
  result.files = files.size() + 2;
  stage.commitWithoutReplacing();
  return result;
}

}  // namespace surrogate::archive
